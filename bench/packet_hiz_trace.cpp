// Compiled with -march=x86-64-v4 (CMakeLists.txt): called only where packetTraceSupported().
// No standard-library templates here (see the header): what this file instantiates would be
// AVX-512 code other files might link to.
#include "packet_hiz_trace.hpp"

// GCC 12 warns of the undefined vectors its own intrinsics start from (GCC bug 105593).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>

#include <cstdlib>

namespace ssrcl::bench {
namespace {

constexpr int kLanes = 16;
// Lanes are refilled once this many are free: refilling costs about a step's instructions, and
// waiting for more leaves lanes idle (docs/BENCHMARKS.md, native roofline).
constexpr int kRefillAt = 4;
// Packets per thread: a step waits on its gather and on the chain of decisions that make its
// index, so the other packets' steps fill the wait (2: 1.2-1.5x over 1; 3: a little more).
constexpr int kPackets = 3;
constexpr int kClimb = 2;  // levels a skip may climb
constexpr float kNoSurface = 3.402823466e38f;  // FLT_MAX, SSRCL_NO_SURFACE
constexpr uint32_t kEmptyHalfTexel = 0x7c00u;  // min +inf, max 0: a range nothing meets, ignored by min and max
constexpr float kPi = 3.14159265358979f;

int imin(int a, int b) { return a < b ? a : b; }
int ceilLog2(int v) {
  int s = 0;
  while ((1 << s) < v) ++s;
  return s;
}

// A generated ray, one array per field (struct of arrays, so lanes load with one expand each):
// t at a cell boundary x is x * ix + nx (ix = 1 / ds.x); 1/z at t is k0 + t * dk; the ray
// starts at t0 in cell (cx, cy) of level 0, its own pixel left behind.
enum Field { kIx, kNx, kIy, kNy, kK0, kDk, kIdk, kT0, kCx, kCy, kPixel, kFields };

struct RayBuffer {
  float* field[kFields];
  float* tHit;
  size_t count = 0;
};

// sin and cos of 2 pi u: of the half angle by Taylor series to 1e-6 on [-pi/2, pi/2], doubled.
void sinCos2Pi(__m512 u, __m512& s, __m512& c) {
  const __m512 x = _mm512_mul_ps(_mm512_sub_ps(u, _mm512_roundscale_ps(u, _MM_FROUND_TO_NEAREST_INT)),
                                 _mm512_set1_ps(kPi));  // half angle in [-pi/2, pi/2]
  const __m512 x2 = _mm512_mul_ps(x, x);
  __m512 sp = _mm512_set1_ps(1.0f / 362880.0f);
  sp = _mm512_fmadd_ps(sp, x2, _mm512_set1_ps(-1.0f / 5040.0f));
  sp = _mm512_fmadd_ps(sp, x2, _mm512_set1_ps(1.0f / 120.0f));
  sp = _mm512_fmadd_ps(sp, x2, _mm512_set1_ps(-1.0f / 6.0f));
  sp = _mm512_fmadd_ps(sp, x2, _mm512_set1_ps(1.0f));
  const __m512 sh = _mm512_mul_ps(sp, x);
  __m512 cp = _mm512_set1_ps(-1.0f / 3628800.0f);
  cp = _mm512_fmadd_ps(cp, x2, _mm512_set1_ps(1.0f / 40320.0f));
  cp = _mm512_fmadd_ps(cp, x2, _mm512_set1_ps(-1.0f / 720.0f));
  cp = _mm512_fmadd_ps(cp, x2, _mm512_set1_ps(1.0f / 24.0f));
  cp = _mm512_fmadd_ps(cp, x2, _mm512_set1_ps(-0.5f));
  const __m512 ch = _mm512_fmadd_ps(cp, x2, _mm512_set1_ps(1.0f));
  s = _mm512_mul_ps(_mm512_set1_ps(2.0f), _mm512_mul_ps(sh, ch));
  c = _mm512_fmsub_ps(ch, ch, _mm512_mul_ps(sh, sh));
}

// A uniform in [0, 1) from 24 bits of Wellons' lowbias32 hash.
__m512 hashUniform(__m512i v) {
  v = _mm512_xor_si512(v, _mm512_srli_epi32(v, 16));
  v = _mm512_mullo_epi32(v, _mm512_set1_epi32(0x7feb352d));
  v = _mm512_xor_si512(v, _mm512_srli_epi32(v, 15));
  v = _mm512_mullo_epi32(v, _mm512_set1_epi32(int(0x846ca68bu)));
  v = _mm512_xor_si512(v, _mm512_srli_epi32(v, 16));
  return _mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_srli_epi32(v, 8)), _mm512_set1_ps(1.0f / 16777216.0f));
}

