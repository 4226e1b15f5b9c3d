#pragma once
// The optional edge-aware filter (kernels/filter.cl) after the resolve, on the listed tiles.
// With it on, the resolve writes to the resolved roles this stage plans instead of the outputs.
#include "frame_resources.hpp"

namespace ssrcl::detail {

class FilterStage {
 public:
  static const StageAccess access;

  void configure(Device::Impl& device, const TraceSettings& s);
  bool enabled() const { return enabled_; }
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const FrameResources& resources);
  void enqueue(cl::CommandQueue& q, const FrameConstants& frame, int tiles, StageEvents& events);

 private:
  bool enabled_ = false;
  cl::Kernel kernel_;
};

}  // namespace ssrcl::detail
