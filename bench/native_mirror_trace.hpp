#pragma once
// The mirror pass in native C++ (std::thread, and whatever SIMD the compiler gives the loops):
// per-pixel setup as kernels/setup.cl does it (view point, view normal, constant thickness, HZB
// level 0 bounding each pixel's plane), the min-depth pyramid as kernels/hzb.cl, and a Hi-Z
// traversal (the kernel's earlier one) with the hit test of kernels/trace.cl, in float as the
// kernels compute: a second implementation whose hits the OpenCL ones must match. From the same setup, the min-max
// packet trace (bench/packet_hiz_trace, depth alone, AVX-512 or AVX2) is the roofline: what these cores can trace
// (bench/ssrcl_roofline, bench/ssrcl_trace_roofline, docs/BENCHMARKS.md, native roofline).
#include <glm/glm.hpp>
#include <vector>

#include "native_frame_stages.hpp"
#include "packet_hiz_trace.hpp"

#include "ssrcl/camera.hpp"
#include "ssrcl/io.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::bench {

// The settings under which the OpenCL pipeline traces the rays this implementation traces: every
// pixel a mirror (one ray), the constant thickness model (the adaptive one is a stage of its own).
TraceSettings nativeMirrorSettings();

struct NativeStageMs {
  double setup = 0, hzb = 0, trace = 0;
};


// Per-pixel hit distances of two passes (0 where no hit): the pixels either hits, and of those
// the ones where only one hits or the distances differ by more than 1%.
struct HitAgreement {
  long long hitPixels = 0, disagreeing = 0;
};
HitAgreement compareHitDistances(const std::vector<float>& a, const std::vector<float>& b);
// The same for hit points (3 floats a pixel: screen x, y, anything; x < 0: no hit): they differ
// where only one hits or the points lie more than `pixels` apart on either axis.
HitAgreement compareHitPoints(const std::vector<float>& a, const std::vector<float>& b, float pixels);

// What the packet trace (bench/packet_hiz_trace) did in its last run.
struct PacketStats {
  long long rays = 0, hits = 0, laneSteps = 0, packetSteps = 0;
  double pyramidMs = 0;  // the min-max pyramid, before the trace (not in runPackets' time)
  double cpuMs = 0;      // CPU time of the threads' ray generation and trace, all threads together
};

class NativeMirrorTrace {
 public:
  // Every reflecting pixel (surface facing the camera, roughness <= settings.maxRoughness) gets
  // its mirror ray; settings give thicknessRelative (constant model) and the iteration cap.
  NativeMirrorTrace(const GBuffer& gbuffer, const Camera& camera, const TraceSettings& settings);
  ~NativeMirrorTrace();
  NativeMirrorTrace(const NativeMirrorTrace&) = delete;
  NativeMirrorTrace& operator=(const NativeMirrorTrace&) = delete;

  // One timed run of the three stages on `threads` threads.
  NativeStageMs run(int threads);
  // One timed run of the stages before the trace on `threads` threads: setup, the HZB, the
  // adaptive thickness (bench/native_frame_stages; only with settings.thicknessModel Adaptive,
  // else 0 ms), the range pyramid and the colour pyramid.
  FrameStageMs runFrame(int threads);
  // After run(): the mirror rays again by the min-max packet trace (bench/packet_hiz_trace: its
  // own ray generation, hit test on depth alone, thickness settings.thicknessRelative of the
  // depth), on `threads` threads; the milliseconds of ray generation and trace (the pyramid is
  // built first, timed in packetStats()). Only where packetTraceSupported().
  double runPackets(int threads);
  // The same for `samplesPerPixel` GGX VNDF rays of every reflecting pixel (alpha = roughness^2,
  // the roughness setup read); no per-pixel output, the counts in packetStats().
  double runGlossyPackets(int threads, int samplesPerPixel);
  // The texels the packet trace reads (docs/BENCHMARKS.md, native roofline's experiments; Half by default).
  void setPacketTexels(TexelFormat format);
  // The lanes the packet trace runs in: packetTraceIsa() by default; AVX2 on an AVX-512 CPU too.
  void setPacketIsa(PacketIsa isa);
  const PacketStats& packetStats() const;
  // After run(): every mirror ray marched in half-pixel steps over the depth buffer (a sample
  // hits where the ray's depth lies within [depth, depth (1 + thicknessRelative)] of a pixel
  // other than its own): the reference of the packet trace's hits.
  void runLinearMarch(int threads);
  // Per pixel, after run(): the mirror hit's view-space distance, 0 where none (as "distance").
  const std::vector<float>& distance() const;
  // Per pixel 3 floats, after runPackets() / runLinearMarch(): the hit's screen x, y and 1/z; -1 where none.
  const std::vector<float>& packetHitPoints() const;
  const std::vector<float>& linearHitPoints() const;
  // After run() / runFrame(): the HZB (every level), the surface planes (kernels/surface_plane.cl;
  // the adaptive thickness applied after runFrame()); after runFrame(): the range pyramid and the
  // colour pyramid, every level, in the HZB's layout.
  const std::vector<float>& hzb() const;
  const std::vector<glm::vec4>& planes() const;
  const std::vector<glm::vec2>& rangePyramid() const;
  const std::vector<glm::vec4>& colorPyramid() const;
  long long rays() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace ssrcl::bench
