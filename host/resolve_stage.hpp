#pragma once
// The resolve (kernels/resolve.cl): each reflecting pixel's estimate from its own and its
// neighbours' rays (ratio estimator, Stachowiak), accumulated over the trace's batches, then
// normalised into the reflection and distance passes, on the listed tiles.
#include "trace_stage.hpp"

namespace ssrcl::detail {

class ResolveStage {
 public:
  void configure(Device::Impl& device, const TraceSettings& s);
  void plan(DeviceBuffers& buffers, const FrameShape& frame);
  // `rgba` and `distance` receive the result (the outputs, or the filter's input).
  void bind(const SetupStage& setup, const TraceStage& trace, const cl::Buffer& rgba, const cl::Buffer& distance);
  static ResolveParams params(const FrameShape& frame, const CameraConstants& camera, const TraceSettings& s);
  // Adds the rays of one batch (params.first_sample, params.batch_size) over `tiles` listed tiles.
  void accumulate(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events);
  void finalize(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events);

 private:
  FrameShape frame_;
  cl::Kernel accumulate_, finalize_;
  cl::Buffer radiance_, weight_;  // running sums across batches
};

// The range of `tiles` listed tiles as 2D SSRCL_TILE work-groups side by side.
cl::NDRange listedTiles(int tiles);

}  // namespace ssrcl::detail
