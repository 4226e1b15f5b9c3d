#include "color_pyramid_stage.hpp"

namespace ssrcl::detail {

// Prefiltered hits replace the rough rays' radiance with their footprint's mean.
const StageAccess ColorPyramidStage::access{
    "color_mips", {Role::PyramidLevels, Role::RayList, Role::PixelRays}, {Role::ColorPyramid, Role::RayRadiance}};

void ColorPyramidStage::configure(Device::Impl& device, const TraceSettings& s, bool hitCounts) {
  reduce_ = s.prefilter;
  hitCounts_ = hitCounts;
  if (!reduce_) return;
  const cl::Program& program =
      device.program({"ssrcl_shared.h", "common.cl", "color_lookup.cl", "color_pyramid.cl", "hit_prefilter.cl"});
  reduce_kernel_ = cl::Kernel(program, "color_reduce");
  if (!hitCounts) return;
  count_ = cl::Kernel(program, "count_hits");
  weights_ = cl::Kernel(program, "weights_from_counts");
  lookup_ = cl::Kernel(program, "prefilter_hits");
}

void ColorPyramidStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  resources.plan(access, buffers, Role::ColorPyramid,
                 (reduce_ ? frame.pyramidTexels() : frame.pixels()) * sizeof(cl_float4));
  buffers.add(counts_, reduce_ && hitCounts_ ? frame.pixels() * sizeof(cl_int) : 0);
}

// Without hit counts (an auxiliary view's pyramid, read at once with the weights setup wrote) only
// the reduction is bound.
void ColorPyramidStage::bind(const FrameResources& resources) {
  if (!reduce_) return;
  auto in = [&](Role role) { return resources.read(access, role); };
  const cl::Buffer& pyramid = resources.write(access, Role::ColorPyramid);
  bindArgs(reduce_kernel_, 0, "pyramid, levels", pyramid, in(Role::PyramidLevels));
  if (!hitCounts_) return;
  const cl::Buffer& radiance = resources.write(access, Role::RayRadiance);
  bindArgs(count_, 1, "ray_list, pixel_rays, ray_radiance, counts", in(Role::RayList), in(Role::PixelRays), radiance,
           counts_);
  bindArgs(weights_, 1, "pyramid, counts", pyramid, counts_);
  bindArgs(lookup_, 1, "ray_list, pixel_rays, pyramid, levels, ray_radiance", in(Role::RayList), in(Role::PixelRays),
           pyramid, in(Role::PyramidLevels), radiance);
}

void ColorPyramidStage::reduce(cl::CommandQueue& q, StageEvents& events) {
  if (reduce_) reducePyramid(q, reduce_kernel_, frame_, events, "color_mips");
}

void ColorPyramidStage::enqueue(cl::CommandQueue& q, StageEvents& events) {
  if (reduce_) q.enqueueFillBuffer(counts_, cl_int(0), 0, frame_.pixels() * sizeof(cl_int), nullptr,
                                   newEvent(events, "color_mips"));
}

void ColorPyramidStage::prefilterHits(cl::CommandQueue& q, const TraceParams& params, StageEvents& events) {
  if (!reduce_) return;
  const cl::NDRange rays(roundUp(size_t(params.listed) * params.batch_size, 64)), pixels(roundUp(frame_.pixels(), 64));
  for (cl::Kernel* k : {&count_, &weights_, &lookup_}) k->setArg(0, params);
  q.enqueueNDRangeKernel(count_, cl::NullRange, rays, cl::NDRange(64), nullptr, newEvent(events, "color_mips"));
  q.enqueueNDRangeKernel(weights_, cl::NullRange, pixels, cl::NDRange(64), nullptr, newEvent(events, "color_mips"));
  reducePyramid(q, reduce_kernel_, frame_, events, "color_mips");
  q.enqueueNDRangeKernel(lookup_, cl::NullRange, rays, cl::NDRange(64), nullptr, newEvent(events, "color_mips"));
}

}  // namespace ssrcl::detail
