#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <memory>
#include <string>
#include <thread>
#include <utility>

#include "../io/conventions.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/temporal.hpp"

namespace ssrcl {
namespace {

// A frame's pixel geometry in world space (its surface pixels' points and normals from its
// statistics, computed there once per frame).
struct FrameGeometry {
  const TemporalFrame* frame;
  const TemporalFrameStatistics& statistics;
  glm::dvec3 eye;

  FrameGeometry(const TemporalFrame& f, const TemporalFrameStatistics& statistics);

  // Of surface pixels only.
  const glm::dvec3& point(int x, int y) const;
  const glm::dvec3& normal(int x, int y) const;
  // Screen position (pixels) and planar depth of a world point.
  glm::dvec3 screen(const glm::dvec3& world) const {
    return cameraToScreen(frame->camera, glm::dvec3(frame->camera.view * glm::dvec4(world, 1.0)));
  }
  // The planar depth of a world point in this frame and that of the surface the frame shows at its
  // pixel (NaN where it lies off the screen or the frame shows no surface there).
  std::pair<double, double> depthAndShown(const glm::dvec3& world) const { return depthAndShownAt(screen(world)); }
  // The same of its screen position s.
  std::pair<double, double> depthAndShownAt(const glm::dvec3& s) const {
    const Image& d = *frame->depth;
    if (!(s.z > 0.0) || !(s.x >= 0.0 && s.x < d.width) || !(s.y >= 0.0 && s.y < d.height)) return {s.z, NAN};
    const float shown = d.at(int(s.x), int(s.y), 0);
    return {s.z, detail::isSurfaceDepth(shown) ? double(shown) : NAN};
  }
};

// Half the side of the neighbourhood whose radiance a tap is compared by: 5x5, enough pixels for
// a spread that a filtered pass's blotchy noise does not underestimate.
constexpr int kRadianceRadius = 2;

// Rows [0, h) split over threads: every row is computed alone, so the result is the same for any split.
template <typename RowFn>
void forRows(int h, const RowFn& rows) {
  const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(rows, h * t / threads, h * (t + 1) / threads);
  for (std::thread& t : pool) t.join();
}

// Mean and variance of each colour channel of a frame's pass over the surface pixels of each
// pixel's neighbourhood (separable sums: a row pass, then a column pass). The variance is kept as
// sqrt(2 variance): the test's sqrt(2 min(a, b)) is min(sqrt(2a), sqrt(2b)) to the bit (sqrt is
// monotonic and correctly rounded), and so costs no square root a tap.
struct RadianceStats {
  int width = 0;
  std::vector<double> mean, spread;  // 3 a pixel

  explicit RadianceStats(const TemporalFrame& f) : width(f.reflection->width) {
    const int w = width, h = f.reflection->height;
    constexpr int kSums = 7;  // count, 3 sums, 3 sums of squares
    constexpr int kRows = 2 * kRadianceRadius + 1;
    mean.assign(size_t(w) * h * 3, 0.0);
    spread.assign(size_t(w) * h * 3, 0.0);
    forRows(h, [&](int y0, int y1) {
      // The row sums of the rows a pixel's column sums take, in a ring (row r in slot r % kRows):
      // the frame's row sums at once would be 56 bytes a pixel of memory touched once.
      std::vector<double> ring(size_t(kRows) * w * kSums);
      const auto sumRow = [&](int y) {
        double* row = &ring[size_t(y % kRows) * w * kSums];
        for (int x = 0; x < w; ++x) {
          double* r = &row[size_t(x) * kSums];
          std::fill(r, r + kSums, 0.0);
          for (int sx = std::max(0, x - kRadianceRadius); sx <= std::min(w - 1, x + kRadianceRadius); ++sx) {
            if (!detail::isSurfaceDepth(f.depth->at(sx, y, 0))) continue;
            r[0] += 1.0;
            for (int c = 0; c < 3; ++c) {
              const double v = f.reflection->at(sx, y, c);
              r[1 + c] += v;
              r[4 + c] += v * v;
            }
          }
        }
      };
      int summed = std::max(0, y0 - kRadianceRadius);  // the next row to sum
      for (int y = y0; y < y1; ++y) {
        for (; summed <= std::min(h - 1, y + kRadianceRadius); ++summed) sumRow(summed);
        for (int x = 0; x < w; ++x) {
          double sum[kSums] = {};
          for (int sy = std::max(0, y - kRadianceRadius); sy <= std::min(h - 1, y + kRadianceRadius); ++sy)
            for (int k = 0; k < kSums; ++k) sum[k] += ring[(size_t(sy % kRows) * w + x) * kSums + k];
          if (sum[0] <= 0.0) continue;
          for (int c = 0; c < 3; ++c) {
            const double m = sum[1 + c] / sum[0];
            mean[(size_t(y) * w + x) * 3 + c] = m;
            spread[(size_t(y) * w + x) * 3 + c] = std::sqrt(2.0 * std::max(0.0, sum[4 + c] / sum[0] - m * m));
          }
        }
      }
    });
  }

