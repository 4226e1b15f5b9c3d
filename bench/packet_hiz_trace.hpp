#pragma once
// The Hi-Z traversal of bench/native_mirror_trace (kernels/trace.cl trace_hiz + hit_pixel) for 16
// rays at once in AVX-512 lanes: the SIMD half of the native roofline. Plain pointers and no inline
// code here: packet_hiz_trace.cpp is compiled for x86-64-v4 alone, and nothing it defines may be
// merged into code the other files run on CPUs without AVX-512.
#include <cstddef>

namespace ssrcl::bench {

struct HzbLevel {
  int offset, width, height;
};

// What the traversal reads (setup's per-pixel outputs and the min-depth pyramid).
struct HizScene {
  int width, height;
  const float* hzb;
  const HzbLevel* levels;
  int levelCount;            // at most kMaxPacketLevels
  const float* planes;       // per pixel kPlaneFloats, from packPlanes
  int maxIterations;
};
constexpr int kMaxPacketLevels = 32;  // sides up to 2^31 pixels
constexpr int kPlaneFloats = 8;

// What the hit test reads of a pixel in one 32-byte record, so that a lane's step at full
// resolution touches one cache line instead of three (planes 64-byte aligned): normal x, y, z, dot(point, normal), depth
// (>= FLT_MAX: no surface), thickness. Pixels [first, first + count) of setup's arrays (positions
// and normals 4 floats per pixel).
void packPlanes(const float* positions, const float* normals, const float* thickness, size_t first, size_t count,
                float* planes);

// Screen rays (trace.cl ScreenRay + the view-space direction), one array per field.
enum RayField { kS0x, kS0y, kDsx, kDsy, kQ0x, kQ0y, kQ0z, kQ0w, kDqx, kDqy, kDqz, kDqw, kDirx, kDiry, kDirz, kRayFields };
struct RayArrays {
  const float* field[kRayFields];
  size_t count;
};

// Whether this CPU runs tracePackets (AVX-512 F/DQ/BW/VL, and the build compiled it).
bool packetTraceSupported();

// Each ray's hit t, or -1 on a miss, as trace_hiz returns it. Lanes that finish take the next
// ray at once, so the 16 lanes stay busy while rays take 8 to 512 steps.
void tracePackets(const HizScene& scene, const RayArrays& rays, float* tHit);

}  // namespace ssrcl::bench
