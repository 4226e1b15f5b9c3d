#include "back_pyramid_stage.hpp"

#include "hzb_stage.hpp"

namespace ssrcl::detail {

const StageAccess BackPyramidStage::access{
    "back pyramid", {Role::DepthPyramid, Role::Planes, Role::BackGuess, Role::PyramidLevels}, {Role::BackPyramid}};

void BackPyramidStage::configure(Device::Impl& device, bool used, bool guessed) {
  used_ = used;
  guessed_ = guessed;
  const cl::Program& program = device.program({"ssrcl_shared.h", "common.cl", "back_pyramid.cl"});
  level0_ = cl::Kernel(program, "back_level0");
  reduce_ = cl::Kernel(program, "range_reduce");
}

void BackPyramidStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  resources.plan(access, buffers, Role::BackPyramid, frame.pyramidTexels() * sizeof(cl_float2));
}

void BackPyramidStage::bind(const FrameResources& resources) {
  const cl::Buffer& back = resources.write(access, Role::BackPyramid);
  bindArgs(level0_, 1, "hzb, planes, guess, guessed, range", resources.read(access, Role::DepthPyramid),
           resources.read(access, Role::Planes), resources.read(access, Role::BackGuess), cl_int(guessed_), back);
  bindArgs(reduce_, 0, "pyramid, levels", back, resources.read(access, Role::PyramidLevels));
  bindArgs(reduce_, 3, "hzb", resources.read(access, Role::DepthPyramid));  // 2: the level, per pass
}

void BackPyramidStage::enqueue(cl::CommandQueue& q, const FrameConstants& frame, StageEvents& events) {
  if (!used_) return;
  level0_.setArg(0, frame);
  // A work-item per 8 pixels of a row (kernels/back_pyramid.cl SSRCL_BACK_LANES).
  const int items = (frame_.width + 7) / 8;
  q.enqueueNDRangeKernel(level0_, cl::NullRange,
                         cl::NDRange(roundUp(items, SSRCL_TILE), roundUp(frame_.height, SSRCL_TILE)),
                         cl::NDRange(SSRCL_TILE, SSRCL_TILE), nullptr, newEvent(events, "hzb"));
  reducePyramid(q, reduce_, frame_, events, "hzb");
}

}  // namespace ssrcl::detail