struct V3 {
  __m512 x, y, z;
};
__m512 dot(const V3& a, const V3& b) {
  return _mm512_fmadd_ps(a.x, b.x, _mm512_fmadd_ps(a.y, b.y, _mm512_mul_ps(a.z, b.z)));
}
V3 scale(const V3& a, __m512 s) { return {_mm512_mul_ps(a.x, s), _mm512_mul_ps(a.y, s), _mm512_mul_ps(a.z, s)}; }
V3 normalize(const V3& a) { return scale(a, _mm512_div_ps(_mm512_set1_ps(1.0f), _mm512_sqrt_ps(dot(a, a)))); }
// 2 (o . n) n - o: o reflected about n.
V3 reflect(const V3& o, const V3& n) {
  const __m512 d2 = _mm512_mul_ps(_mm512_set1_ps(2.0f), dot(o, n));
  return {_mm512_fmsub_ps(d2, n.x, o.x), _mm512_fmsub_ps(d2, n.y, o.y), _mm512_fmsub_ps(d2, n.z, o.z)};
}

// A GGX microfacet normal seen from o (view-space, towards the eye) about normal n, by the
// visible-normal distribution (spherical caps, Dupuy and Benyoub 2023); alpha = roughness^2.
V3 sampleVndf(const V3& o, const V3& n, __m512 alpha, __m512 u1, __m512 u2) {
  // Tangent frame of n (Duff et al. 2017).
  const __m512 one = _mm512_set1_ps(1.0f);
  const __m512 sign = _mm512_or_ps(one, _mm512_and_ps(n.z, _mm512_set1_ps(-0.0f)));
  const __m512 a = _mm512_div_ps(_mm512_set1_ps(-1.0f), _mm512_add_ps(sign, n.z));
  const __m512 b = _mm512_mul_ps(_mm512_mul_ps(n.x, n.y), a);
  const V3 t1{_mm512_fmadd_ps(_mm512_mul_ps(sign, _mm512_mul_ps(n.x, n.x)), a, one), _mm512_mul_ps(sign, b),
              _mm512_sub_ps(_mm512_setzero_ps(), _mm512_mul_ps(sign, n.x))};
  const V3 t2{b, _mm512_fmadd_ps(_mm512_mul_ps(n.y, n.y), a, sign), _mm512_sub_ps(_mm512_setzero_ps(), n.y)};
  const V3 vh = normalize({_mm512_mul_ps(alpha, dot(o, t1)), _mm512_mul_ps(alpha, dot(o, t2)), dot(o, n)});
  __m512 s, c;
  sinCos2Pi(u1, s, c);
  const __m512 z = _mm512_fmsub_ps(_mm512_sub_ps(one, u2), _mm512_add_ps(one, vh.z), vh.z);
  const __m512 sinTheta = _mm512_sqrt_ps(_mm512_max_ps(_mm512_setzero_ps(), _mm512_fnmadd_ps(z, z, one)));
  const V3 h{_mm512_fmadd_ps(sinTheta, c, vh.x), _mm512_fmadd_ps(sinTheta, s, vh.y), _mm512_add_ps(z, vh.z)};
  const V3 m = normalize({_mm512_mul_ps(alpha, h.x), _mm512_mul_ps(alpha, h.y), _mm512_max_ps(h.z, _mm512_setzero_ps())});
  return {_mm512_fmadd_ps(m.x, t1.x, _mm512_fmadd_ps(m.y, t2.x, _mm512_mul_ps(m.z, n.x))),
          _mm512_fmadd_ps(m.x, t1.y, _mm512_fmadd_ps(m.y, t2.y, _mm512_mul_ps(m.z, n.y))),
          _mm512_fmadd_ps(m.x, t1.z, _mm512_fmadd_ps(m.y, t2.z, _mm512_mul_ps(m.z, n.z)))};
}

__m512 projectRow(const float* P, int row, const V3& p) {
  return _mm512_fmadd_ps(_mm512_set1_ps(P[row]), p.x,
                         _mm512_fmadd_ps(_mm512_set1_ps(P[4 + row]), p.y,
                                         _mm512_fmadd_ps(_mm512_set1_ps(P[8 + row]), p.z, _mm512_set1_ps(P[12 + row]))));
}