  // Whether two pixels' neighbourhoods (this frame's at (x, y), o's at (ox, oy)) show the same
  // radiance, within what their spread explains.
  bool agrees(int x, int y, const RadianceStats& o, int ox, int oy, const TemporalSettings& s) const {
    const size_t i = (size_t(y) * width + x) * 3, j = (size_t(oy) * o.width + ox) * 3;
    for (int c = 0; c < 3; ++c) {
      const double a = mean[i + c], b = o.mean[j + c];
      const double tolerance = s.radianceSigmas * std::min(spread[i + c], o.spread[j + c]) +
                               s.radianceShare * std::max(std::abs(a), std::abs(b));
      if (!(std::abs(a - b) <= tolerance)) return false;
    }
    return true;
  }
};

// Asks for the cache line of an image's pixel around (x, y) (pixel coordinates), if in the image.
void prefetchPixel(const Image& image, double x, double y) {
  if (!(x >= 0.0 && y >= 0.0 && x < image.width && y < image.height)) return;
  __builtin_prefetch(&image.data[(size_t(y) * image.width + size_t(x)) * image.channels]);
}

void requireImage(const Image* image, int width, int height, int channels, const std::string& what) {
  if (!image || image->width != width || image->height != height || image->channels != channels)
    throw Error(ErrorCode::InvalidArgument, "temporalBlend: frame " + what + " must be " + std::to_string(width) + "x" +
                                                std::to_string(height) + " with " + std::to_string(channels) +
                                                " channel(s)");
}

}  // namespace

// Each surface pixel's world point (from its depth and camera) and unit normal: a blend takes
// each about four times from every window that holds the frame, so they are computed once here
// (the same arithmetic, so the same values as computing them at each tap).
struct SurfaceGeometry {
  std::vector<glm::dvec3> points, normals;  // a pixel; zero where no surface

  SurfaceGeometry(const TemporalFrame& f, const glm::dmat4& inverseProjection, const glm::dmat4& inverseView)
      : points(size_t(f.camera.width) * f.camera.height), normals(points.size()) {
    const int w = f.camera.width;
    forRows(f.camera.height, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y)
        for (int x = 0; x < w; ++x) {
          const float depth = f.depth->at(x, y, 0);
          if (!detail::isSurfaceDepth(depth)) continue;
          const glm::dvec3 c = cameraPointAt(inverseProjection, f.camera, x + 0.5, y + 0.5, depth);
          points[size_t(y) * w + x] = glm::dvec3(inverseView * glm::dvec4(c, 1.0));
          const glm::dvec3 v(f.normal->at(x, y, 0), f.normal->at(x, y, 1), f.normal->at(x, y, 2));
          const double len = glm::length(v);
          normals[size_t(y) * w + x] = len > 0.0 ? v / len : glm::dvec3(0.0);
        }
    });
  }
};

struct TemporalFrameStatistics {
  int width = 0, height = 0;
  glm::dmat4 inverseView;
  RadianceStats radiance;
  SurfaceGeometry surface;
};

namespace {

FrameGeometry::FrameGeometry(const TemporalFrame& f, const TemporalFrameStatistics& s)
    : frame(&f), statistics(s), eye(glm::dvec3(s.inverseView[3])) {}

const glm::dvec3& FrameGeometry::point(int x, int y) const {
  return statistics.surface.points[size_t(y) * statistics.width + x];
}

const glm::dvec3& FrameGeometry::normal(int x, int y) const {
  return statistics.surface.normals[size_t(y) * statistics.width + x];
}

}  // namespace

std::shared_ptr<const TemporalFrameStatistics> temporalFrameStatistics(const TemporalFrame& frame) {
  if (!frame.reflection) throw Error(ErrorCode::InvalidArgument, "temporalFrameStatistics: frame reflection missing");
  const int w = frame.camera.width, h = frame.camera.height;
  requireImage(frame.reflection, w, h, 4, "reflection (of its camera's size)");
  requireImage(frame.depth, w, h, 1, "depth (of its camera's size)");
  requireImage(frame.normal, w, h, 3, "normal (of its camera's size)");
  const glm::dmat4 inverseProjection = glm::inverse(frame.camera.projection);
  const glm::dmat4 inverseView = glm::inverse(frame.camera.view);
  return std::make_shared<const TemporalFrameStatistics>(
      TemporalFrameStatistics{w, h, inverseView, RadianceStats(frame),
                              SurfaceGeometry(frame, inverseProjection, inverseView)});
}

