#include "filter_stage.hpp"

#include "resolve_stage.hpp"

namespace ssrcl::detail {

const StageAccess FilterStage::access{"denoise",
                                      {Role::TileList, Role::Positions, Role::Normals, Role::PixelRays,
                                       Role::ResolvedRgba, Role::ResolvedDistance},
                                      {Role::Reflection, Role::Distance}};

void FilterStage::configure(Device::Impl& device, const TraceSettings& s) {
  enabled_ = s.denoise;
  if (enabled_) kernel_ = cl::Kernel(device.program({"ssrcl_shared.h", "common.cl", "filter.cl"}), "denoise");
}

void FilterStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame) {
  resources.plan(access, buffers, Role::ResolvedDistance, enabled_ ? frame.pixels() * sizeof(float) : 0);
}

void FilterStage::bind(const FrameResources& resources) {
  if (!enabled_) return;
  auto in = [&](Role role) { return resources.read(access, role); };
  bindArgs(kernel_, 1, "tile_list, positions, normals, pixel_rays, in_rgba, in_distance, out_rgba, out_distance",
           in(Role::TileList), in(Role::Positions), in(Role::Normals), in(Role::PixelRays), in(Role::ResolvedRgba),
           in(Role::ResolvedDistance), resources.write(access, Role::Reflection),
           resources.write(access, Role::Distance));
}

void FilterStage::enqueue(cl::CommandQueue& q, const FrameConstants& frame, int tiles, StageEvents& events) {
  if (!enabled_ || tiles == 0) return;
  kernel_.setArg(0, FilterParams{frame});
  enqueueTileRows(q, kernel_, tiles, newEvent(events, "denoise"));
}

}  // namespace ssrcl::detail
