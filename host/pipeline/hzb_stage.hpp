#pragma once
// The HZB (kernels/hzb.cl): the min-depth pyramid the Hi-Z tracer descends. Setup writes level 0;
// this stage reduces the others. Owns the level table the colour pyramid shares.
#include "stage_support.hpp"

namespace ssrcl::detail {

class HzbStage {
 public:
  void configure(Device::Impl& device);
  void plan(DeviceBuffers& buffers, const FrameShape& frame);
  void bind(cl::CommandQueue& q);  // writes the level table
  void enqueue(cl::CommandQueue& q, StageEvents& events);

  cl::Buffer hzb;     // every level packed, level 0 at offset 0
  cl::Buffer levels;  // HzbLevel per level

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