void validateTemporalSettings(const TemporalSettings& s) {
  const auto check = [](bool ok, const char* name) {
    if (!ok) throw Error(ErrorCode::InvalidArgument, std::string("TemporalSettings::") + name + " out of range");
  };
  check(s.planeTolerance > 0.0f && s.planeTolerance < 1.0f, "planeTolerance");
  check(s.maxNormalDegrees > 0.0f && s.maxNormalDegrees <= 180.0f, "maxNormalDegrees");
  check(s.distanceTolerance > 0.0f && s.distanceTolerance < 1.0f, "distanceTolerance");
  check(s.movedTolerance > 0.0f && s.movedTolerance < 1.0f, "movedTolerance");
  check(s.roughnessSpread >= 0.0f && s.roughnessSpread <= 10.0f, "roughnessSpread");
  check(s.radianceSigmas > 0.0f && s.radianceSigmas <= 1000.0f, "radianceSigmas");
  check(s.radianceShare >= 0.0f && s.radianceShare <= 1000.0f, "radianceShare");
  check(s.mirrorRoughness >= 0.0f && s.mirrorRoughness <= 1.0f, "mirrorRoughness");
  check(!s.constantRoughness || (*s.constantRoughness >= 0.0f && *s.constantRoughness <= 1.0f), "constantRoughness");
}

