#include "filter_stage.hpp"

#include "resolve_stage.hpp"

namespace ssrcl::detail {

const StageAccess FilterStage::access{
    "denoise",
    {Role::TileList, Role::Positions, Role::Normals, Role::PixelRays, Role::ResolvedRgba, Role::ResolvedDistance},
    {Role::Reflection, Role::Distance, Role::ResolvedRgba, Role::ResolvedDistance}};

void FilterStage::configure(Device::Impl& device, const TraceSettings& s) {
  enabled_ = s.denoise;
  separable_ = s.denoise && s.separableDenoise;
  if (!enabled_) return;
  const cl::Program& program = device.program({"ssrcl_shared.h", "common.cl", "filter.cl"});
  kernel_ = cl::Kernel(program, "denoise");
  if (separable_) second_ = cl::Kernel(program, "denoise");
}

void FilterStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame) {
  resources.plan(access, buffers, Role::ResolvedDistance, enabled_ ? frame.pixels() * sizeof(float) : 0);
}

void FilterStage::bind(const FrameResources& resources) {
  if (!enabled_) return;
  auto in = [&](Role role) { return resources.read(access, role); };
  auto out = [&](Role role) { return resources.write(access, role); };
  auto bindPass = [&](cl::Kernel& kernel, Role rgba, Role distance, Role outRgba, Role outDistance) {
    bindArgs(kernel, 1, "tile_list, positions, normals, pixel_rays, in_rgba, in_distance, out_rgba, out_distance",
             in(Role::TileList), in(Role::Positions), in(Role::Normals), in(Role::PixelRays), in(rgba), in(distance),
             out(outRgba), out(outDistance));
  };
  if (!separable_) {
    bindPass(kernel_, Role::ResolvedRgba, Role::ResolvedDistance, Role::Reflection, Role::Distance);
    return;
  }
  bindPass(kernel_, Role::Reflection, Role::Distance, Role::ResolvedRgba, Role::ResolvedDistance);
  bindPass(second_, Role::ResolvedRgba, Role::ResolvedDistance, Role::Reflection, Role::Distance);
}

void FilterStage::enqueue(cl::CommandQueue& q, const FrameConstants& frame, int tiles, StageEvents& events) {
  if (!enabled_ || tiles == 0) return;
  kernel_.setArg(0, FilterParams{frame, separable_ ? 2 : 3});
  enqueueTileRows(q, kernel_, tiles, newEvent(events, "denoise"));
  if (!separable_) return;
  second_.setArg(0, FilterParams{frame, 1});
  enqueueTileRows(q, second_, tiles, newEvent(events, "denoise"));
}

}  // namespace ssrcl::detail
