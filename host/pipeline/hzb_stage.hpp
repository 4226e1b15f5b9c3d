#pragma once
// The HZB (kernels/hzb.cl): the min-depth pyramid the Hi-Z tracer descends. Setup writes level 0;
// this stage reduces the others. Plans the level table the colour pyramid shares.
#include "frame_resources.hpp"

namespace ssrcl::detail {

class HzbStage {
 public:
  static const StageAccess access;

  void configure(Device::Impl& device);
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame);
  void bind(cl::CommandQueue& q, const FrameResources& resources);  // writes the level table
  void enqueue(cl::CommandQueue& q, StageEvents& events);

 private:
  FrameShape frame_;
  cl::Kernel kernel_;
};

// Runs a pyramid reduction kernel (arguments: pyramid, level table, destination level) over
// levels 1.. of `frame`, one event each under `stage`, in work-groups of SSRCL_TILE^2 work-items
// `groupWidth` wide.
void reducePyramid(cl::CommandQueue& q, cl::Kernel& kernel, const FrameShape& frame, StageEvents& events,
                   const std::string& stage, int groupWidth = SSRCL_TILE);

}  // namespace ssrcl::detail
