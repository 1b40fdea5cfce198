// The per-pixel ray caster; see rasteriser.hpp.
#include "synthetic/rasteriser.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace horopter::synth {

Ray Camera::ray(double x, double y) const {
  const Vec3 dRig{(x - cx) / f, (y - cy) / f, 1.0};
  Ray r;
  r.o = centre;
  r.d = rigToWorld.apply(dRig);
  r.length = norm(dRig);
  r.dn = (1.0 / r.length) * r.d;
  return r;
}

cv::Rect Camera::screenRect(Vec3 lo, Vec3 hi) const {
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0;
  double x1 = -x0, y1 = -x0;
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner{(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z};
    const Vec3 c = toCamera(corner);
    if (c.z <= 1e-3) return {0, 0, width, height};
    const double u = cx + f * c.x / c.z, v = cy + f * c.y / c.z;
    x0 = std::min(x0, u), x1 = std::max(x1, u);
    y0 = std::min(y0, v), y1 = std::max(y1, v);
  }
  // One pixel of margin; clip to the image (empty when fully outside).
  const int ix0 = static_cast<int>(std::max(0.0, std::floor(x0) - 1));
  const int iy0 = static_cast<int>(std::max(0.0, std::floor(y0) - 1));
  const int ix1 = static_cast<int>(std::min<double>(width, std::ceil(x1) + 2));
  const int iy1 = static_cast<int>(std::min<double>(height, std::ceil(y1) + 2));
  if (ix1 <= ix0 || iy1 <= iy0) return {};
  return {ix0, iy0, ix1 - ix0, iy1 - iy0};
}

void Layer::reset(int width, int height) {
  colour.create(height, width, CV_8UC3);
  colour.setTo(cv::Scalar::all(0));
  depth.create(height, width, CV_64FC1);
  depth.setTo(cv::Scalar::all(std::numeric_limits<double>::infinity()));
}

void render(const Camera& camera, const std::vector<Primitive>& primitives, Layer& layer) {
  std::vector<cv::Rect> rects;
  rects.reserve(primitives.size());
  for (const Primitive& p : primitives) {
    Vec3 lo, hi;
    p.bounds(lo, hi);
    rects.push_back(p.shape == Primitive::Shape::Room ? cv::Rect(0, 0, camera.width, camera.height)
                                                      : camera.screenRect(lo, hi));
  }
  const double pixelMetres = 1.0 / camera.f;
  // A surface is replaced only by a strictly nearer one; each row belongs to
  // one thread, so the split does not change the result.
  cv::parallel_for_(cv::Range(0, camera.height), [&](const cv::Range& rows) {
    for (std::size_t i = 0; i < primitives.size(); ++i) {
      const cv::Rect& r = rects[i];
      const int y0 = std::max(rows.start, r.y), y1 = std::min(rows.end, r.y + r.height);
      for (int y = y0; y < y1; ++y) {
        auto* colour = layer.colour.ptr<cv::Vec3b>(y);
        auto* depth = layer.depth.ptr<double>(y);
        for (int x = r.x; x < r.x + r.width; ++x) {
          const Ray ray = camera.ray(x, y);
          Hit hit;
          if (!intersect(primitives[i], ray, depth[x], hit)) continue;
          const cv::Vec3f c = shade(primitives[i], ray, hit, pixelMetres);
          depth[x] = hit.t;
          colour[x] = cv::Vec3b(cv::saturate_cast<uchar>(c[0]), cv::saturate_cast<uchar>(c[1]),
                                cv::saturate_cast<uchar>(c[2]));
        }
      }
    }
  });
}

}  // namespace horopter::synth
