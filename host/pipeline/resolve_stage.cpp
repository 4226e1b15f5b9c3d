#include "resolve_stage.hpp"

namespace ssrcl::detail {

namespace {
// The range of `tiles` listed tiles as 2D SSRCL_TILE work-groups side by side.
cl::NDRange listedTiles(int tiles) { return cl::NDRange(size_t(tiles) * SSRCL_TILE, SSRCL_TILE); }
}  // namespace

void enqueueTileRows(cl::CommandQueue& q, cl::Kernel& kernel, int tiles, cl::Event* event) {
  q.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(size_t(tiles), SSRCL_TILE), cl::NDRange(1, SSRCL_TILE),
                         nullptr, event);
}

const StageAccess ResolveStage::access{"resolve",
                                       {Role::TileList, Role::Positions, Role::Normals, Role::PixelRays, Role::RayHits,
                                        Role::RayRadiance, Role::RayStates},
                                       {Role::ResolvedRgba, Role::ResolvedDistance, Role::Reflection, Role::Distance,
                                        Role::ViewShare}};

void ResolveStage::configure(Device::Impl& device, const TraceSettings& s, int views) {
  views_ = views;
  std::vector<std::string> defines = {roughnessMappingDefine(s.roughnessMapping),
                                      "SSRCL_RESOLVE_RAY_STRIDE=" + std::to_string(resolveRayStride(s))};
  if (views > 0) defines.push_back("SSRCL_VIEWS=1");
  const cl::Program& program = device.program({"ssrcl_shared.h", "common.cl", "ggx.cl", "resolve.cl"}, defines);
  accumulate_ = cl::Kernel(program, "resolve_accumulate");
  finalize_ = cl::Kernel(program, "resolve_finalize");
}

void ResolveStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  // The radiance sums become the filter's input where they lie (a frame's float4s less).
  resources.plan(access, buffers, Role::ResolvedRgba, frame.pixels() * sizeof(cl_float4));
  buffers.add(weight_, frame.pixels() * sizeof(cl_float2));
  buffers.add(sources_, views_ > 0 ? frame.pixels() * (views_ + 1) * sizeof(float) : 0);
}

void ResolveStage::bind(const FrameResources& resources, bool filtered) {
  auto in = [&](Role role) { return resources.read(access, role); };
  auto out = [&](Role role) { return resources.write(access, role); };
  bindArgs(accumulate_, 1,
           "tile_list, positions, normals, pixel_rays, ray_hit, ray_radiance, acc_radiance, acc_weight, ray_state, "
           "acc_sources",
           in(Role::TileList), in(Role::Positions), in(Role::Normals), in(Role::PixelRays), in(Role::RayHits),
           in(Role::RayRadiance), out(Role::ResolvedRgba), weight_, in(Role::RayStates), sources_);
  bindArgs(finalize_, 1, "tile_list, acc_radiance, acc_weight, out_rgba, out_distance, acc_sources, out_view",
           in(Role::TileList), out(Role::ResolvedRgba), weight_, out(filtered ? Role::ResolvedRgba : Role::Reflection),
           out(filtered ? Role::ResolvedDistance : Role::Distance), sources_, out(Role::ViewShare));
}

ResolveParams ResolveStage::params(const FrameConstants& frame, const TraceSettings& s, int views) {
  ResolveParams p{};
  p.frame = frame;
  p.reuse_radius = s.reuseRadius;
  p.view_count = views;
  return p;  // batch_size and first_sample are per batch
}

void ResolveStage::accumulate(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events) {
  accumulate_.setArg(0, params);
  enqueueTileRows(q, accumulate_, tiles, newEvent(events, "resolve"));
}

void ResolveStage::finalize(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events) {
  finalize_.setArg(0, params);
  q.enqueueNDRangeKernel(finalize_, cl::NullRange, listedTiles(tiles), cl::NDRange(SSRCL_TILE, SSRCL_TILE), nullptr,
                         newEvent(events, "resolve"));
}

}  // namespace ssrcl::detail
