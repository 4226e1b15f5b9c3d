#pragma once
// The mirror pass in native C++ (std::thread, and whatever SIMD the compiler gives the loops):
// per-pixel setup as kernels/setup.cl does it (view point, view normal, constant thickness, HZB
// level 0 bounding each pixel's plane), the min-depth pyramid as kernels/hzb.cl, and the Hi-Z
// traversal with the hit test of kernels/trace.cl, in float as the kernels compute. It is the
// roofline `ssrcl bench --roofline` sets the OpenCL stages against, and a second implementation
// whose hits the OpenCL ones must match.
#include <vector>

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
  // After run(): the trace again, 16 rays per instruction (bench/packet_hiz_trace), on `threads`
  // threads; its milliseconds. Only where packetTraceSupported().
  double runPackets(int threads);
  // Per pixel, after run() / runPackets(): the mirror hit's view-space distance, 0 where none (as "distance").
  const std::vector<float>& distance() const;
  const std::vector<float>& packetDistance() const;
  long long rays() const;

 private:
  struct Impl;
  Impl* impl_;
};

}  // namespace ssrcl::bench
