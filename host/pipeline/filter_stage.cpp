#include "filter_stage.hpp"

#include "resolve_stage.hpp"

namespace ssrcl::detail {

void FilterStage::configure(Device::Impl& device, const TraceSettings& s) {
  enabled_ = s.denoise;
  if (enabled_) kernel_ = cl::Kernel(device.program({"ssrcl_shared.h", "common.cl", "filter.cl"}), "denoise");
}

void FilterStage::plan(DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  buffers.add(resolvedRgba, enabled_ ? frame.pixels() * sizeof(cl_float4) : 0);
  buffers.add(resolvedDistance, enabled_ ? frame.pixels() * sizeof(float) : 0);
}

void FilterStage::bind(const SetupStage& setup, const cl::Buffer& rgba, const cl::Buffer& distance) {
  if (enabled_)
    bindArgs(kernel_, 1, "tile_list, positions, normals, pixel_rays, in_rgba, in_distance, out_rgba, out_distance",
             setup.tileList, setup.positions, setup.normals, setup.pixelRays, resolvedRgba,
             resolvedDistance, rgba, distance);
}

void FilterStage::enqueue(cl::CommandQueue& q, const TraceSettings& s, int tiles, StageEvents& events) {
  if (!enabled_ || tiles == 0) return;
  kernel_.setArg(0, FilterParams{frame_.width, frame_.height, frame_.tilesX, s.mirrorRoughness});
  q.enqueueNDRangeKernel(kernel_, cl::NullRange, listedTiles(tiles), cl::NDRange(SSRCL_TILE, SSRCL_TILE), nullptr,
                         newEvent(events, "denoise"));
}

}  // namespace ssrcl::detail