// The screen ray of lanes `valid` from point p along dir (trace.cl make_screen_ray: to the near
// or far plane, cut at the screen's edge), appended to the buffer.
void appendRays(const PacketFrame& fr, __mmask16 valid, const V3& p, const V3& dir, __m512i x, __m512i y,
                __m512i pixel, RayBuffer& out) {
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f);
  const __m512 pz = p.z, lengthMax = _mm512_mul_ps(_mm512_set1_ps(-1e6f), pz);
  const __mmask16 up = _mm512_cmp_ps_mask(dir.z, zero, _CMP_GT_OQ), down = _mm512_cmp_ps_mask(dir.z, zero, _CMP_LT_OQ);
  const __m512 toNear = _mm512_div_ps(_mm512_sub_ps(_mm512_set1_ps(-fr.nearPlane * 1.001f), pz), dir.z);
  const __m512 toFar = _mm512_div_ps(_mm512_sub_ps(_mm512_set1_ps(-fr.farPlane), pz), dir.z);
  __m512 len = _mm512_mask_mov_ps(_mm512_mask_mov_ps(lengthMax, up, toNear), down, toFar);
  len = _mm512_min_ps(len, lengthMax);
  valid &= _mm512_cmp_ps_mask(len, zero, _CMP_GT_OQ);
  const V3 p1{_mm512_fmadd_ps(dir.x, len, p.x), _mm512_fmadd_ps(dir.y, len, p.y), _mm512_fmadd_ps(dir.z, len, p.z)};
  const float* P = fr.projection;
  const __m512 w0 = projectRow(P, 3, p), w1 = projectRow(P, 3, p1);
  valid &= _mm512_cmp_ps_mask(w0, zero, _CMP_GT_OQ) & _mm512_cmp_ps_mask(w1, zero, _CMP_GT_OQ);
  const __m512 k0 = _mm512_div_ps(one, w0), k1 = _mm512_div_ps(one, w1);
  const __m512 hw = _mm512_set1_ps(0.5f * float(fr.width)), hh = _mm512_set1_ps(0.5f * float(fr.height));
  const __m512 s0x = _mm512_mul_ps(_mm512_fmadd_ps(projectRow(P, 0, p), k0, one), hw);
  const __m512 s0y = _mm512_mul_ps(_mm512_fnmadd_ps(projectRow(P, 1, p), k0, one), hh);
  __m512 dsx = _mm512_sub_ps(_mm512_mul_ps(_mm512_fmadd_ps(projectRow(P, 0, p1), k1, one), hw), s0x);
  __m512 dsy = _mm512_sub_ps(_mm512_mul_ps(_mm512_fnmadd_ps(projectRow(P, 1, p1), k1, one), hh), s0y);
  // Cut at the screen's edge.
  const __mmask16 right = _mm512_cmp_ps_mask(dsx, zero, _CMP_GT_OQ), downY = _mm512_cmp_ps_mask(dsy, zero, _CMP_GT_OQ);
  const __m512 ex = _mm512_maskz_mov_ps(right, _mm512_set1_ps(float(fr.width)));
  const __m512 ey = _mm512_maskz_mov_ps(downY, _mm512_set1_ps(float(fr.height)));
  const __m512 inf = _mm512_set1_ps(__builtin_inff());
  const __m512 tex = _mm512_mask_div_ps(inf, _mm512_cmp_ps_mask(dsx, zero, _CMP_NEQ_OQ), _mm512_sub_ps(ex, s0x), dsx);
  const __m512 tey = _mm512_mask_div_ps(inf, _mm512_cmp_ps_mask(dsy, zero, _CMP_NEQ_OQ), _mm512_sub_ps(ey, s0y), dsy);
  const __m512 tMax = _mm512_min_ps(one, _mm512_min_ps(tex, tey));
  dsx = _mm512_mul_ps(dsx, tMax);
  dsy = _mm512_mul_ps(dsy, tMax);
  const __m512 dk = _mm512_mul_ps(_mm512_sub_ps(k1, k0), tMax);
  const __m512 major = _mm512_max_ps(_mm512_abs_ps(dsx), _mm512_abs_ps(dsy));
  valid &= _mm512_cmp_ps_mask(major, zero, _CMP_GT_OQ) & _mm512_cmp_ps_mask(major, inf, _CMP_LT_OQ) &
           _mm512_cmp_ps_mask(_mm512_abs_ps(s0x), inf, _CMP_LT_OQ) & _mm512_cmp_ps_mask(_mm512_abs_ps(s0y), inf, _CMP_LT_OQ);
  if (!valid) return;
  // A still axis never reaches a boundary: its t there is huge and positive (ix > 0 so the
  // boundary ahead is the upper one, and the pixel centre lies below it).
  const __m512 huge = _mm512_set1_ps(1e30f);
  const __m512 ix = _mm512_mask_div_ps(huge, _mm512_cmp_ps_mask(dsx, zero, _CMP_NEQ_OQ), one, dsx);
  const __m512 iy = _mm512_mask_div_ps(huge, _mm512_cmp_ps_mask(dsy, zero, _CMP_NEQ_OQ), one, dsy);
  const __m512 nx = _mm512_sub_ps(zero, _mm512_mul_ps(s0x, ix)), ny = _mm512_sub_ps(zero, _mm512_mul_ps(s0y, iy));
  // Leave the origin pixel: t where it crosses the pixel's boundary ahead, and the next cell.
  const __mmask16 posX = _mm512_cmp_ps_mask(ix, zero, _CMP_GT_OQ), posY = _mm512_cmp_ps_mask(iy, zero, _CMP_GT_OQ);
  const __m512i oneI = _mm512_set1_epi32(1);
  const __m512 tx = _mm512_fmadd_ps(_mm512_cvtepi32_ps(_mm512_mask_add_epi32(x, posX, x, oneI)), ix, nx);
  const __m512 ty = _mm512_fmadd_ps(_mm512_cvtepi32_ps(_mm512_mask_add_epi32(y, posY, y, oneI)), iy, ny);
  const __mmask16 stepX = _mm512_cmp_ps_mask(tx, ty, _CMP_LE_OQ);
  const __m512i sx = _mm512_mask_mov_epi32(_mm512_set1_epi32(-1), posX, oneI);
  const __m512i sy = _mm512_mask_mov_epi32(_mm512_set1_epi32(-1), posY, oneI);
  const __m512i cx = _mm512_mask_add_epi32(x, stepX, x, sx), cy = _mm512_mask_add_epi32(y, __mmask16(~stepX), y, sy);
  const size_t at = out.count;
  const __m512 fields[kFields] = {ix, nx, iy, ny, k0, dk, _mm512_div_ps(one, dk), _mm512_min_ps(tx, ty),
                                  _mm512_castsi512_ps(cx), _mm512_castsi512_ps(cy), _mm512_castsi512_ps(pixel)};
  for (int f = 0; f < kFields; ++f) _mm512_mask_compressstoreu_ps(out.field[f] + at, valid, fields[f]);
  out.count = at + size_t(__builtin_popcount(valid));
}

