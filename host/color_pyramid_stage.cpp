#include "color_pyramid_stage.hpp"

namespace ssrcl::detail {

void ColorPyramidStage::configure(Device::Impl& device, const TraceSettings& s) {
  reduce_ = s.prefilter;
  if (reduce_)
    kernel_ = cl::Kernel(device.program({"ssrcl_shared.h", "common.cl", "color_lookup.cl", "color_pyramid.cl"}), "color_reduce");
}

void ColorPyramidStage::plan(DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  buffers.add(pyramid, (reduce_ ? frame.pyramidTexels() : frame.pixels()) * sizeof(cl_float4));
}

void ColorPyramidStage::bind(const HzbStage& hzb) {
  if (reduce_) bindArgs(kernel_, 0, pyramid, hzb.levels);
}

void ColorPyramidStage::enqueue(cl::CommandQueue& q, StageEvents& events) {
  if (reduce_) reducePyramid(q, kernel_, frame_, events, "color_mips");
}

}  // namespace ssrcl::detail
