#include "hzb_stage.hpp"

namespace ssrcl::detail {

const StageAccess HzbStage::access{"hzb", {}, {Role::DepthPyramid, Role::PyramidLevels}};

void HzbStage::configure(Device::Impl& device) {
  kernel_ = cl::Kernel(device.program({"ssrcl_shared.h", "common.cl", "hzb.cl"}), "depth_reduce");
}

void HzbStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  resources.plan(access, buffers, Role::DepthPyramid, frame.pyramidTexels() * sizeof(float));
  resources.plan(access, buffers, Role::PyramidLevels, frame.levels.size() * sizeof(HzbLevel), CL_MEM_READ_ONLY);
}

void HzbStage::bind(cl::CommandQueue& q, const FrameResources& resources) {
  const cl::Buffer& levels = resources.write(access, Role::PyramidLevels);
  q.enqueueWriteBuffer(levels, CL_TRUE, 0, frame_.levels.size() * sizeof(HzbLevel), frame_.levels.data());
  bindArgs(kernel_, 0, "pyramid, levels", resources.write(access, Role::DepthPyramid), levels);
}

// Work-groups of one 64-texel row: PoCL vectorises a group's work-item loop along x, and the reduction
// reads whole rows; 1.2x faster than 8x8 groups at 1080p (docs/BENCHMARKS.md), same texels.
constexpr int kHzbGroupWidth = 64;

void HzbStage::enqueue(cl::CommandQueue& q, StageEvents& events) {
  reducePyramid(q, kernel_, frame_, events, "hzb", kHzbGroupWidth);
}

void reducePyramid(cl::CommandQueue& q, cl::Kernel& kernel, const FrameShape& frame, StageEvents& events,
                   const std::string& stage, int groupWidth) {
  const int groupHeight = SSRCL_TILE * SSRCL_TILE / groupWidth;
  for (size_t l = 1; l < frame.levels.size(); ++l) {
    const cl::NDRange range(roundUp(frame.levels[l].width, groupWidth), roundUp(frame.levels[l].height, groupHeight));
    kernel.setArg(2, static_cast<cl_int>(l));
    q.enqueueNDRangeKernel(kernel, cl::NullRange, range, cl::NDRange(groupWidth, groupHeight), nullptr,
                           newEvent(events, stage));
  }
}

}  // namespace ssrcl::detail