// Rays of rows [y0, y1), 16 pixels at a time.
void generateRays(const PacketFrame& fr, int samples, uint32_t seed, int y0, int y1, RayBuffer& out) {
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  for (int y = y0; y < y1; ++y)
    for (int x0 = 0; x0 < fr.width; x0 += kLanes) {
      const __mmask16 inRow = __mmask16((1u << imin(kLanes, fr.width - x0)) - 1);
      const size_t first = size_t(y) * fr.width + x0;
      const __m128i flags = _mm_maskz_loadu_epi8(inRow, fr.reflects + first);
      __mmask16 valid = _mm512_test_epi32_mask(_mm512_cvtepu8_epi32(flags), _mm512_set1_epi32(0xff));
      if (!valid) continue;
      const __m512i pixel = _mm512_add_epi32(_mm512_set1_epi32(int(first)), lane);
      const __m512i at4 = _mm512_slli_epi32(pixel, 2);
      const auto load = [&](const float* base, int c) {
        return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), valid, at4, base + c, 4);
      };
      const V3 p{load(fr.positions, 0), load(fr.positions, 1), load(fr.positions, 2)};
      const V3 n{load(fr.normals, 0), load(fr.normals, 1), load(fr.normals, 2)};
      // Towards the eye (at the view-space origin: perspective).
      const V3 o = normalize({_mm512_sub_ps(_mm512_setzero_ps(), p.x), _mm512_sub_ps(_mm512_setzero_ps(), p.y),
                              _mm512_sub_ps(_mm512_setzero_ps(), p.z)});
      valid &= _mm512_cmp_ps_mask(dot(o, n), _mm512_setzero_ps(), _CMP_GT_OQ);
      const __m512i xs = _mm512_add_epi32(_mm512_set1_epi32(x0), lane), ys = _mm512_set1_epi32(y);
      if (samples == 0) {
        appendRays(fr, valid, p, reflect(o, n), xs, ys, pixel, out);
        continue;
      }
      const __m512 r = load(fr.normals, 3);
      const __m512 alpha = _mm512_max_ps(_mm512_mul_ps(r, r), _mm512_set1_ps(1e-4f));
      for (int s = 0; s < samples; ++s) {
        const __m512i key = _mm512_add_epi32(_mm512_mullo_epi32(pixel, _mm512_set1_epi32(samples)), _mm512_set1_epi32(s));
        const __m512i k2 = _mm512_slli_epi32(key, 1);
        const __m512i seedV = _mm512_set1_epi32(int(seed * 0x9e3779b9u));
        const __m512 u1 = hashUniform(_mm512_xor_si512(k2, seedV));
        const __m512 u2 = hashUniform(_mm512_xor_si512(_mm512_add_epi32(k2, _mm512_set1_epi32(1)), seedV));
        const V3 dir = reflect(o, sampleVndf(o, n, alpha, u1, u2));
        // Directions below the surface get no ray (they would start inside it).
        appendRays(fr, valid & _mm512_cmp_ps_mask(dot(dir, n), _mm512_setzero_ps(), _CMP_GT_OQ), p, dir, xs, ys,
                   pixel, out);
      }
    }
}

