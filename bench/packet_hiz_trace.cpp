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

// dot(q(t).xyz, n) - q(t).w * dot(p, n): trace.cl plane_side.
vf planeSide(const vf* ray, vf t, const vf* p, const vf* n) {
  const vf qx = ray[kQ0x] + t * ray[kDqx], qy = ray[kQ0y] + t * ray[kDqy], qz = ray[kQ0z] + t * ray[kDqz];
  const vf qw = ray[kQ0w] + t * ray[kDqw];
  return (qx * n[0] + qy * n[1] + qz * n[2]) - qw * (p[0] * n[0] + p[1] * n[1] + p[2] * n[2]);
}

// One packet's rays and where each lane stands in trace_hiz's loop.
struct Packet {
  vf ray[kRayFields] = {};
  vf nudge = {}, t = {};
  vi deeper = {}, mip = {}, iterations = {}, rayIndex = vi{} - 1;  // -1: lane free
};

// What one step of a packet reads, fetched for every packet before any is used, so that the
// packets' texel reads (mostly cache misses) overlap instead of each step waiting on its own.
struct StepReads {
  vi alive, fine, coarse, pixel4;
  vf tExit, p[4], n[3], thickness, dMin;
};
constexpr int kPacketsInFlight = 4;

}  // namespace

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
  Packet packets[kPacketsInFlight];
  StepReads reads[kPacketsInFlight];
  size_t next = 0;
  for (;;) {
    bool anyLoaded = false;
    for (int k = 0; k < kPacketsInFlight; ++k) {
      Packet& pk = packets[k];
      StepReads& rd = reads[k];
      // Free lanes take the next rays.
      __mmask16 fresh = 0;
      for (__mmask16 free = maskOf(pk.rayIndex < 0); free && next < rays.count; free &= free - 1, ++next) {
        const int lane = __builtin_ctz(free);
        fresh |= __mmask16(1u << lane);
        for (int f = 0; f < kRayFields; ++f) pk.ray[f][lane] = rays.field[f][next];
        pk.rayIndex[lane] = int(next);
      }
      const vf* ray = pk.ray;
      if (fresh) {
        const vi isFresh = fromMask(fresh);
        const vf ax = vabs(ray[kDsx]), ay = vabs(ray[kDsy]);
        pk.nudge = isFresh ? 0.01f / vmax(ax, ay) : pk.nudge;  // a hundredth of a pixel along the major axis
        pk.deeper = isFresh ? vi(ray[kQ0z] * ray[kDqw] - ray[kDqz] * ray[kQ0w] > zero) : pk.deeper;
        vi cx, cy;
        const vf leave = cellExit(ray, zero, pk.nudge, one, cx, cy);  // leave the origin pixel first
        pk.t = isFresh ? leave : pk.t;
        pk.mip = isFresh ? zeroI : pk.mip;
        pk.iterations = isFresh ? zeroI : pk.iterations;
      }
      const vi loaded = pk.rayIndex >= 0;
      anyLoaded |= maskOf(loaded) != 0;
      rd.alive = loaded & (pk.iterations < sc.maxIterations) & (pk.t <= one);
      const vi missed = loaded & ~rd.alive;
      _mm512_mask_i32scatter_ps(tHit, maskOf(missed), (__m512i)pk.rayIndex, (__m512)(zero - 1.0f), 4);
      pk.rayIndex = missed ? zeroI - 1 : pk.rayIndex;

      vi cellX, cellY;
      rd.tExit = cellExit(ray, pk.t, pk.nudge, __builtin_convertvector(vi(zeroI + 1) << pk.mip, vf), cellX, cellY);
      rd.fine = rd.alive & (pk.mip == 0);
      const vi px = imin(imax(cellX, zeroI), lastX), py = imin(imax(cellY, zeroI), lastY);
      rd.pixel4 = (py * sc.width + px) * 4;
      for (int c = 0; c < 4; ++c) rd.p[c] = gather(sc.positions + c, rd.pixel4, rd.fine);
      for (int c = 0; c < 3; ++c) rd.n[c] = gather(sc.normals + c, rd.pixel4, rd.fine);
      rd.thickness = gather(sc.thickness, rd.pixel4 >> 2, rd.fine);
      rd.coarse = rd.alive & (pk.mip > 0);
      const vi levelWidth = level(1, pk.mip);
      const vi cx = imin(imax(cellX, zeroI), levelWidth - 1), cy = imin(imax(cellY, zeroI), level(2, pk.mip) - 1);
      rd.dMin = gather(sc.hzb, level(0, pk.mip) + cy * levelWidth + cx, rd.coarse);
    }
    if (!anyLoaded) break;

    for (int k = 0; k < kPacketsInFlight; ++k) {
      Packet& pk = packets[k];
      const StepReads& rd = reads[k];
      const vf* ray = pk.ray;
      // Full resolution (hit_pixel): the pixel's plane crossed from the front, or within its thickness.
      const vf tIn = pk.t, tOut = vmin(rd.tExit, one);
      const vf gIn = planeSide(ray, tIn, rd.p, rd.n), gOut = planeSide(ray, tOut, rd.p, rd.n);
      const vi surface = rd.p[3] < kNoSurface;
      const vi inFront = ~surface | (gOut > zero);
      const vi facing = surface & (rd.n[0] * ray[kDirx] + rd.n[1] * ray[kDiry] + rd.n[2] * ray[kDirz] < zero);
      const vi crosses = rd.fine & facing & (gIn > zero) & (gOut <= zero);
      const vi within = rd.fine & facing & (gIn <= zero) & (-gIn / vf(ray[kQ0w] + tIn * ray[kDqw]) <= rd.thickness);
      const vi hit = crosses | within;
      const vf tHitLane = crosses ? tIn + (tOut - tIn) * (gIn / (gIn - gOut)) : tIn;
      _mm512_mask_i32scatter_ps(tHit, maskOf(hit), (__m512i)pk.rayIndex, (__m512)tHitLane, 4);

      // Coarser levels: climb while in front of the cell's nearest depth, descend where it may hit.
      const vf depth = -vf(ray[kQ0z] + pk.t * ray[kDqz]) / vf(ray[kQ0w] + pk.t * ray[kDqw]);
      const vi ahead = depth < rd.dMin;
      const vf denom = ray[kDqz] + rd.dMin * ray[kDqw];
      const vf root = -(ray[kQ0z] + rd.dMin * ray[kQ0w]) / denom;
      const vi rootOk = pk.deeper & (rd.dMin < kNoSurface) & (denom != zero) & (vabs(root) <= kNoSurface);
      const vf tCross = rootOk ? root : kInf;
      const vi climb = rd.coarse & ahead & ~(tCross <= rd.tExit);

      pk.t = climb | (rd.fine & ~hit) ? rd.tExit : (rd.coarse & ahead) ? vmax(pk.t, tCross) : pk.t;
      pk.mip = climb ? imin(pk.mip + 1, lastLevel)
                     : (rd.coarse ? pk.mip - 1 : (rd.fine & inFront) ? firstCoarse : pk.mip);
      pk.iterations += rd.alive & 1;
      pk.rayIndex = hit ? zeroI - 1 : pk.rayIndex;
    }
  }
}

}  // namespace ssrcl::bench
