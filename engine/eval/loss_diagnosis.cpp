// Why a part was lost (horopter eval-tracking --diagnose); see
// horopter/eval/tracking_eval.hpp. Each lost part gets the first cause that holds,
// from the tracker's state back to the pixels, so the counts say which stage
// to fix first.
#include <algorithm>
#include <cmath>

#include "horopter/eval/tracking_eval.hpp"

namespace horopter {

const char* lossCauseName(LossCause cause) {
  switch (cause) {
    case LossCause::NoGodfather:
      return "no-godfather";
    case LossCause::BarelyVisible:
      return "barely-visible";
    case LossCause::RightViewOut:
      return "right-view-out";
    case LossCause::NoDisparity:
      return "no-disparity";
    case LossCause::OutsideMask:
      return "outside-mask";
    case LossCause::FaceNeckCut:
      return "face-neck-cut";
    case LossCause::Merged:
      return "merged";
    case LossCause::NoSkin:
      return "no-skin";
    case LossCause::Removed:
      return "removed";
    case LossCause::Filtered:
      return "filtered";
    case LossCause::NoTrack:
      return "no-track";
    case LossCause::Swapped:
      return "swapped";
    case LossCause::Elsewhere:
      return "elsewhere";
    case LossCause::Count:
      break;
  }
  return "unknown";
}

namespace {

double distance(cv::Point2f a, cv::Point2f b) {
  return std::hypot(double(a.x - b.x), double(a.y - b.y));
}

// The fraction of the disc of radius r around p where `pass(x, y)` holds.
template <typename Pass>
double discFraction(cv::Size size, cv::Point2f p, int r, Pass pass) {
  int in = 0, all = 0;
  for (int y = cvRound(p.y) - r; y <= cvRound(p.y) + r; ++y)
    for (int x = cvRound(p.x) - r; x <= cvRound(p.x) + r; ++x) {
      if ((x - p.x) * (x - p.x) + (y - p.y) * (y - p.y) > float(r * r)) continue;
      ++all;
      if (x >= 0 && y >= 0 && x < size.width && y < size.height && pass(x, y)) ++in;
    }
  return all ? static_cast<double>(in) / all : 0;
}

}  // namespace

void LossDiagnosis::add(const TrialFrame& t, const TrialOptions& o) {
  const synth::PersonTruth& main = t.truth.people.at(0);
  const Frame& f = t.frame;
  const double tol = std::max(20.0, 0.5 * main.faceWidthPx);
  const cv::Point2f truthAt[3] = {main.head2d, main.leftHand2d, main.rightHand2d};
  const cv::Point3f truth3d[3] = {main.head3d, main.leftHand3d, main.rightHand3d};
  const PartState* track[3] = {&f.body.head, &f.body.leftHand, &f.body.rightHand};
  const int r = std::max(2, cvRound(0.25f * main.faceWidthPx));
  for (int part = 0; part < 3; ++part) {
    if (!t.partLost[part]) continue;
    const cv::Point2f at = truthAt[part];
    LossCause cause = LossCause::Elsewhere;
    auto near = [&](cv::Point2f p) { return distance(p, at) <= tol; };
    bool detected = false;
    const HandDetection* detection = nullptr;
    if (f.detections) {
      if (part == 0) {
        for (const FaceDetection& d : f.detections->faces)
          detected = detected || near(d.centre);
      } else {
        for (const HandDetection& d : f.detections->hands)
          if (near(d.centroid) && !detection) detection = &d;
        detected = detection != nullptr;
      }
    }
    if (!f.body.godfather) {
      cause = LossCause::NoGodfather;
    } else if (!detected) {
      const cv::Size size = t.truth.disparity.size();
      const float hz = truth3d[part].z;
      const double focal = t.focalPx, base = t.baselineM;
      const double shown = discFraction(size, at, r, [&](int x, int y) {
        const double d = t.truth.disparity.at<std::int16_t>(y, x) / 16.0;
        return d > 0 && focal > 0 && std::abs(focal * base / d - hz) < 0.08;
      });
      const bool region = f.detections && f.detections->scope == DetectionScope::HoropterRegion;
      const double masked =
          f.mask.empty() ? 0 : discFraction(f.mask.size(), at, r, [&](int x, int y) {
            return f.mask.at<std::uint8_t>(y, x) != 0;
          });
      const double valid =
          f.disparity.empty() ? 0 : discFraction(f.disparity.size(), at, r, [&](int x, int y) {
            return f.disparity.at<std::int16_t>(y, x) > 0;
          });
      bool cut = false, merged = false;
      if (f.detections) {
        for (const FaceDetection& d : f.detections->faces) {
          const int mx = static_cast<int>(o.detector.faceMargin * d.box.width);
          const cv::Rect out(
              d.box.x - mx, d.box.y - mx, d.box.width + 2 * mx,
              d.box.height + mx + static_cast<int>(o.detector.neckFraction * d.box.height) + mx);
          cut = cut || out.contains(cv::Point(cvRound(at.x), cvRound(at.y)));
        }
        for (const HandDetection& d : f.detections->hands)
          merged = merged || d.box.contains(cv::Point(cvRound(at.x), cvRound(at.y)));
      }
      const double skin =
          f.left.type() != CV_8UC3 ? 0 : discFraction(f.left.size(), at, r, [&](int x, int y) {
            return o.detector.skin.isSkinBgr(f.left.at<cv::Vec3b>(y, x));
          });
      if (part != 0 && shown < 1.0 / 3)
        cause = LossCause::BarelyVisible;
      else if (region && masked < 1.0 / 3 && hz > 0 && focal > 0 && at.x < focal * base / hz)
        cause = LossCause::RightViewOut;
      else if (region && masked < 1.0 / 3 && valid < 0.5)
        cause = LossCause::NoDisparity;
      else if (region && masked < 1.0 / 3)
        cause = LossCause::OutsideMask;
      else if (part != 0 && cut)
        cause = LossCause::FaceNeckCut;
      else if (part != 0 && merged)
        cause = LossCause::Merged;
      else if (part != 0 && skin < 0.2)
        cause = LossCause::NoSkin;
      else
        cause = LossCause::Removed;  // for the head: the cascade missed it
    } else if (part != 0 && f.tracking) {
      const double fw = std::max(1.0f, f.tracking->faceWidthPx);
      const TrackerOptions& to = o.tracker;
      const bool refused =
          distance(detection->centroid, f.body.head.image) > to.reachFaceWidths * fw ||
          detection->areaPx > to.maxHandAreaFaces * fw * fw ||
          detection->areaPx < to.minHandAreaFaces * fw * fw;
      const cv::Point2f other = truthAt[part == 1 ? 2 : 1];
      if (refused)
        cause = LossCause::Filtered;
      else if (!track[part]->tracked)
        cause = LossCause::NoTrack;
      else if (distance(track[part]->image, other) <= tol)
        cause = LossCause::Swapped;
      else
        cause = LossCause::Elsewhere;
    } else if (!track[part]->tracked) {
      cause = LossCause::NoTrack;
    }
    ++counts[part][static_cast<int>(cause)];
    if (log) {
      // The seed: trials run in parallel (--jobs) interleave their lines.
      // The part's true disparity tells a part too near for the search
      // range from one the right view does not see (x < d).
      const float z = truth3d[part].z;
      std::fprintf(log, "seed %llu frame %lld %s %s: truth (%.0f, %.0f) true-d %.1f track",
                   static_cast<unsigned long long>(o.seed), static_cast<long long>(f.index),
                   part == 0 ? "head" : (part == 1 ? "left" : "right"), lossCauseName(cause), at.x,
                   at.y, z > 0 ? t.focalPx * t.baselineM / z : 0.0);
      if (track[part]->tracked)
        std::fprintf(log, " (%.0f, %.0f)%s", track[part]->image.x, track[part]->image.y,
                     track[part]->observed ? "" : " coasting");
      else
        std::fprintf(log, " none");
      std::fprintf(log, " head (%.0f, %.0f) z %.2f fw %.0f", f.body.head.image.x,
                   f.body.head.image.y, f.body.head.rig.z, main.faceWidthPx);
      if (f.detections)
        for (const FaceDetection& face : f.detections->faces)
          std::fprintf(log, " face-luma %.0f", face.skinLuma);
      if (f.detections)
        for (const FaceDetection& face : f.detections->bodyFaces)
          std::fprintf(log, " body-face (%.0f, %.0f) w%.0f y%.0f d%.1f", face.centre.x,
                       face.centre.y, face.width, face.skinLuma, face.disparityPx);
      std::fprintf(log, " | hands");
      if (f.detections)
        for (const HandDetection& d : f.detections->hands)
          std::fprintf(log, " (%.0f, %.0f a%d r%.0f s%.2f y%.0f d%.1f)", d.centroid.x, d.centroid.y,
                       d.areaPx, d.radiusPx, d.stereoAgreement, d.meanLuma, d.disparityPx);
      std::fprintf(log, " | truth L (%.0f, %.0f) R (%.0f, %.0f)\n", main.leftHand2d.x,
                   main.leftHand2d.y, main.rightHand2d.x, main.rightHand2d.y);
    }
  }
}

}  // namespace horopter
