#pragma once
// The native roofline's row loops (bench/native_mirror_trace, bench/native_frame_stages): rows on
// std::threads, ISA clones of the loops, a pyramid level reduced row by row, and the viewing line
// of kernels/common.cl.
#include <algorithm>
#include <atomic>
#include <functional>
#include <glm/glm.hpp>
#include <thread>
#include <vector>

#include "packet_hiz_trace.hpp"  // HzbLevel

// The row loops in clones for the ISA extensions the CPU has (picked at load time), so the
// roofline gets FMA and wide vectors where they exist and the binary still runs everywhere;
// flattened, so what they call is compiled into each clone.
#if defined(__x86_64__) && defined(__GNUC__)
#define SSRCL_NATIVE_CLONES __attribute__((flatten, target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define SSRCL_NATIVE_CLONES
#endif

namespace ssrcl::bench {

// Rows in blocks taken from a shared counter: rays' costs vary a lot between rows.
inline void parallelRows(int rows, int threads, const std::function<void(int)>& row) {
  std::atomic<int> next{0};
  constexpr int kBlock = 4;
  auto worker = [&] {
    for (int y0; (y0 = next.fetch_add(kBlock)) < rows;)
      for (int y = y0; y < std::min(rows, y0 + kBlock); ++y) row(y);
  };
  // No thread for less than a block each: the small pyramid levels would wait on thread starts.
  threads = std::min(threads, (rows + kBlock - 1) / kBlock);
  std::vector<std::thread> pool;
  for (int k = 1; k < threads; ++k) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
}

// Levels 1.. of a pyramid, row(l, y) for each row, on `threads` threads where a level has the
// texels to be worth starting them: on a loaded machine each start waits for a time slice, and
// the twenty small levels' starts cost more than their work.
inline void reduceLevels(const std::vector<HzbLevel>& levels, int threads, const std::function<void(int, int)>& row) {
  for (int l = 1; l < int(levels.size()); ++l) {
    const HzbLevel level = levels[l];
    parallelRows(level.height, level.width * level.height >= (1 << 16) ? threads : 1, [&row, l](int y) { row(l, y); });
  }
}

// OpenCL C's fmin and fmax (a NaN operand is ignored) as a compare and a select, which loops
// vectorise: std::fmin and std::fmax are library calls unless NaNs are assumed away.
inline float clFmin(float a, float b) { return a <= b || b != b ? a : b; }
inline float clFmax(float a, float b) { return a >= b || b != b ? a : b; }

// common.cl predicts, with 1 / d and 0.01 / d given (the same roundings: 2 / d1 is 2 (1 / d1)).
inline bool predicts(float d0, float inv0, float d1, float inv1, float d2, float inv2, float tolInv2) {
  return std::fabs(inv2 - (2.0f * inv1 - inv0)) <= tolInv2 || std::fabs(d2 - (2.0f * d1 - d0)) <= 0.01f * d2;
}

// Row y of pyramid level l (levels as host/pipeline/stage_support.cpp lays them out: each level
// ceil(half) of the last) from the four texels under each of its texels, as kernels/common.cl
// reduce_cell clamps them: combine(a, b, c, d, x1 != x0, y1 != y0), (b, d) the right column,
// (c, d) the lower row, repeated at an odd edge. The texels with both columns in a loop of their
// own (no clamped index: it vectorises), then the odd edge's.
template <class T, class Combine>
inline void reducePyramidRow(const std::vector<HzbLevel>& levels, int l, int y, T* pyramid, Combine combine) {
  const HzbLevel dst = levels[l], src = levels[l - 1];
  const int y0 = 2 * y, y1 = std::min(y0 + 1, src.height - 1), pairs = src.width / 2;
  const T* row0 = pyramid + src.offset + y0 * src.width;
  const T* row1 = pyramid + src.offset + y1 * src.width;
  T* out = pyramid + dst.offset + y * dst.width;
  const bool hasY1 = y1 != y0;
  for (int x = 0; x < pairs; ++x) out[x] = combine(row0[2 * x], row0[2 * x + 1], row1[2 * x], row1[2 * x + 1], true, hasY1);
  if (pairs < dst.width) {
    const int x0 = 2 * pairs;
    out[pairs] = combine(row0[x0], row0[x0], row1[x0], row1[x0], false, hasY1);
  }
}

// common.cl view_line: the viewing line through NDC point `ndc`, a point on it and the step that
// grows planar depth by 1.
inline void viewLine(const glm::mat4& invProj, glm::vec2 ndc, glm::vec3& origin, glm::vec3& step) {
  const glm::vec4 a = invProj * glm::vec4(ndc, 0.0f, 1.0f);
  const glm::vec4 e = invProj[2];
  const glm::vec3 v = glm::vec3(a) * e.w - glm::vec3(e) * a.w;
  step = v / -v.z;
  origin = e.w != 0.0f ? glm::vec3(e) / e.w : glm::vec3(a) / a.w;
}

}  // namespace ssrcl::bench
