#include "resolve_stage.hpp"

namespace ssrcl::detail {

cl::NDRange listedTiles(int tiles) { return cl::NDRange(size_t(tiles) * SSRCL_TILE, SSRCL_TILE); }

void ResolveStage::configure(Device::Impl& device, const TraceSettings& s, int views) {
  views_ = views;
  std::vector<std::string> defines = {roughnessMappingDefine(s.roughnessMapping),
                                      "SSRCL_RESOLVE_RAY_STRIDE=" + std::to_string(resolveRayStride(s))};
  if (views > 0) defines.push_back("SSRCL_VIEWS=1");
  const cl::Program& program = device.program({"ssrcl_shared.h", "common.cl", "ggx.cl", "resolve.cl"}, defines);
  accumulate_ = cl::Kernel(program, "resolve_accumulate");
  finalize_ = cl::Kernel(program, "resolve_finalize");
}

void ResolveStage::plan(DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  buffers.add(radiance_, frame.pixels() * sizeof(cl_float4));
  buffers.add(weight_, frame.pixels() * sizeof(cl_float2));
  buffers.add(sources_, views_ > 0 ? frame.pixels() * (views_ + 1) * sizeof(float) : 0);
}

void ResolveStage::bind(const SetupStage& setup, const TraceStage& trace, const cl::Buffer& rgba,
                        const cl::Buffer& distance, const cl::Buffer& view) {
  bindArgs(accumulate_, 1,
           "tile_list, positions, normals, pixel_rays, ray_hit, ray_radiance, acc_radiance, acc_weight, ray_state, "
           "acc_sources",
           setup.tileList, setup.positions, setup.normals, setup.pixelRays, trace.rayHit,
           trace.rayRadiance, radiance_, weight_, trace.rayState, sources_);
  bindArgs(finalize_, 1, "tile_list, acc_radiance, acc_weight, out_rgba, out_distance, acc_sources, out_view",
           setup.tileList, radiance_, weight_, rgba, distance, sources_, view);
}

ResolveParams ResolveStage::params(const FrameShape& frame, const CameraConstants& camera, const TraceSettings& s,
                                   int views) {
  ResolveParams p{};
  std::copy(std::begin(camera.invProj), std::end(camera.invProj), p.inv_proj);
  p.width = frame.width;
  p.height = frame.height;
  p.tiles_x = frame.tilesX;
  p.mirror_roughness = s.mirrorRoughness;
  p.reuse_radius = s.reuseRadius;
  p.view_count = views;
  return p;  // batch_size and first_sample are per batch
}

void ResolveStage::accumulate(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events) {
  accumulate_.setArg(0, params);
  q.enqueueNDRangeKernel(accumulate_, cl::NullRange, listedTiles(tiles), cl::NDRange(SSRCL_TILE, SSRCL_TILE), nullptr,
                         newEvent(events, "resolve"));
}

void ResolveStage::finalize(cl::CommandQueue& q, const ResolveParams& params, int tiles, StageEvents& events) {
  finalize_.setArg(0, params);
  q.enqueueNDRangeKernel(finalize_, cl::NullRange, listedTiles(tiles), cl::NDRange(SSRCL_TILE, SSRCL_TILE), nullptr,
                         newEvent(events, "resolve"));
}

}  // namespace ssrcl::detail
