#pragma once
// The resolve (kernels/resolve.cl): each reflecting pixel's estimate from its own and its
// neighbours' rays (ratio estimator, Stachowiak), accumulated over the trace's batches, then
// normalised into the reflection and distance passes, on the listed tiles.
#include "trace_stage.hpp"

namespace ssrcl::detail {

class ResolveStage {
 public:
  // With views > 0 it also sums the found weight per ray source into `view` (kernels/resolve.cl).
  void configure(Device::Impl& device, const TraceSettings& s, int views);
  void plan(DeviceBuffers& buffers, const FrameShape& frame);
  // `rgba` and `distance` receive the result (the outputs, or the filter's input), `view` the
  // source index and share of views per pixel (with views).
  void bind(const SetupStage& setup, const TraceStage& trace, const cl::Buffer& rgba, const cl::Buffer& distance,
            const cl::Buffer& view);
  static ResolveParams params(const FrameShape& frame, const CameraConstants& camera, const TraceSettings& s,
                              int views);
  // Adds the rays of one batch (params.first_sample, params.batch_size) over `tiles` listed tiles.
  void accumulate(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events);
  void finalize(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events);

 private:
  FrameShape frame_;
  int views_ = 0;
  cl::Kernel accumulate_, finalize_;
  cl::Buffer radiance_, weight_, sources_;  // running sums across batches
};

// The range of `tiles` listed tiles as 2D SSRCL_TILE work-groups side by side.
cl::NDRange listedTiles(int tiles);

}  // namespace ssrcl::detail