// A cell's range of 1/z, [lo, hi], for the lanes of `m`: the gather of the format's texels.
// Half: level 0 holds 1/z itself (exact, as the linear march reads it; the range is
// [1/z * farRatio, 1/z]), the coarser levels two halfs.
template <TexelFormat F>
void fetchRange(const uint32_t* texels, __m512i index, __mmask16 m, __mmask16 fine, __m512 farRatio, __m512i table,
                __m512& lo, __m512& hi) {
  if constexpr (F == TexelFormat::Float) {
    const __m512i a = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), __mmask8(m), _mm512_castsi512_si256(index),
                                                  texels, 8);
    const __m512i b = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), __mmask8(m >> 8),
                                                  _mm512_extracti64x4_epi64(index, 1), texels, 8);
    const __m512i even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    lo = _mm512_castsi512_ps(_mm512_permutex2var_epi32(a, even, b));
    hi = _mm512_castsi512_ps(_mm512_permutex2var_epi32(a, _mm512_add_epi32(even, _mm512_set1_epi32(1)), b));
  } else {
    const __m512i t = F == TexelFormat::Half ? _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), m, index, texels, 4)
                                             : _mm512_permutexvar_epi32(index, table);
    const __m512 u = _mm512_castsi512_ps(t);
    lo = _mm512_mask_mul_ps(_mm512_cvtph_ps(_mm512_cvtepi32_epi16(t)), fine, u, farRatio);
    hi = _mm512_mask_mov_ps(_mm512_cvtph_ps(_mm512_cvtepi32_epi16(_mm512_srli_epi32(t, 16))), fine, u);
  }
}

// 16 lanes, each a ray where trace_hiz's loop stands: t, its cell (cx, cy) of level `level`.
struct Packet {
  __m512 ix, nx, iy, ny, k0, dk, idk, t, result, dt, perDt;  // dt: the march's sample spacing
  __m512i posX, posY, cx, cy, level, steps, slot;  // posX, posY: 1 where the ray goes to +x, +y
  __mmask16 live = 0, done = 0;                      // done: finished, result not yet written
};

