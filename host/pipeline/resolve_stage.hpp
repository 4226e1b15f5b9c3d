#pragma once
// The resolve (kernels/resolve.cl): each reflecting pixel's estimate from its own and its
// neighbours' rays (ratio estimator, Stachowiak), accumulated over the trace's batches, then
// normalised into the reflection and distance passes, on the listed tiles.
#include "frame_resources.hpp"

namespace ssrcl::detail {

class ResolveStage {
 public:
  // With views > 0 it also sums the found weight per ray source into `view` (kernels/resolve.cl).
  static const StageAccess access;

  void configure(Device::Impl& device, const TraceSettings& s, int views);
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame);
  // The result goes to the outputs, or with `filtered` to the filter's input; with views the
  // source index and share of views per pixel to the view share.
  void bind(const FrameResources& resources, bool filtered);
  static ResolveParams params(const FrameConstants& frame, const TraceSettings& s, int views);
  // Adds the rays of one batch (params.first_sample, params.batch_size) over `tiles` listed tiles.
  void accumulate(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events);
  void finalize(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events);

 private:
  FrameShape frame_;
  int views_ = 0;
  cl::Kernel accumulate_, finalize_;
  cl::Buffer weight_, sources_;  // running sums across batches, with Role::ResolvedRgba's
};

// Runs `kernel` with one work-item a row of each of `tiles` listed tiles: work-groups of
// (1, SSRCL_TILE), group g on tile tile_list[g]. For kernels that put a row's pixels in float8
// lanes (resolve_accumulate, denoise).
void enqueueTileRows(cl::CommandQueue& q, cl::Kernel& kernel, int tiles, cl::Event* event);

}  // namespace ssrcl::detail
