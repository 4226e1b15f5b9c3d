#include "native_frame_stages.hpp"

#include <cfloat>
#include <cmath>

#include "native_rows.hpp"

namespace ssrcl::bench {
namespace {

using glm::vec2;
using glm::vec3;
using glm::vec4;
constexpr float kNoSurface = FLT_MAX;  // SSRCL_NO_SURFACE

float mix(float a, float b, float f) { return a + (b - a) * f; }  // OpenCL C's mix

// thickness.cl predicts and joined, on one line's positions (element k at line[k * step]).
bool predicts(float d0, float d1, float d2) {
  const float tol = 0.01f;
  return std::fabs(1.0f / d2 - (2.0f / d1 - 1.0f / d0)) <= tol / d2 || std::fabs(d2 - (2.0f * d1 - d0)) <= tol * d2;
}

bool joined(const vec4* line, int k, int length, int step) {
  const float da = line[(k - 1) * step].w, db = line[k * step].w;
  if (da >= kNoSurface || db >= kNoSurface) return false;
  if (std::fabs(db - da) <= 0.02f * clFmin(da, db)) return true;
  if (k >= 2 && line[(k - 2) * step].w < kNoSurface && predicts(line[(k - 2) * step].w, da, db)) return true;
  return k + 1 < length && line[(k + 1) * step].w < kNoSurface && predicts(line[(k + 1) * step].w, db, da);
}

struct ThicknessLines {
  int w, h;
  const vec4* positions;
  vec4* planes;
  vec2* rowRuns;
  AdaptiveThickness model;

