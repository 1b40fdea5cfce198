// The per-pixel ray caster; see rasteriser.hpp.
#include "synthetic/rasteriser.hpp"

#include "synthetic/capsule_pairs.hpp"
#include "synthetic/capsule_rows.hpp"
#include "synthetic/intersections.hpp"
#include "synthetic/shading.hpp"

#include <opencv2/core/utility.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace horopter::synth {

Ray Camera::ray(double x, double y) const {
  const Vec3 dRig{(x - cx) / f, (y - cy) / f, 1.0};
  Ray r;
  r.o = centre;
  r.d = rigToWorld.apply(dRig);
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

cv::Rect screenRect(const Camera& camera, const Primitive& p) {
  const cv::Rect image(0, 0, camera.width, camera.height);
  if (p.shape == Primitive::Shape::Room) return image;
  Vec3 lo, hi;
  p.bounds(lo, hi);
  return camera.screenRect(lo, hi) & image;
}

void coverage(const Camera& camera, const Primitive& p, RowIntervals& out) {
  const cv::Rect r = screenRect(camera, p);
  std::optional<detail::CapsuleRows> spans;
  if (p.shape == Primitive::Shape::Capsule) {
    Primitive prepared = p;
    prepare(prepared, camera.centre);
    spans.emplace(prepared, camera.rigToWorld, camera.f, camera.cx, camera.cy, camera.width);
  }
  for (int y = r.y; y < r.y + r.height; ++y) {
    int x0 = r.x, x1 = r.x + r.width;
    if (spans && !spans->span(y, x0, x1)) continue;
    out.add(y, x0, x1);
  }
}

namespace {

constexpr int kRayBatch = 32;

// The ray tests of pixels xb <= x < xe of a row (at most kRayBatch): the
// hits of the pixels where `p` is nearer than depth[x], and their columns;
// returns how many. Each pixel is one long chain of dependent
// operations, so callers test a batch, then shade or record its hits: two
// short loops let the processor overlap neighbouring pixels.
template <typename Test>
int rayTestBatch(const Primitive& p, const Camera& camera, const double* columnX, double rowY,
                 int xb, int xe, const double* depth, Hit* hits, int* xs, Test test) {
  if (p.shape == Primitive::Shape::Capsule)
    return detail::capsuleRowHits(p, camera, columnX, rowY, xb, xe, depth, hits, xs);
  int n = 0;
  Ray ray;
  ray.o = camera.centre;
  for (int x = xb; x < xe; ++x) {
    ray.d = camera.rigToWorld.apply(Vec3{columnX[x], rowY, 1.0});
    // The hits array outlives a primitive: the one field a test may leave
    // as it was (only the Face mapping reads it) starts as in a new Hit.
    hits[n].back = false;
    if (!test(p, ray, depth[x], hits[n])) continue;
    xs[n++] = x;
  }
  return n;
}

}  // namespace

cv::Rect render(const Camera& camera, const std::vector<Primitive>& unprepared, Layer& layer,
                const RowIntervals* only, double stripes) {
  std::vector<Primitive> primitives = unprepared;
  for (Primitive& p : primitives)
    prepare(p, camera.centre);
  std::vector<cv::Rect> rects;
  std::vector<std::optional<detail::CapsuleRows>> capsuleRows;
  rects.reserve(primitives.size());
  capsuleRows.reserve(primitives.size());
  cv::Rect all;
  for (const Primitive& p : primitives) {
    rects.push_back(screenRect(camera, p));
    capsuleRows.emplace_back();
    if (p.shape == Primitive::Shape::Capsule)
      capsuleRows.back().emplace(p, camera.rigToWorld, camera.f, camera.cx, camera.cy,
                                 camera.width);
    if (!rects.back().empty()) all = all.empty() ? rects.back() : (all | rects.back());
  }
  // The texture of each primitive's face materials, looked up once.
  std::vector<std::array<const Texture*, 6>> faceTextures(primitives.size());
  for (std::size_t i = 0; i < primitives.size(); ++i)
    for (int face = 0; face < 6; ++face)
      faceTextures[i][static_cast<std::size_t>(face)] =
          &texture(primitives[i].materials[face].texture);
  const double pixelMetres = 1.0 / camera.f;
  // The rig direction's x of each column, as Camera::ray computes it.
  std::vector<double> columnX(static_cast<std::size_t>(camera.width));
  for (int x = 0; x < camera.width; ++x)
    columnX[static_cast<std::size_t>(x)] = (x - camera.cx) / camera.f;
  if (only) {
    // Redrawing parts of a frame (`only`): each primitive in turn over the rows,
    // shading as it goes (few surfaces there end up hidden). A surface is
    // replaced only by a strictly nearer one; each row belongs to one thread,
    // so the split does not change the result.
    cv::parallel_for_(
        cv::Range(0, camera.height),
        [&](const cv::Range& rows) {
          // One batch's hits and columns (rayTestBatch), constructed once:
          // not per segment.
          Hit hits[kRayBatch];
          int xs[kRayBatch];
          for (std::size_t i = 0; i < primitives.size(); ++i) {
            const Primitive& p = primitives[i];
            // One pixel loop per shape, so that its ray test is inlined.
            auto loop = [&](auto test) {
              const cv::Rect& r = rects[i];
              const std::optional<detail::CapsuleRows>& spans = capsuleRows[i];
              // Pixels x0 <= x < x1 of row y.
              auto segment = [&](int y, int x0, int x1) {
                if (x1 <= x0) return;
                auto* colour = layer.colour.ptr<cv::Vec3b>(y);
                auto* depth = layer.depth.ptr<double>(y);
                const double rowY = (y - camera.cy) / camera.f;
                // In batches: the ray tests of a batch, then the shading of its
                // hits (rayTestBatch). The result is the same as one loop: a
                // primitive touches each pixel once.
                for (int xb = x0; xb < x1; xb += kRayBatch) {
                  const int xe = std::min(x1, xb + kRayBatch);
                  const int n =
                      rayTestBatch(p, camera, columnX.data(), rowY, xb, xe, depth, hits, xs, test);
                  for (int k = 0; k < n; ++k) {
                    depth[xs[k]] = hits[k].t;
                    colour[xs[k]] =
                        shadePixel(p, hits[k], *faceTextures[i][hits[k].face], pixelMetres);
                  }
                }
              };
              const int y0 = std::max(rows.start, r.y), y1 = std::min(rows.end, r.y + r.height);
              for (int y = y0; y < y1; ++y) {
                if (only->row(y).empty()) continue;
                int x0 = r.x, x1 = r.x + r.width;
                if (spans && !spans->span(y, x0, x1)) continue;
                for (const Interval& in : only->row(y))
                  segment(y, std::max(x0, in.x0), std::min(x1, in.x1));
              }
            };
            switch (p.shape) {
              case Primitive::Shape::Box:
                loop([](auto&&... a) {
                  return detail::intersectBox(std::forward<decltype(a)>(a)...);
                });
                break;
              case Primitive::Shape::Room:
                loop([](auto&&... a) {
                  return detail::intersectRoom(std::forward<decltype(a)>(a)...);
                });
                break;
              case Primitive::Shape::Ellipsoid:
                loop([](auto&&... a) {
                  return detail::intersectEllipsoid(std::forward<decltype(a)>(a)...);
                });
                break;
              case Primitive::Shape::Capsule:
                loop([](auto&&... a) {
                  return detail::intersectCapsule(std::forward<decltype(a)>(a)...);
                });
                break;
            }
          }
        },
        stripes);
    return all;
  }
  // A whole image: row by row, every primitive's ray tests in order, a surface replacing
  // another only when strictly nearer (the depth row holds the nearest so
  // far), then one shading per pixel, of the surface that won. That is what
  // drawing the primitives one after another leaves, without shading the
  // surfaces that end up hidden (a third of the shading when the room is
  // drawn). Each row belongs to one thread, so the split does not change the
  // result.
  cv::parallel_for_(
      cv::Range(0, camera.height),
      [&](const cv::Range& rows) {
        std::vector<Hit> rowHits(static_cast<std::size_t>(camera.width));
        std::vector<int> winner(static_cast<std::size_t>(camera.width), -1);
        Hit hits[kRayBatch];  // one batch's (rayTestBatch), constructed once
        int xs[kRayBatch];
        for (int y = rows.start; y < rows.end; ++y) {
          auto* colour = layer.colour.ptr<cv::Vec3b>(y);
          auto* depth = layer.depth.ptr<double>(y);
          const double rowY = (y - camera.cy) / camera.f;
          int lo = camera.width, hi = 0;  // the pixels some primitive won
          for (std::size_t i = 0; i < primitives.size(); ++i) {
            const Primitive& p = primitives[i];
            const cv::Rect& r = rects[i];
            if (y < r.y || y >= r.y + r.height) continue;
            int x0 = r.x, x1 = r.x + r.width;
            if (capsuleRows[i] && !capsuleRows[i]->span(y, x0, x1)) continue;
            // Pixels a <= x < b, in batches: the ray tests, then the record
            // of the hits (rayTestBatch).
            auto testSpan = [&](int a, int b, auto test) {
              for (int xb = a; xb < b; xb += kRayBatch) {
                const int xe = std::min(b, xb + kRayBatch);
                const int n =
                    rayTestBatch(p, camera, columnX.data(), rowY, xb, xe, depth, hits, xs, test);
                for (int k = 0; k < n; ++k) {
                  const int x = xs[k];
                  depth[x] = hits[k].t;
                  rowHits[static_cast<std::size_t>(x)] = hits[k];
                  winner[static_cast<std::size_t>(x)] = static_cast<int>(i);
                }
                if (n > 0) {  // xs increases
                  lo = std::min(lo, xs[0]);
                  hi = std::max(hi, xs[n - 1] + 1);
                }
              }
            };
            // One loop per shape, so that its ray test is inlined.
            auto spans = [&](auto test) { testSpan(x0, x1, test); };
            switch (p.shape) {
              case Primitive::Shape::Box:
                spans([](auto&&... a) {
                  return detail::intersectBox(std::forward<decltype(a)>(a)...);
                });
                break;
              case Primitive::Shape::Room:
                spans([](auto&&... a) {
                  return detail::intersectRoom(std::forward<decltype(a)>(a)...);
                });
                break;
              case Primitive::Shape::Ellipsoid:
                spans([](auto&&... a) {
                  return detail::intersectEllipsoid(std::forward<decltype(a)>(a)...);
                });
                break;
              case Primitive::Shape::Capsule:
                spans([](auto&&... a) {
                  return detail::intersectCapsule(std::forward<decltype(a)>(a)...);
                });
                break;
            }
          }
          for (int x = lo; x < hi; ++x) {
            const int w = winner[static_cast<std::size_t>(x)];
            if (w < 0) continue;
            winner[static_cast<std::size_t>(x)] = -1;
            const std::size_t wi = static_cast<std::size_t>(w);
            const Hit& hit = rowHits[static_cast<std::size_t>(x)];
            colour[x] = shadePixel(primitives[wi], hit, *faceTextures[wi][hit.face], pixelMetres);
          }
        }
      },
      stripes);
  return all;
}

}  // namespace horopter::synth