template <TexelFormat F>
void traceBuffer(const MinMaxPyramid& pyr, int maxIterations, const RayBuffer& rays, PacketCounters& counters) {
  const __m512 farRatio = _mm512_set1_ps(pyr.farRatio);
  alignas(64) int baseTable[kLanes] = {}, shiftTable[kLanes] = {};
  for (int l = 0; l < pyr.levelCount; ++l) {
    baseTable[l] = pyr.levels[l].base;
    shiftTable[l] = pyr.levels[l].shift;
  }
  const __m512i bases = _mm512_load_si512(baseTable), shifts = _mm512_load_si512(shiftTable);
  // NoMemory: 16 texels of level 0's middle row, looked up by the low bits of the index.
  const PyramidLevel& l0 = pyr.levels[0];
  const __m512i table = _mm512_loadu_si512(pyr.texels + l0.base + ((l0.height / 2) << l0.shift) + l0.width / 2);
  const __m512i one = _mm512_set1_epi32(1), lastLevel = _mm512_set1_epi32(pyr.levelCount - 1);
  const __m512i climbMax = _mm512_set1_epi32(kClimb);
  const __m512i maxSteps = _mm512_set1_epi32(maxIterations);
  const __m512i lane = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  const __m512 oneF = _mm512_set1_ps(1.0f), halfF = _mm512_set1_ps(0.5f);
  size_t next = 0;
  long long laneSteps = 0, packetSteps = 0, hits = 0;
  // One step of packet k, after its free lanes take new rays; false when it has none left.
  const auto advance = [&](Packet& k) __attribute__((always_inline)) {
    const __mmask16 freeLanes = __mmask16(~k.live);
    const int nFree = __builtin_popcount(freeLanes);
    if (next < rays.count && (nFree >= kRefillAt || !k.live)) {
      _mm512_mask_i32scatter_ps(rays.tHit, k.done, k.slot, k.result, 4);
      k.done = 0;
      const size_t take = rays.count - next < size_t(nFree) ? rays.count - next : size_t(nFree);
      const __mmask16 m = take == size_t(nFree) ? freeLanes : __mmask16(_pdep_u32((1u << take) - 1, freeLanes));
      const auto in = [&](__m512 old, int f) { return _mm512_mask_expandloadu_ps(old, m, rays.field[f] + next); };
      k.ix = in(k.ix, kIx);
      k.nx = in(k.nx, kNx);
      k.iy = in(k.iy, kIy);
      k.ny = in(k.ny, kNy);
      k.k0 = in(k.k0, kK0);
      k.dk = in(k.dk, kDk);
      k.idk = in(k.idk, kIdk);
      k.t = in(k.t, kT0);
      k.cx = _mm512_castps_si512(in(_mm512_castsi512_ps(k.cx), kCx));
      k.cy = _mm512_castps_si512(in(_mm512_castsi512_ps(k.cy), kCy));
      k.slot = _mm512_mask_expand_epi32(k.slot, m, _mm512_add_epi32(lane, _mm512_set1_epi32(int(next))));
      k.result = _mm512_mask_mov_ps(k.result, m, _mm512_set1_ps(-1.0f));
      k.level = _mm512_maskz_mov_epi32(__mmask16(~m), k.level);
      k.steps = _mm512_maskz_mov_epi32(__mmask16(~m), k.steps);
      // Half a pixel along the major axis: 0.5 / max(|ds.x|, |ds.y|) = 0.5 min(|ix|, |iy|).
      k.dt = _mm512_mask_mul_ps(k.dt, m, halfF, _mm512_min_ps(_mm512_abs_ps(k.ix), _mm512_abs_ps(k.iy)));
      k.perDt = _mm512_mask_div_ps(k.perDt, m, oneF, k.dt);
      k.posX = _mm512_mask_mov_epi32(k.posX, m,
                                     _mm512_maskz_mov_epi32(_mm512_cmp_ps_mask(k.ix, _mm512_setzero_ps(), _CMP_GT_OQ), one));
      k.posY = _mm512_mask_mov_epi32(k.posY, m,
                                     _mm512_maskz_mov_epi32(_mm512_cmp_ps_mask(k.iy, _mm512_setzero_ps(), _CMP_GT_OQ), one));
      k.live |= m;
      next += take;
    }
    if (!k.live) return false;
    ++packetSteps;
    laneSteps += __builtin_popcount(k.live);
    const __m512 size = _mm512_castsi512_ps(_mm512_slli_epi32(_mm512_add_epi32(k.level, _mm512_set1_epi32(127)), 23));
    // Where the ray leaves its cell, and its 1/z over the part of the cell it crosses.
    const __m512 tx = _mm512_fmadd_ps(_mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_add_epi32(k.cx, k.posX)), size), k.ix, k.nx);
    const __m512 ty = _mm512_fmadd_ps(_mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_add_epi32(k.cy, k.posY)), size), k.iy, k.ny);
    const __m512 tExit = _mm512_min_ps(tx, ty), tEnd = _mm512_min_ps(tExit, oneF);
    const __m512 u0 = _mm512_fmadd_ps(k.t, k.dk, k.k0), u1 = _mm512_fmadd_ps(tEnd, k.dk, k.k0);
    const __m512 rayLo = _mm512_min_ps(u0, u1), rayHi = _mm512_max_ps(u0, u1);
    const __m512i index = _mm512_add_epi32(
        _mm512_add_epi32(_mm512_permutexvar_epi32(k.level, bases),
                         _mm512_sllv_epi32(k.cy, _mm512_permutexvar_epi32(k.level, shifts))),
        k.cx);
    const __mmask16 fine = _mm512_cmpeq_epi32_mask(k.level, _mm512_setzero_si512());
    __m512 lo, hi;
    fetchRange<F>(pyr.texels, index, k.live, fine, farRatio, table, lo, hi);
    const __mmask16 meets = _mm512_mask_cmp_ps_mask(_mm512_mask_cmp_ps_mask(k.live, rayHi, lo, _CMP_GE_OQ), rayLo, hi,
                                                    _CMP_LE_OQ);
    // Met: t moves on to where the ray's 1/z enters the range (trace.cl's tCross), within the cell.
    __m512 enter = _mm512_mask_mul_ps(k.t, _mm512_cmp_ps_mask(u0, hi, _CMP_GT_OQ), _mm512_sub_ps(hi, k.k0), k.idk);
    enter = _mm512_mask_mul_ps(enter, _mm512_cmp_ps_mask(u0, lo, _CMP_LT_OQ), _mm512_sub_ps(lo, k.k0), k.idk);
    const __m512 tMet = _mm512_min_ps(_mm512_max_ps(enter, k.t), tEnd);
    // A pixel is hit where a sample of the half-pixel march (t = (i + 1/2) dt) lies in its range: the
    // first sample from tMet on, before the ray leaves the range (towards the eye through its
    // near end, away through its far end) and the pixel.
    const __m512 sample = _mm512_mul_ps(
        _mm512_add_ps(_mm512_roundscale_ps(_mm512_fmsub_ps(tMet, k.perDt, halfF), _MM_FROUND_TO_POS_INF), halfF), k.dt);
    const __mmask16 nearer = _mm512_cmp_ps_mask(k.dk, _mm512_setzero_ps(), _CMP_GT_OQ);
    const __mmask16 still = _mm512_cmp_ps_mask(k.dk, _mm512_setzero_ps(), _CMP_EQ_OQ);
    const __m512 leave = _mm512_mask_mov_ps(
        _mm512_mul_ps(_mm512_sub_ps(_mm512_mask_mov_ps(lo, nearer, hi), k.k0), k.idk), still, tEnd);
    const __mmask16 sampled = _mm512_cmp_ps_mask(sample, _mm512_min_ps(leave, tEnd), _CMP_LE_OQ);
    const __mmask16 hit = meets & fine & sampled, descend = meets & ~fine, skip = k.live & ~hit & ~descend;
    // Descending: the child holding the ray at tMet, by the t where it crosses the cell's middle.
    const __m512i cx2 = _mm512_add_epi32(k.cx, k.cx), cy2 = _mm512_add_epi32(k.cy, k.cy);
    const __m512 halfSize = _mm512_mul_ps(size, halfF);
    const __m512 midX = _mm512_fmadd_ps(_mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_add_epi32(cx2, one)), halfSize), k.ix, k.nx);
    const __m512 midY = _mm512_fmadd_ps(_mm512_mul_ps(_mm512_cvtepi32_ps(_mm512_add_epi32(cy2, one)), halfSize), k.iy, k.ny);
    // Past the middle along the ray: the upper child where the ray goes to +x, else the lower.
    const __mmask16 pastX = _mm512_cmp_ps_mask(tMet, midX, _CMP_GE_OQ), pastY = _mm512_cmp_ps_mask(tMet, midY, _CMP_GE_OQ);
    const __m512i childX = _mm512_add_epi32(cx2, _mm512_mask_xor_epi32(k.posX, __mmask16(~pastX), k.posX, one));
    const __m512i childY = _mm512_add_epi32(cy2, _mm512_mask_xor_epi32(k.posY, __mmask16(~pastY), k.posY, one));
    // Skipping: the next cell along the ray, then its parent (one level up, as trace_hiz climbs).
    const __mmask16 stepX = _mm512_cmp_ps_mask(tx, ty, _CMP_LE_OQ);
    const __m512i sx = _mm512_sub_epi32(_mm512_add_epi32(k.posX, k.posX), one);
    const __m512i sy = _mm512_sub_epi32(_mm512_add_epi32(k.posY, k.posY), one);
    __m512i nextX = _mm512_mask_add_epi32(k.cx, stepX, k.cx, sx), nextY = _mm512_mask_add_epi32(k.cy, ~stepX, k.cy, sy);
    // Up as many levels as the next cell has ancestors the current one does not share (the
    // highest bit in which their coordinates differ), at most kClimb: the parent of a sibling is
    // the cell just descended from, whose range the ray met (docs/BENCHMARKS.md, native roofline: one level into
    // another parent 11% fewer steps than always one up, two 6.6% fewer again, no cap more).
    const __m512i differ = _mm512_or_si512(_mm512_xor_si512(nextX, k.cx), _mm512_xor_si512(nextY, k.cy));
    const __m512i up = _mm512_min_epi32(
        _mm512_min_epi32(_mm512_sub_epi32(_mm512_set1_epi32(31), _mm512_lzcnt_epi32(differ)), climbMax),
        _mm512_sub_epi32(lastLevel, k.level));
    nextX = _mm512_srav_epi32(nextX, up);
    nextY = _mm512_srav_epi32(nextY, up);
    k.cx = _mm512_mask_mov_epi32(_mm512_mask_mov_epi32(k.cx, descend, childX), skip, nextX);
    k.cy = _mm512_mask_mov_epi32(_mm512_mask_mov_epi32(k.cy, descend, childY), skip, nextY);
    k.level = _mm512_mask_sub_epi32(k.level, descend, k.level, one);
    k.level = _mm512_mask_add_epi32(k.level, skip, k.level, up);
    k.t = _mm512_mask_mov_ps(_mm512_mask_mov_ps(k.t, descend, tMet), skip, tExit);
    k.result = _mm512_mask_mov_ps(k.result, hit, sample);
    k.steps = _mm512_mask_add_epi32(k.steps, k.live, k.steps, one);
    const __mmask16 left = skip & _mm512_cmp_ps_mask(tExit, oneF, _CMP_GT_OQ);
    const __mmask16 capped = k.live & _mm512_cmpge_epi32_mask(k.steps, maxSteps);
    const __mmask16 finished = hit | left | capped;
    hits += __builtin_popcount(hit);
    k.live &= __mmask16(~finished);
    k.done |= finished;
    return true;
  };
  Packet packets[kPackets] = {};
  for (bool any = true; any;) {
    any = false;
    for (Packet& k : packets) any |= advance(k);
  }
  for (Packet& k : packets) _mm512_mask_i32scatter_ps(rays.tHit, k.done, k.slot, k.result, 4);
  counters.rays += (long long)rays.count;
  counters.hits += hits;
  counters.laneSteps += laneSteps;
  counters.packetSteps += packetSteps;
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