Image temporalBlend(const std::vector<TemporalFrame>& frames, size_t centre, const TemporalSettings& s) {
  validateTemporalSettings(s);
  if (centre >= frames.size()) throw Error(ErrorCode::InvalidArgument, "temporalBlend: centre is not a frame");
  const TemporalFrame& own = frames[centre];
  if (!own.reflection) throw Error(ErrorCode::InvalidArgument, "temporalBlend: frame reflection missing");
  const int w = own.reflection->width, h = own.reflection->height;
  for (const TemporalFrame& f : frames) {
    requireImage(f.reflection, w, h, 4, "reflection");
    requireImage(f.distance, w, h, 1, "distance");
    requireImage(f.depth, w, h, 1, "depth");
    requireImage(f.normal, w, h, 3, "normal");
    if (f.roughness)
      requireImage(f.roughness, w, h, 1, "roughness");
    else if (!s.constantRoughness)
      throw Error(ErrorCode::InvalidArgument, "temporalBlend: frame roughness missing");
    if (f.camera.width != w || f.camera.height != h)
      throw Error(ErrorCode::InvalidArgument, "temporalBlend: a frame's camera is not of its images' size");
  }
  std::vector<std::shared_ptr<const TemporalFrameStatistics>> statistics;
  std::vector<FrameGeometry> geometry;
  for (const TemporalFrame& f : frames) {
    statistics.push_back(f.statistics ? f.statistics : temporalFrameStatistics(f));
    if (statistics.back()->width != w || statistics.back()->height != h)
      throw Error(ErrorCode::InvalidArgument, "temporalBlend: a frame's statistics are not of its images' size");
    geometry.emplace_back(f, *statistics.back());
  }
  const FrameGeometry& g = geometry[centre];
  // Frame j weighs 1 - d / (R + 1), d = |j - centre|, R the window's longer side: a frame that
  // enters or leaves the window then moves the pass by a smaller step than with equal weights
  // (the frame-to-frame change the shots' metric measures), for little more noise a frame.
  const double reach = double(std::max(centre, frames.size() - 1 - centre)) + 1.0;
  std::vector<double> frameWeight(frames.size());
  for (size_t j = 0; j < frames.size(); ++j) frameWeight[j] = 1.0 - std::abs(double(j) - double(centre)) / reach;
  const double cosNormal = std::cos(glm::radians(double(s.maxNormalDegrees)));

  Image out = *own.reflection;
  // Where a pixel's reflected point and hit fall in each neighbour.
  struct Projection {
    glm::dvec3 reflected, hit;
  };
  const auto blendRows = [&](int rowBegin, int rowEnd) {
    std::vector<Projection> projected(frames.size());
    for (int y = rowBegin; y < rowEnd; ++y)
      for (int x = 0; x < w; ++x) {
        const float depth = own.depth->at(x, y, 0);
        const float roughness = own.roughness ? own.roughness->at(x, y, 0) : *s.constantRoughness;
        const double dist = own.distance->at(x, y, 0);
        // A miss keeps its own pass too: what it holds is the environment's lookup for its own
        // normal, or nothing, without noise; a neighbour's miss is another normal's lookup (a
        // rippled or mixed pixel's), which averaging would only blur in.
        if (!detail::isSurfaceDepth(depth) || roughness <= s.mirrorRoughness || !(dist > 0.0)) continue;
        const glm::dvec3 &p = g.point(x, y), &n = g.normal(x, y);
        const glm::dvec3 view = glm::normalize(p - g.eye);
        // The reflected point: the hit's mirror image behind the reflector, along the viewing ray.
        const glm::dvec3 reflected = p + view * dist;
        // The hit itself, along the mirror direction of the pixel's normal (the lobe's centre).
        const glm::dvec3 hit = p + glm::reflect(view, n) * dist;
        const double spread = double(s.roughnessSpread) * roughness;  // of the hit distance
        // Motion shows only where the frame itself shows the hit: a rough lobe's hit (a mean
        // distance along its centre) may lie on no surface, and a hit may lie off the screen;
        // a neighbour that shows a surface behind it then says no more than the frame would.
        const auto [hitDepth, ownShown] = g.depthAndShown(hit);
        const bool hitShown = std::abs(hitDepth - ownShown) <= ownShown * s.movedTolerance + spread * dist;
        // Every neighbour's projections first, and the pixels they fall on asked for: a
        // neighbour's pixels are far apart in memory from the last one's, and asked for together
        // they arrive together, not one at a time behind each neighbour's taps.
        for (size_t j = 0; j < frames.size(); ++j) {
          if (j == centre) continue;
          Projection& at = projected[j];
          at.reflected = geometry[j].screen(reflected);
          if (hitShown) {
            at.hit = geometry[j].screen(hit);
            prefetchPixel(*frames[j].depth, at.hit.x, at.hit.y);
          }
          prefetchPixel(*frames[j].depth, at.reflected.x - 0.5, at.reflected.y - 0.5);
          prefetchPixel(*frames[j].depth, at.reflected.x - 0.5, at.reflected.y + 0.5);
        }
        double sum[4] = {0, 0, 0, 0}, weight = 0;
        for (size_t j = 0; j < frames.size(); ++j) {
          if (j == centre) continue;
          const FrameGeometry& o = geometry[j];
          const glm::dvec3& q = projected[j].reflected;
          if (!(q.z > 0.0) || !std::isfinite(q.x) || !std::isfinite(q.y)) continue;
          if (hitShown) {  // the hit seen from the neighbour in front of what it shows there: moved
            const auto [seen, shown] = o.depthAndShownAt(projected[j].hit);
            if (seen < shown * (1.0 - s.movedTolerance) - spread * dist) continue;
          }
          // Bilinear over the four pixel centres around q, each tap tested on its own.
          const double fx = q.x - 0.5, fy = q.y - 0.5;
          const int x0 = int(std::floor(fx)), y0 = int(std::floor(fy));
          const double tx = fx - x0, ty = fy - y0;
          for (int k = 0; k < 4; ++k) {
            const int sx = x0 + (k & 1), sy = y0 + (k >> 1);
            if (sx < 0 || sy < 0 || sx >= w || sy >= h) continue;
            const double bilinear = ((k & 1) ? tx : 1 - tx) * ((k >> 1) ? ty : 1 - ty);
            if (bilinear <= 0.0 || !detail::isSurfaceDepth(frames[j].depth->at(sx, sy, 0))) continue;
            const glm::dvec3 &ps = o.point(sx, sy), &ns = o.normal(sx, sy);
            if (glm::dot(n, ns) < cosNormal) continue;
            if (std::abs(glm::dot(ps - p, glm::normalize(n + ns))) > s.planeTolerance * depth) continue;
            // Its hit distance against the distance from it to the reflected point (a miss: none).
            const double ds = frames[j].distance->at(sx, sy, 0);
            if (!(ds > 0.0)) continue;
            const double expected = glm::length(reflected - ps);
            // Within the tolerance a tap weighs in full: weights that fell with the mismatch kept
            // more of the frame's own noise (docs/BENCHMARKS.md "Window weights").
            if (!(std::abs(ds - expected) < (s.distanceTolerance + spread) * expected)) continue;
            if (!statistics[centre]->radiance.agrees(x, y, statistics[j]->radiance, sx, sy, s)) continue;
            const double wk = bilinear * frameWeight[j];
            for (int c = 0; c < 4; ++c) sum[c] += wk * frames[j].reflection->at(sx, sy, c);
            weight += wk;
          }
        }
        if (weight <= 0.0) continue;
        for (int c = 0; c < 4; ++c) out.at(x, y, c) = float((own.reflection->at(x, y, c) + sum[c]) / (1.0 + weight));
      }
  };
  forRows(h, blendRows);
  return out;
}

}  // namespace ssrcl
