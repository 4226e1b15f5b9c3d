#pragma once
// The range pyramid (kernels/back_pyramid.cl): per texel the nearest and the farthest depth at
// which a ray over its pixels can hit a surface, from the final surface planes (after the
// thickness stage), the nearest of coarse levels the HZB's. The Hi-Z trace skips what a ray passes
// wholly in front or behind, reading both ends of a texel at once.
#include "frame_resources.hpp"

namespace ssrcl::detail {

class BackPyramidStage {
 public:
  static const StageAccess access;

  // `used`: only the Hi-Z trace reads the pyramid (kernels/trace.cl cell_range, in the frame and views);
  // for the others it is not built. `guessed`: with a back-face pass, whose misses fall back on the
  // thickness model's guess (BackGuess), a surface reaches as far as the larger of the two.
  void configure(Device::Impl& device, bool used, bool guessed);
  void plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame);
  void bind(const FrameResources& resources);
  void enqueue(cl::CommandQueue& q, const FrameConstants& frame, StageEvents& events);

 private:
  FrameShape frame_;
  bool used_ = false, guessed_ = false;
  cl::Kernel level0_, reduce_;
};

}  // namespace ssrcl::detail