  // thickness.cl surface_thickness, one work-item's line: row `line` (axis 0) or column `line`.
  SSRCL_NATIVE_CLONES void line(int axis, int line) const {
    const int length = axis == 0 ? w : h, step = axis == 0 ? 1 : w, base = axis == 0 ? line * w : line;
    const vec4* at = positions + base;
    int start = 0;
    for (int k = 1; k <= length; ++k) {
      if (k < length && joined(at, k, length, step)) continue;
      const int prev = (k - 1) * step;
      const float dFirst = at[start * step].w, dLast = at[prev].w;
      bool flat = true;
      for (int j = start + 1; j < k - 1 && flat; ++j) {
        const float f = float(j - start) / float(k - 1 - start), d = at[j * step].w;
        flat = std::fabs(1.0f / d - mix(1.0f / dFirst, 1.0f / dLast, f)) <= 0.01f / d ||
               std::fabs(d - mix(dFirst, dLast, f)) <= 0.01f * d;
      }
      const vec3 first(at[start * step]), last(at[prev]);
      const float run = glm::distance(first, last);
      for (int j = start; j < k; ++j) {
        const int i = base + j * step;
        const vec3 p(positions[i]);
        const float chord = flat ? 0.0f : 2.0f * std::sqrt(glm::distance(first, p) * glm::distance(p, last));
        if (axis == 0) {
          rowRuns[i] = vec2(run, chord);
          continue;
        }
        const float d = positions[i].w;
        const vec2 r = rowRuns[i];
        const float depthChord = clFmin(clFmax(chord, r.y), clFmin(run, r.x));
        if (d < kNoSurface)
          planes[i] *= d / clFmin(clFmax(model.scale * depthChord, model.minRel * d), model.maxRel * d);
      }
      start = k;
    }
  }
};

// back_pyramid.cl slab_far_end.
float slabFarEnd(const glm::mat4& invProj, int w, int h, vec2 corner, vec3 n, float c, int& sign) {
  vec3 origin, step;
  viewLine(invProj, vec2(2.0f * corner.x / float(w) - 1.0f, 1.0f - 2.0f * corner.y / float(h)), origin, step);
  const float along = glm::dot(step, n), from = glm::dot(origin, n);
  sign |= along > 0.0f ? 1 : along < 0.0f ? 2 : 3;
  return clFmax((c - from) / along, (c - 1.0f - from) / along) - origin.z;
}

// back_pyramid.cl back_level0, row y; every pixel computed and the sky's result selected away,
// so that the loop vectorises.
SSRCL_NATIVE_CLONES void rangeLevel0Row(const glm::mat4& invProj, int w, int h, int y, const float* hzb,
                                        const vec4* planes, vec2* range) {
  constexpr float lo = -0.05f, hi = 1.05f;  // SSRCL_BACK_MARGIN
  const float fy = float(y);
  for (int x = 0; x < w; ++x) {
    const int i = y * w + x;
    const vec4 plane = planes[i];
    int sign = 0;
    const vec3 n(plane);
    const float fx = float(x);
    float farEnd = clFmax(clFmax(slabFarEnd(invProj, w, h, vec2(fx + lo, fy + lo), n, plane.w, sign),
                                 slabFarEnd(invProj, w, h, vec2(fx + hi, fy + lo), n, plane.w, sign)),
                          clFmax(slabFarEnd(invProj, w, h, vec2(fx + lo, fy + hi), n, plane.w, sign),
                                 slabFarEnd(invProj, w, h, vec2(fx + hi, fy + hi), n, plane.w, sign)));
    farEnd = (sign == 1 || sign == 2) && std::fabs(farEnd) < INFINITY ? farEnd + 1e-3f * std::fabs(farEnd) : INFINITY;
    range[i] = vec2(hzb[i], plane.w != -INFINITY ? farEnd : -INFINITY);  // SSRCL_NO_PLANE: nothing to hit
  }
}

SSRCL_NATIVE_CLONES void rangeReduceRow(const std::vector<HzbLevel>& levels, int l, int y, vec2* range) {
  reducePyramidRow(levels, l, y, range, [](vec2 a, vec2 b, vec2 c, vec2 d, bool, bool) {
    return vec2(clFmin(clFmin(a.x, b.x), clFmin(c.x, d.x)), clFmax(clFmax(a.y, b.y), clFmax(c.y, d.y)));
  });
}

// color_pyramid.cl color_reduce, row y of level l: the mean of the texels under it that exist,
// level 0's weighted first (color_lookup.cl weighted_texel).
SSRCL_NATIVE_CLONES void colorReduceRow(const std::vector<HzbLevel>& levels, int l, int y, vec4* pyramid) {
  const bool fromLevel0 = l == 1;
  reducePyramidRow(levels, l, y, pyramid, [fromLevel0](vec4 a, vec4 b, vec4 c, vec4 d, bool hasX1, bool hasY1) {
    const auto weighted = [fromLevel0](vec4 t) { return fromLevel0 ? vec4(vec3(t) * t.w, t.w) : t; };
    vec4 sum = weighted(a);
    float n = 1.0f;
    if (hasX1) { sum += weighted(b); n += 1.0f; }
    if (hasY1) { sum += weighted(c); n += 1.0f; }
    if (hasX1 && hasY1) { sum += weighted(d); n += 1.0f; }
    return sum / n;
  });
}

}  // namespace

void adaptiveThickness(int width, int height, const vec4* positions, vec4* planes, vec2* rowRuns,
                       AdaptiveThickness model, int threads) {
  const ThicknessLines lines{width, height, positions, planes, rowRuns, model};
  parallelRows(height, threads, [&lines](int y) { lines.line(0, y); });
  parallelRows(width, threads, [&lines](int x) { lines.line(1, x); });
}

void buildRangePyramid(const std::vector<HzbLevel>& levels, const glm::mat4& invProj, const float* hzb,
                  const vec4* planes, vec2* range, int threads) {
  const int w = levels[0].width, h = levels[0].height;
  parallelRows(h, threads, [&](int y) { rangeLevel0Row(invProj, w, h, y, hzb, planes, range); });
  reduceLevels(levels, threads, [&](int l, int y) { rangeReduceRow(levels, l, y, range); });
}

void reduceColorPyramid(const std::vector<HzbLevel>& levels, vec4* pyramid, int threads) {
  reduceLevels(levels, threads, [&](int l, int y) { colorReduceRow(levels, l, y, pyramid); });
}

}  // namespace ssrcl::bench
