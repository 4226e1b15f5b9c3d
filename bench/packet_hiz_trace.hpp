#pragma once
// The fast half of the native roofline: a min-max Hi-Z tracer for packets of rays in SIMD lanes,
// 16 in AVX-512 or 8 in AVX2, whichever the CPU has (docs/BENCHMARKS.md, native roofline). Unlike
// the scalar trace of native_mirror_trace (the OpenCL kernels' arithmetic, their plane hit test),
// it reads only depth: a texel holds the range of inverse depth (1/z, linear along the screen
// segment) its pixels cover, a pixel from 1/z to 1/(z (1 + thickness)); a ray skips any cell
// whose range its own 1/z over the cell misses, and hits the first pixel whose range it meets:
// what a linear march of the depth buffer finds.
// Plain pointers and no inline functions here: the pyramid's functions are compiled for x86-64-v3
// (packet_pyramid.cpp), the traces for x86-64-v4 or v3 alone (packet_hiz_trace_avx512.cpp,
// packet_hiz_trace_avx2.cpp), and nothing they define may be merged into code the other files run
// on other CPUs; the ISA checks and the dispatch (packetTraceIsa, tracePacketRows) are compiled
// for any x86-64 (native_mirror_trace.cpp). The structs' member initialisers make inline
// constructors, which only baseline code runs: the v3 and v4 files take the structs by reference.
#include <cstddef>
#include <cstdint>

namespace ssrcl::bench {

// A level of the scalar trace's min-depth pyramid (native_mirror_trace).
struct HzbLevel {
  int offset, width, height;
};

// Level l of the min-max pyramid: cells of 2^l pixels, texel (x, y) for x in [-1, width] and
// y in [-1, height] at base + (y << shift) + x; the border around each level is zero texels
// (a range no ray meets), so stepping out of the screen needs no bounds check.
struct PyramidLevel {
  int base, shift, width, height;
};
constexpr int kMaxPacketLevels = 16;  // sides up to 2^15 pixels

// What a texel is: Half, 4 bytes (level 0: 1/z as a float, exact as the linear march reads it;
// coarser levels: min and max of 1/z as two halfs rounded outwards); Float, 8 bytes (min and max
// as floats at every level); or NoMemory (the trace makes up texels from its cell coordinates,
// no load: the experiment of what a step costs without memory; hits meaningless).
enum class TexelFormat { Half, Float, NoMemory };

struct MinMaxPyramid {
  int width = 0, height = 0, levelCount = 0;
  PyramidLevel levels[kMaxPacketLevels] = {};
  size_t words = 0;                 // 32-bit words the caller allocates, zeroed (Float: 2 a texel)
  uint32_t* texels = nullptr;
  TexelFormat format = TexelFormat::Half;
  float farRatio = 1.0f;            // 1 / (1 + thicknessRelative): a pixel's range is [1/z farRatio, 1/z]
};
// Fills levels and words for a width x height frame; false where the frame is too large.
bool layoutMinMaxPyramid(int width, int height, TexelFormat format, MinMaxPyramid& pyramid);
// Rows [y0, y1) of level 0 from setup's positions (4 floats a pixel, w = depth, >= FLT_MAX: no
// surface), with the pyramid's farRatio.
void buildMinMaxLevel0(const float* positions, int y0, int y1, MinMaxPyramid& pyramid);
// Rows [y0, y1) of level `level` (>= 1) from level - 1.
void buildMinMaxLevel(int level, int y0, int y1, MinMaxPyramid& pyramid);

// Setup's per-pixel outputs the rays start from, and the camera (perspective only).
struct PacketFrame {
  int width, height;
  const float* positions;         // 4 a pixel: view-space point, depth
  const float* normals;           // 4 a pixel: view-space normal, roughness
  const unsigned char* reflects;  // 1 where the pixel gets rays
  float projection[16];           // column-major
  float nearPlane, farPlane;
  int maxIterations;              // steps before a ray counts as a miss
};

struct PacketCounters {
  long long rays = 0, hits = 0;
  long long laneSteps = 0;    // steps of live rays (each reads one texel)
  long long packetSteps = 0;  // loop iterations of a packet (16 or 8 lanes)
};

// Rows [y0, y1) of the frame: each reflecting pixel's rays (samples == 0: its mirror ray;
// otherwise `samples` GGX VNDF rays with alpha = roughness^2, hashed from pixel, sample and
// seed), generated a packet's width of pixels at a time, traced in packets whose lanes take new
// rays once a few are free, in `isa`'s lanes (one the CPU has: packetTraceIsa() or, on an
// AVX-512 CPU, AVX2 too). hitPoints (mirror rays only; may be null): per pixel 3 floats, the
// screen point (x, y) where the ray enters the hit pixel's range and its 1/z there; -1 where no hit.
enum class PacketIsa { None, Avx2, Avx512 };
void tracePacketRows(PacketIsa isa, const PacketFrame& frame, const MinMaxPyramid& pyramid, int samples, uint32_t seed,
                     int y0, int y1, float* hitPoints, PacketCounters& counters);

// The same, in 16 AVX-512 lanes or 8 AVX2 lanes: the same rays and hits, up to float rounding.
void tracePacketRowsAvx512(const PacketFrame& frame, const MinMaxPyramid& pyramid, int samples, uint32_t seed, int y0,
                           int y1, float* hitPoints, PacketCounters& counters);
void tracePacketRowsAvx2(const PacketFrame& frame, const MinMaxPyramid& pyramid, int samples, uint32_t seed, int y0,
                         int y1, float* hitPoints, PacketCounters& counters);

// nullptr where the lane operations of that ISA's trace (expand, compress, table lookup, climb,
// halfs, masks) give in every lane what they mean, else the name of the first that does not.
const char* packetLaneOpsErrorAvx512();
const char* packetLaneOpsErrorAvx2();

// Which packet trace this CPU runs: AVX-512 where it is x86-64-v4, else AVX2 where it is
// x86-64-v3, else none (or where the build did not compile them: not x86-64).
PacketIsa packetTraceIsa();
const char* packetIsaName(PacketIsa isa);  // "AVX-512", "AVX2", "none"
int packetLanes(PacketIsa isa);            // 16, 8, 0
// Whether this CPU runs the functions above: packetTraceIsa() is not None.
bool packetTraceSupported();

}  // namespace ssrcl::bench
