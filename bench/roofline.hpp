#pragma once
#include <ostream>
#include <string>
#include <vector>

#include "bench_inputs.hpp"
#include "bench_runner.hpp"
#include "native_mirror_trace.hpp"
#include "ssrcl/device.hpp"

namespace ssrcl::cli {

// The OpenCL mirror pass against its native C++ roofline (bench/native_mirror_trace): the same
// rays (every reflecting pixel's mirror ray, constant thickness, Hi-Z), and the stages before the
// trace (bench/native_frame_stages), timed alternately in one run, and how many pixels' hits agree.
struct RooflineResult {
  std::string input;
  int width = 0, height = 0, threads = 0;
  long long rays = 0;
  // setup, hzb, thickness, range pyramid, colour pyramid (bench/device_frame_stages against
  // bench/native_frame_stages), trace (the pipeline's stage)
  std::vector<std::string> stages;
  std::vector<StageStats> opencl, native;    // per stage, milliseconds
  StageStats depthCopy;                      // clEnqueueCopyBuffer of the depth buffer, same run
  bench::HitAgreement hits;
  // The trace again by the min-max packet trace (bench/packet_hiz_trace, 16 rays per AVX-512
  // instruction or 8 per AVX2), where the CPU has either; its hits against a half-pixel march of the depth buffer.
  bool packets = false;
  StageStats packetTrace;
  bench::HitAgreement packetHits;
};

RooflineResult runRoofline(const Device& device, const BenchInput& input, int repetitions);
void printRoofline(std::ostream& out, const std::vector<RooflineResult>& results);

}  // namespace ssrcl::cli
