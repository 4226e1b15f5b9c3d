// Compiled with -march=x86-64-v4 (CMakeLists.txt): called only where packetTraceSupported().
// The arithmetic is trace.cl's, operation for operation, so the hits match the scalar loop's.
#include "packet_hiz_trace.hpp"

#include <immintrin.h>

namespace ssrcl::bench {
namespace {

typedef float vf __attribute__((vector_size(64)));
typedef int vi __attribute__((vector_size(64)));
constexpr int kLanes = 16;
constexpr float kNoSurface = 3.402823466e38f;  // FLT_MAX, SSRCL_NO_SURFACE
const float kInf = __builtin_inff();

__mmask16 maskOf(vi m) { return _mm512_movepi32_mask((__m512i)m); }
vi fromMask(__mmask16 m) { return (vi)_mm512_movm_epi32(m); }
vf vabs(vf x) { return (vf)((vi)x & 0x7fffffff); }
vf vmin(vf a, vf b) { return b < a ? b : a; }  // std::min(a, b)
vf vmax(vf a, vf b) { return a < b ? b : a; }  // std::max(a, b)
vi imin(vi a, vi b) { return b < a ? b : a; }
vi imax(vi a, vi b) { return a < b ? b : a; }
vf gather(const float* base, vi index, vi mask) {
  return (vf)_mm512_mask_i32gather_ps(_mm512_setzero_ps(), maskOf(mask), (__m512i)index, base, 4);
}

// trace.cl cell_exit, per lane: the parameter where the ray leaves its cell of `size` pixels.
vf cellExit(const vf* ray, vf t, vf nudge, vf size, vi& cellX, vi& cellY) {
  const vf tn = t + nudge;
  const vf cx = _mm512_floor_ps(vf(ray[kS0x] + tn * ray[kDsx]) / size);
  const vf cy = _mm512_floor_ps(vf(ray[kS0y] + tn * ray[kDsy]) / size);
  cellX = __builtin_convertvector(cx, vi);
  cellY = __builtin_convertvector(cy, vi);
  const vf zero = {};
  const vf bx = (cx + (ray[kDsx] > zero ? 1.0f : zero)) * size;
  const vf by = (cy + (ray[kDsy] > zero ? 1.0f : zero)) * size;
  vf tx = (bx - ray[kS0x]) / ray[kDsx];
  vf ty = (by - ray[kS0y]) / ray[kDsy];
  tx = vabs(ray[kDsx]) < 1e-12f ? kInf : tx;
  ty = vabs(ray[kDsy]) < 1e-12f ? kInf : ty;
  return vmin(tx, ty);
}

// dot(q(t).xyz, n) - q(t).w * dot(p, n): trace.cl plane_side, dot(p, n) from packPlanes.
vf planeSide(const vf* ray, vf t, const vf* n, vf pn) {
  const vf qx = ray[kQ0x] + t * ray[kDqx], qy = ray[kQ0y] + t * ray[kDqy], qz = ray[kQ0z] + t * ray[kDqz];
  const vf qw = ray[kQ0w] + t * ray[kDqw];
  return (qx * n[0] + qy * n[1] + qz * n[2]) - qw * pn;
}

}  // namespace

void packPlanes(const float* positions, const float* normals, const float* thickness, size_t first, size_t count,
                float* planes) {
  for (size_t i = first; i < first + count; ++i) {
    const float* p = positions + 4 * i;
    const float* n = normals + 4 * i;
    float* out = planes + kPlaneFloats * i;
    out[0] = n[0];
    out[1] = n[1];
    out[2] = n[2];
    out[3] = p[0] * n[0] + p[1] * n[1] + p[2] * n[2];
    out[4] = p[3];
    out[5] = thickness[i];
    out[6] = out[7] = 0.0f;
  }
}

void tracePackets(const HizScene& sc, const RayArrays& rays, float* tHit) {
  // The level table in two registers, looked up per lane by its mip.
  alignas(64) int table[3][kMaxPacketLevels] = {};
  for (int l = 0; l < sc.levelCount; ++l) {
    table[0][l] = sc.levels[l].offset;
    table[1][l] = sc.levels[l].width;
    table[2][l] = sc.levels[l].height;
  }
  __m512i levelLo[3], levelHi[3];
  for (int k = 0; k < 3; ++k) {
    levelLo[k] = _mm512_load_si512(table[k]);
    levelHi[k] = _mm512_load_si512(table[k] + kLanes);
  }
  const auto level = [&](int k, vi mip) { return (vi)_mm512_permutex2var_epi32(levelLo[k], (__m512i)mip, levelHi[k]); };

  const vi zeroI = {}, lastLevel = zeroI + (sc.levelCount - 1), firstCoarse = imin(zeroI + 1, lastLevel);
  const vi lastX = zeroI + (sc.width - 1), lastY = zeroI + (sc.height - 1);
  const vf zero = {}, one = zero + 1.0f;
  // Each lane's ray and where it stands in trace_hiz's loop.
  vf ray[kRayFields] = {};
  vf nudge = {}, t = {};
  vi deeper = {}, mip = {}, iterations = {}, rayIndex = zeroI - 1;  // -1: lane free
  size_t next = 0;
  for (;;) {
    // Free lanes take the next rays.
    __mmask16 fresh = 0;
    for (__mmask16 free = maskOf(rayIndex < 0); free && next < rays.count; free &= free - 1, ++next) {
      const int lane = __builtin_ctz(free);
      fresh |= __mmask16(1u << lane);
      for (int f = 0; f < kRayFields; ++f) ray[f][lane] = rays.field[f][next];
      rayIndex[lane] = int(next);
    }
    const vi loaded = rayIndex >= 0;
    if (!maskOf(loaded)) break;
    if (fresh) {
      const vi isFresh = fromMask(fresh);
      const vf ax = vabs(ray[kDsx]), ay = vabs(ray[kDsy]);
      nudge = isFresh ? 0.01f / vmax(ax, ay) : nudge;  // a hundredth of a pixel along the major axis
      deeper = isFresh ? vi(ray[kQ0z] * ray[kDqw] - ray[kDqz] * ray[kQ0w] > zero) : deeper;
      vi cx, cy;
      const vf leave = cellExit(ray, zero, nudge, one, cx, cy);  // leave the origin pixel first
      t = isFresh ? leave : t;
      mip = isFresh ? zeroI : mip;
      iterations = isFresh ? zeroI : iterations;
    }
    const vi alive = loaded & (iterations < sc.maxIterations) & (t <= one);
    const vi missed = loaded & ~alive;
    _mm512_mask_i32scatter_ps(tHit, maskOf(missed), (__m512i)rayIndex, (__m512)(zero - 1.0f), 4);

    vi cellX, cellY;
    const vf tExit = cellExit(ray, t, nudge, __builtin_convertvector(vi(zeroI + 1) << mip, vf), cellX, cellY);

    // Full resolution (hit_pixel): the pixel's plane crossed from the front, or within its thickness.
    const vi fine = alive & (mip == 0);
    const vi px = imin(imax(cellX, zeroI), lastX), py = imin(imax(cellY, zeroI), lastY);
    const vi record = (py * sc.width + px) * kPlaneFloats;
    vf n[3];
    for (int c = 0; c < 3; ++c) n[c] = gather(sc.planes + c, record, fine);
    const vf pn = gather(sc.planes + 3, record, fine);
    const vf tIn = t, tOut = vmin(tExit, one);
    const vf gIn = planeSide(ray, tIn, n, pn), gOut = planeSide(ray, tOut, n, pn);
    const vi surface = gather(sc.planes + 4, record, fine) < kNoSurface;
    const vi inFront = ~surface | (gOut > zero);
    const vi facing = surface & (n[0] * ray[kDirx] + n[1] * ray[kDiry] + n[2] * ray[kDirz] < zero);
    const vi crosses = fine & facing & (gIn > zero) & (gOut <= zero);
    const vi behind = fine & facing & (gIn <= zero);
    const vf thickness = gather(sc.planes + 5, record, behind);
    const vi within = behind & (-gIn / vf(ray[kQ0w] + tIn * ray[kDqw]) <= thickness);
    const vi hit = crosses | within;
    const vf tHitLane = crosses ? tIn + (tOut - tIn) * (gIn / (gIn - gOut)) : tIn;
    _mm512_mask_i32scatter_ps(tHit, maskOf(hit), (__m512i)rayIndex, (__m512)tHitLane, 4);

    // Coarser levels: climb while in front of the cell's nearest depth, descend where it may hit.
    const vi coarse = alive & (mip > 0);
    const vi levelWidth = level(1, mip);
    const vi cx = imin(imax(cellX, zeroI), levelWidth - 1), cy = imin(imax(cellY, zeroI), level(2, mip) - 1);
    const vf dMin = gather(sc.hzb, level(0, mip) + cy * levelWidth + cx, coarse);
    const vf depth = -vf(ray[kQ0z] + t * ray[kDqz]) / vf(ray[kQ0w] + t * ray[kDqw]);
    const vi ahead = depth < dMin;
    const vf denom = ray[kDqz] + dMin * ray[kDqw];
    const vf root = -(ray[kQ0z] + dMin * ray[kQ0w]) / denom;
    const vi rootOk = deeper & (dMin < kNoSurface) & (denom != zero) & (vabs(root) <= kNoSurface);
    const vf tCross = rootOk ? root : kInf;
    const vi climb = coarse & ahead & ~(tCross <= tExit);

    t = climb | (fine & ~hit) ? tExit : (coarse & ahead) ? vmax(t, tCross) : t;
    mip = climb ? imin(mip + 1, lastLevel) : (coarse ? mip - 1 : (fine & inFront) ? firstCoarse : mip);
    iterations += alive & 1;
    rayIndex = hit | missed ? zeroI - 1 : rayIndex;
  }
}

}  // namespace ssrcl::bench
