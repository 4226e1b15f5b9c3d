#include "native_frame_stages.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <vector>

#include "native_rows.hpp"

namespace ssrcl::bench {
namespace {

using glm::vec2;
using glm::vec3;
using glm::vec4;
constexpr float kNoSurface = FLT_MAX;  // SSRCL_NO_SURFACE

float mix(float a, float b, float f) { return a + (b - a) * f; }  // OpenCL C's mix

// thickness.cl surface_thickness on one line (row or column) copied out contiguous: the depths'
// reciprocals and the neighbour tests (joined) for the whole line first, in loops without early
// exits that vectorise, then the runs.
struct LineScratch {
  std::vector<vec4> points;                 // the line's positions
  std::vector<float> depth, inv, tolInv;    // d, 1 / d, 0.01 / d; depth and inv padded by one each side
  std::vector<unsigned char> joined;        // joined[k]: pixels k - 1 and k on one surface
  std::vector<vec2> rows;                   // columns: the pixels' row runs and chords
  std::vector<float> factor;                // columns: what each pixel's plane is multiplied by
  void resize(int length) {
    points.resize(length);
    rows.resize(length);
    factor.resize(length);
    depth.resize(length + 2);
    inv.resize(length + 2);
    tolInv.resize(length);
    joined.resize(length + 1);
  }
};

struct ThicknessLines {
  int w, h;
  const vec4* positions;
  vec4* planes;
  vec2* rowRuns;
  AdaptiveThickness model;

  // The line's depths with a no-surface pixel either side (thickness.cl's bounds checks), their
  // reciprocals and each pixel's join to the one before it.
  SSRCL_NATIVE_CLONES static void joins(LineScratch& s, int length) {
    float* d = s.depth.data() + 1;
    float* inv = s.inv.data() + 1;
    d[-1] = d[length] = kNoSurface;
    for (int k = 0; k < length; ++k) d[k] = s.points[k].w;
    for (int k = -1; k <= length; ++k) inv[k] = 1.0f / d[k];
    for (int k = 0; k < length; ++k) s.tolInv[k] = 0.01f / d[k];
    for (int k = 1; k < length; ++k) {
      const float da = d[k - 1], db = d[k], dp = d[k - 2], dn = d[k + 1];
      const bool surfaces = da < kNoSurface && db < kNoSurface;
      const bool close = std::fabs(db - da) <= 0.02f * clFmin(da, db);
      const bool back = dp < kNoSurface && predicts(dp, inv[k - 2], da, inv[k - 1], db, inv[k], s.tolInv[k]);
      const bool ahead = dn < kNoSurface && predicts(dn, inv[k + 1], db, inv[k], da, inv[k - 1], s.tolInv[k - 1]);
      s.joined[k] = surfaces & (close | back | ahead);
    }
    s.joined[length] = 0;
  }

  // One line whose points (and for a column, row runs) are in s: a row's runs and chords to
  // `runs`, or a column's plane factors to s.factor.
  SSRCL_NATIVE_CLONES void line(int axis, int length, LineScratch& s, vec2* runs) const {
    joins(s, length);
    const float* d = s.depth.data() + 1;
    const float* inv = s.inv.data() + 1;
    int start = 0;
    for (int k = 1; k <= length; ++k) {
      if (s.joined[k]) continue;
      // The run [start, k): flat (a slab seen from the front) or each pixel's chord.
      const int last = k - 1;
      bool flat = true;
      for (int j = start + 1; j < last && flat; ++j) {
        const float f = float(j - start) / float(last - start);
        flat = std::fabs(inv[j] - mix(inv[start], inv[last], f)) <= s.tolInv[j] ||
               std::fabs(d[j] - mix(d[start], d[last], f)) <= 0.01f * d[j];
      }
      const vec3 first(s.points[start]), end(s.points[last]);
      const float run = glm::distance(first, end);
      for (int j = start; j < k; ++j) {
        const vec3 p(s.points[j]);
        const float chord = flat ? 0.0f : 2.0f * std::sqrt(glm::distance(first, p) * glm::distance(p, end));
        if (axis == 0) {
          runs[j] = vec2(run, chord);
          continue;
        }
        const vec2 r = s.rows[j];
        const float depthChord = clFmin(clFmax(chord, r.y), clFmin(run, r.x));
        s.factor[j] = d[j] < kNoSurface
                          ? d[j] / clFmin(clFmax(model.scale * depthChord, model.minRel * d[j]), model.maxRel * d[j])
                          : 1.0f;
      }
      start = k;
    }
  }

  void row(int y, LineScratch& s) const {
    s.resize(w);
    std::copy(positions + size_t(y) * w, positions + size_t(y + 1) * w, s.points.begin());
    line(0, w, s, rowRuns + size_t(y) * w);
  }