void tracePacketRows(const PacketFrame& frame, const MinMaxPyramid& pyramid, int samples, uint32_t seed, int y0,
                     int y1, float* hitPoints, PacketCounters& counters) {
  const size_t capacity = size_t(y1 - y0) * frame.width * size_t(samples > 0 ? samples : 1) + kLanes;
  float* storage = static_cast<float*>(std::aligned_alloc(64, (kFields + 1) * capacity * sizeof(float)));
  if (!storage) return;
  RayBuffer rays;
  for (int f = 0; f < kFields; ++f) rays.field[f] = storage + f * capacity;
  rays.tHit = storage + kFields * capacity;
  generateRays(frame, samples, seed, y0, y1, rays);
  for (size_t k = 0; k < rays.count; ++k) rays.tHit[k] = -1.0f;
  if (pyramid.format == TexelFormat::Half) traceBuffer<TexelFormat::Half>(pyramid, frame.maxIterations, rays, counters);
  if (pyramid.format == TexelFormat::Float) traceBuffer<TexelFormat::Float>(pyramid, frame.maxIterations, rays, counters);
  if (pyramid.format == TexelFormat::NoMemory)
    traceBuffer<TexelFormat::NoMemory>(pyramid, frame.maxIterations, rays, counters);
  if (hitPoints) {
    for (size_t i = 3 * size_t(y0) * frame.width; i < 3 * size_t(y1) * frame.width; ++i) hitPoints[i] = -1.0f;
    for (size_t k = 0; k < rays.count; ++k) {
      const float t = rays.tHit[k];
      if (!(t >= 0.0f)) continue;
      int pixel;
      __builtin_memcpy(&pixel, rays.field[kPixel] + k, 4);
      // x at t from t = x * ix + nx.
      float* out = hitPoints + 3 * size_t(pixel);
      out[0] = (t - rays.field[kNx][k]) / rays.field[kIx][k];
      out[1] = (t - rays.field[kNy][k]) / rays.field[kIy][k];
      out[2] = rays.field[kK0][k] + t * rays.field[kDk][k];
    }
  }
  std::free(storage);
}

}  // namespace ssrcl::bench
