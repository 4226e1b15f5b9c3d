#pragma once
// The optional edge-aware filter (kernels/filter.cl) after the resolve, on the listed tiles.
// Over the square of taps, the resolve writes to the resolved roles this stage plans and the filter
// reads them. Separable (TraceSettings::separableDenoise), the resolve writes the outputs, a pass
// along y filters them into the resolved roles and one along x filters those back: no buffer more.
#include "frame_resources.hpp"

namespace ssrcl::detail {

class FilterStage {
 public:
  static const StageAccess access;

  void configure(Device::Impl& device, const TraceSettings& s);
  bool enabled() const { return enabled_; }
  // Whether the resolve is to write to the resolved roles (the square filter's input), not the outputs.
  bool readsResolved() const { return enabled_ && !separable_; }
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const FrameResources& resources);
  void enqueue(cl::CommandQueue& q, const FrameConstants& frame, int tiles, StageEvents& events);

 private:
  bool enabled_ = false, separable_ = false;
  cl::Kernel kernel_, second_;  // the square, or the pass along y; the pass along x
};

}  // namespace ssrcl::detail
