// The min-max pyramid the packet trace reads (packet_hiz_trace.hpp). Compiled with
// -march=x86-64-v3 (CMakeLists.txt): F16C rounds the halfs; called only where
// packetTraceSupported(), on CPUs with AVX2 or AVX-512 (every x86-64-v4 CPU is also v3).
#include <immintrin.h>

#include "packet_hiz_trace.hpp"

namespace ssrcl::bench {
namespace {

constexpr float kNoSurface = 3.402823466e38f;  // FLT_MAX, SSRCL_NO_SURFACE
constexpr uint32_t kEmptyHalfTexel = 0x7c00u;  // min +inf, max 0: a range nothing meets, ignored by min and max

int imin(int a, int b) { return a < b ? a : b; }
int ceilLog2(int v) {
  int s = 0;
  while ((1 << s) < v) ++s;
  return s;
}

}  // namespace

bool layoutMinMaxPyramid(int width, int height, TexelFormat format, MinMaxPyramid& p) {
  p.width = width;
  p.height = height;
  p.format = format;
  size_t offset = 0;
  int l = 0;
  for (int w = width, h = height;; w = (w + 1) / 2, h = (h + 1) / 2, ++l) {
    if (l == kMaxPacketLevels) return false;
    const int shift = ceilLog2(w + 2);
    // Texel (-1, -1) at the level's first word, so base points at (0, 0).
    p.levels[l] = {int(offset) + (1 << shift) + 1, shift, w, h};
    offset += size_t(h + 2) << shift;
    if (offset > (size_t(1) << 30)) return false;  // indices are 32-bit, Float doubles them
    if (w == 1 && h == 1) break;
  }
  p.levelCount = l + 1;
  p.words = offset * (format == TexelFormat::Float ? 2 : 1);
  return true;
}

void buildMinMaxLevel0(const float* positions, int y0, int y1, MinMaxPyramid& p) {
  const PyramidLevel& l = p.levels[0];
  const float farRatio = p.farRatio;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < l.width; ++x) {
      const float d = positions[4 * (size_t(y) * l.width + x) + 3];
      const size_t t = size_t(l.base) + (size_t(y) << l.shift) + x;
      const bool surface = d > 0.0f && d < kNoSurface;
      const float hi = 1.0f / d, lo = hi * farRatio;
      if (p.format == TexelFormat::Float) {
        const float range[2] = {surface ? lo : __builtin_inff(), surface ? hi : 0.0f};
        __builtin_memcpy(p.texels + 2 * t, range, 8);
      } else {
        // 1/z, 0 where no surface (a range [0, 0] nothing meets).
        const float u = surface ? hi : 0.0f;
        __builtin_memcpy(p.texels + t, &u, 4);
      }
    }
}

void buildMinMaxLevel(int level, int y0, int y1, MinMaxPyramid& p) {
  const PyramidLevel& d = p.levels[level];
  const PyramidLevel& s = p.levels[level - 1];
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < d.width; ++x) {
      // Children past the last column or row are that one again (odd sizes): min and max ignore the repeat.
      const int xs[2] = {2 * x, imin(2 * x + 1, s.width - 1)}, ys[2] = {2 * y, imin(2 * y + 1, s.height - 1)};
      const size_t out = size_t(d.base) + (size_t(y) << d.shift) + x;
      if (p.format == TexelFormat::Float) {
        float lo = __builtin_inff(), hi = 0.0f;
        for (int c = 0; c < 4; ++c) {
          float r[2];
          __builtin_memcpy(r, p.texels + 2 * (size_t(s.base) + (size_t(ys[c >> 1]) << s.shift) + xs[c & 1]), 8);
          lo = r[0] < lo ? r[0] : lo;
          hi = r[1] > hi ? r[1] : hi;
        }
        const float range[2] = {lo, hi};
        __builtin_memcpy(p.texels + 2 * out, range, 8);
      } else {
        // Non-negative halfs order as their bits do. Level 1 reads level 0's 1/z, rounded outwards
        // so that the half range holds the float one.
        uint32_t lo = 0xffffu, hi = 0;
        for (int c = 0; c < 4; ++c) {
          uint32_t v = p.texels[size_t(s.base) + (size_t(ys[c >> 1]) << s.shift) + xs[c & 1]];
          if (level == 1) {
            float u;
            __builtin_memcpy(&u, &v, 4);
            v = u > 0.0f ? uint32_t(_cvtss_sh(u * p.farRatio, _MM_FROUND_TO_NEG_INF)) |
                               uint32_t(_cvtss_sh(u, _MM_FROUND_TO_POS_INF)) << 16
                         : kEmptyHalfTexel;
          }
          lo = (v & 0xffffu) < lo ? v & 0xffffu : lo;
          hi = (v >> 16) > hi ? v >> 16 : hi;
        }
        p.texels[out] = lo | hi << 16;
      }
    }
}

}  // namespace ssrcl::bench
