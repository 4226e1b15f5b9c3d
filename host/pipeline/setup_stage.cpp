#include "setup_stage.hpp"

namespace ssrcl::detail {

namespace {

// The setup kernel's arguments after its parameters; the input passes are set again each frame.
const KernelArgList kSetupArgs{
    1,
    "color_in, depth_in, normal_in, roughness_in, position_out, hzb_out, normal_out, color_out, pixel_rays, "
    "ray_list, tile_list, ray_count, plane_out, fill_normal_out"};

}  // namespace

// Level 0 of both pyramids is setup's: the HZB and colour pyramid stages reduce the rest.
const StageAccess SetupStage::access{"setup",
                                     {},
                                     {Role::Positions, Role::Normals, Role::FillNormals, Role::Planes, Role::PixelRays,
                                      Role::RayList, Role::TileList, Role::DepthPyramid, Role::ColorPyramid}};

void SetupStage::configure(Device::Impl& device) {
  device_ = &device;
  kernel_ = cl::Kernel(
      device.program({"ssrcl_shared.h", "common.cl", "color_lookup.cl", "surface_plane.cl", "setup.cl"}), "setup");
}

void SetupStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame, int colorChannels,
                      bool roughnessImage, bool fillNormals) {
  frame_ = frame;
  colorChannels_ = colorChannels;
  fillNormals_ = fillNormals;
  const size_t pixels = frame.pixels();
  colorIn_.plan(*device_, buffers, pixels * colorChannels * sizeof(float));
  depthIn_.plan(*device_, buffers, pixels * sizeof(float));
  normalIn_.plan(*device_, buffers, pixels * 3 * sizeof(float));
  roughnessIn_.plan(*device_, buffers, roughnessImage ? pixels * sizeof(float) : 0);
  resources.plan(access, buffers, Role::Positions, pixels * sizeof(cl_float4));
  resources.plan(access, buffers, Role::Normals, pixels * sizeof(cl_float4));
  resources.plan(access, buffers, Role::FillNormals, fillNormals ? pixels * sizeof(cl_float4) : 0);
  resources.plan(access, buffers, Role::PixelRays, pixels * sizeof(cl_int));
  resources.plan(access, buffers, Role::RayList, pixels * sizeof(cl_int));
  resources.plan(access, buffers, Role::TileList, size_t(frame.tilesX) * frame.tilesY * sizeof(cl_int));
  buffers.add(counts_, SSRCL_COUNTERS * sizeof(cl_int));
  resources.plan(access, buffers, Role::Planes, pixels * sizeof(cl_float4));
}

void SetupStage::bind(const FrameResources& resources) {
  // Argument 0 is the parameter block, set at each enqueue. HZB and colour level 0 start at
  // offset 0 of their buffers.
  auto out = [&](Role role) { return resources.write(access, role); };
  bindArgs(kernel_, kSetupArgs, colorIn_.own(), depthIn_.own(), normalIn_.own(), roughnessIn_.own(), out(Role::Positions), out(Role::DepthPyramid),
           out(Role::Normals), out(Role::ColorPyramid), out(Role::PixelRays), out(Role::RayList), out(Role::TileList),
           counts_, out(Role::Planes), out(Role::FillNormals));
}

SetupParams SetupStage::params(const FrameConstants& frame, const TraceSettings& s, int colorChannels) {
  SetupParams p{};
  p.frame = frame;
  p.color_channels = colorChannels;
  p.constant_roughness = s.constantRoughness.value_or(-1.0f);  // the kernel's "unset"
  p.max_roughness = s.maxRoughness;
  p.samples_per_pixel = s.samplesPerPixel;
  p.full_rays_roughness = s.fullRaysRoughness;
  p.trace_stride = s.traceStride;
  p.classify = s.classifyWork;
  p.thickness_rel = s.thicknessRelative;
  p.adaptive_thickness = s.thicknessModel == ThicknessModel::Adaptive;
  p.edge_colors = s.edgeColors;
  return p;
}

void SetupStage::enqueue(cl::CommandQueue& q, const Inputs& in, const SetupParams& params, StageEvents& events) {
  const size_t pixels = frame_.pixels();
  // This frame's passes.
  kernel_.setArg(kSetupArgs["color_in"], colorIn_.put(q, in.color, pixels * colorChannels_ * sizeof(float), events));
  kernel_.setArg(kSetupArgs["depth_in"], depthIn_.put(q, in.depth, pixels * sizeof(float), events));
  kernel_.setArg(kSetupArgs["normal_in"], normalIn_.put(q, in.normal, pixels * 3 * sizeof(float), events));
  kernel_.setArg(kSetupArgs["roughness_in"], roughnessIn_.put(q, in.roughness, pixels * sizeof(float), events));
  q.enqueueFillBuffer(counts_, cl_int(0), 0, SSRCL_COUNTERS * sizeof(cl_int), nullptr, newEvent(events, "upload"));
  SetupParams planned = params;
  planned.fill_normals = fillNormals_;
  kernel_.setArg(0, planned);
  q.enqueueNDRangeKernel(kernel_, cl::NullRange, frame_.tiled2d(), cl::NDRange(SSRCL_TILE, SSRCL_TILE), nullptr,
                         newEvent(events, "setup"));
}

SetupStage::Counts SetupStage::readCounts(cl::CommandQueue& q) {
  cl_int c[SSRCL_COUNTERS] = {};
  q.enqueueReadBuffer(counts_, CL_TRUE, 0, sizeof(c), c);
  return {c[SSRCL_COUNT_LISTED], c[SSRCL_COUNT_RAYS], c[SSRCL_COUNT_TILES], c[SSRCL_COUNT_TRACED]};
}

}  // namespace ssrcl::detail