  // Columns x0 .. x0 + kColumns - 1: read and written a row of the block at a time (a column
  // alone would take a cache line a pixel).
  static constexpr int kColumns = 16;
  void columns(int x0, std::vector<LineScratch>& block) const {
    const int n = std::min(kColumns, w - x0);
    for (int c = 0; c < n; ++c) block[c].resize(h);
    for (int y = 0; y < h; ++y)
      for (int c = 0; c < n; ++c) {
        const size_t i = size_t(y) * w + x0 + c;
        block[c].points[y] = positions[i];
        block[c].rows[y] = rowRuns[i];
      }
    for (int c = 0; c < n; ++c) line(1, h, block[c], nullptr);
    for (int y = 0; y < h; ++y)
      for (int c = 0; c < n; ++c) planes[size_t(y) * w + x0 + c] *= block[c].factor[y];
  }
};

// back_pyramid.cl slab_ends.
float slabEnds(const glm::mat4& invProj, int w, int h, vec2 corner, vec3 n, float c, int& sign, float& near) {
  vec3 origin, step;
  viewLine(invProj, vec2(2.0f * corner.x / float(w) - 1.0f, 1.0f - 2.0f * corner.y / float(h)), origin, step);
  const float along = glm::dot(step, n), from = glm::dot(origin, n);
  sign |= along > 0.0f ? 1 : along < 0.0f ? 2 : 3;
  const float a = (c - from) / along, b = (c - 1.0f - from) / along;
  near = clFmin(a, b) - origin.z;
  return clFmax(a, b) - origin.z;
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
    float n0, n1, n2, n3;
    float farEnd = clFmax(clFmax(slabEnds(invProj, w, h, vec2(fx + lo, fy + lo), n, plane.w, sign, n0),
                                 slabEnds(invProj, w, h, vec2(fx + hi, fy + lo), n, plane.w, sign, n1)),
                          clFmax(slabEnds(invProj, w, h, vec2(fx + lo, fy + hi), n, plane.w, sign, n2),
                                 slabEnds(invProj, w, h, vec2(fx + hi, fy + hi), n, plane.w, sign, n3)));
    float nearEnd = clFmin(clFmin(n0, n1), clFmin(n2, n3));
    const bool bounded = (sign == 1 || sign == 2) && std::fabs(farEnd) < INFINITY && std::fabs(nearEnd) < INFINITY;
    farEnd = bounded ? farEnd + 1e-3f * std::fabs(farEnd) : INFINITY;
    nearEnd = clFmin(bounded ? nearEnd - 1e-3f * std::fabs(nearEnd) : -INFINITY, hzb[i]);
    const bool sky = plane.w == -INFINITY;  // SSRCL_NO_PLANE: nothing to hit
    range[i] = vec2(sky ? INFINITY : nearEnd, sky ? -INFINITY : farEnd);
  }
}

// back_pyramid.cl range_reduce, row y of level l: the nearest the HZB's, the farthest of the four.
SSRCL_NATIVE_CLONES void rangeReduceRow(const std::vector<HzbLevel>& levels, int l, int y, const float* hzb,
                                        vec2* range) {
  reducePyramidRow(levels, l, y, range, [](vec2 a, vec2 b, vec2 c, vec2 d, bool, bool) {
    return vec2(0.0f, clFmax(clFmax(a.y, b.y), clFmax(c.y, d.y)));
  });
  const HzbLevel dst = levels[l];
  for (int x = 0, i = dst.offset + y * dst.width; x < dst.width; ++x, ++i) range[i].x = hzb[i];
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
  parallelRows(height, threads, [&lines](int y) {
    thread_local LineScratch scratch;
    lines.row(y, scratch);
  });
  const int blocks = (width + ThicknessLines::kColumns - 1) / ThicknessLines::kColumns;
  parallelRows(blocks, threads, [&lines](int b) {
    thread_local std::vector<LineScratch> block(ThicknessLines::kColumns);
    lines.columns(b * ThicknessLines::kColumns, block);
  });
}

void buildRangePyramid(const std::vector<HzbLevel>& levels, const glm::mat4& invProj, const float* hzb,
                  const vec4* planes, vec2* range, int threads) {
  const int w = levels[0].width, h = levels[0].height;
  parallelRows(h, threads, [&](int y) { rangeLevel0Row(invProj, w, h, y, hzb, planes, range); });
  reduceLevels(levels, threads, [&](int l, int y) { rangeReduceRow(levels, l, y, hzb, range); });
}

void reduceColorPyramid(const std::vector<HzbLevel>& levels, vec4* pyramid, int threads) {
  reduceLevels(levels, threads, [&](int l, int y) { colorReduceRow(levels, l, y, pyramid); });
}

}  // namespace ssrcl::bench
