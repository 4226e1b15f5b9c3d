#include "view_stage.hpp"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>

#include "ssrcl/error.hpp"

namespace ssrcl::detail {
namespace {

// A view without a roughness image and no constant roughness set has none of its pixels glossy.
TraceSettings viewSettings(const ViewSource& view, const TraceSettings& s) {
  TraceSettings v = s;
  if (!view.inputs.has("roughness") && v.constantRoughness < 0.0f) v.constantRoughness = 1.0f;
  return v;
}

}  // namespace

const StageAccess ViewStage::access{"views",
                                    {Role::Positions, Role::Normals, Role::RayList, Role::PixelRays},
                                    {Role::RayHits, Role::RayRadiance, Role::RayStates}};
const StageAccess ViewStage::viewAccess{"views (in a view)",
                                        {Role::BackPyramid, Role::PyramidLevels, Role::Positions, Role::Normals,
                                         Role::Planes, Role::ColorPyramid},
                                        {}};

std::string ViewStage::name(const ViewSource& view, int index) {
  return view.label.empty() ? "view " + std::to_string(index + 1) : view.label;
}

void ViewStage::validate(const ViewSource& view, int index, const TraceSettings& s) {
  const std::string what = name(view, index);
  try {
    validateCamera(view.camera, (what + " camera").c_str());
    view.inputs.validate(view.camera, viewSettings(view, s));
  } catch (const Error& e) {
    throw Error(e.code(), what + ": " + e.what());
  }
}

void ViewStage::configure(Device::Impl& device, const TraceSettings& s, size_t viewCount) {
  units_.resize(viewCount);
  if (viewCount == 0) return;  // nothing to build: clang preprocesses a program even when PoCL has it cached
  program_ = device.program(
      {"ssrcl_shared.h", "common.cl", "sequence.cl", "ggx.cl", "ggx_lanes.cl", "color_lookup.cl", "surface_plane.cl",
       "trace.cl", "view_trace.cl"},
      {tracerDefine(s.tracer), roughnessMappingDefine(s.roughnessMapping), "SSRCL_COUNT_WORK=0", "SSRCL_VIEWS=1"});
  for (auto& unit : units_) {
    if (!unit) unit = std::make_unique<Unit>();
    unit->setup.configure(device);
    unit->thickness.configure(device, s, false);  // views have no back-face depth
    unit->hzb.configure(device);
    unit->range.configure(device, s.tracer == Tracer::HiZ, false);
    unit->colors.configure(device, s, false);
    unit->kernel = cl::Kernel(program_, "trace_views");
  }
}

void ViewStage::plan(DeviceBuffers& buffers, const std::vector<ViewSource>& views, size_t rayRecords) {
  colorChannels_.clear();
  for (size_t k = 0; k < units_.size(); ++k) {
    Unit& u = *units_[k];
    const Camera& c = views[k].camera;
    u.frame = FrameShape(c.width, c.height);
    colorChannels_.push_back(views[k].inputs.view("color").channels);
    u.resources.beginPlan();
    u.setup.plan(u.resources, buffers, u.frame, colorChannels_.back(), views[k].inputs.has("roughness"), false);
    u.thickness.plan(u.resources, buffers, u.frame);
    u.hzb.plan(u.resources, buffers, u.frame);
    u.range.plan(u.resources, buffers, u.frame);
    u.colors.plan(u.resources, buffers, u.frame);
  }
  buffers.add(cameras_, units_.size() * sizeof(ViewCamera), CL_MEM_READ_ONLY);
  buffers.add(viewOrder_, units_.empty() ? 0 : rayRecords * sizeof(cl_uint));
}

void ViewStage::bind(cl::CommandQueue& q, const Camera& main, const std::vector<ViewSource>& views,
                     const FrameResources& resources) {
  auto in = [&](Role role) { return resources.read(access, role); };
  auto out = [&](Role role) { return resources.write(access, role); };
  std::vector<ViewCamera> cameras(units_.size());
  const glm::dmat4 mainToWorld = glm::inverse(main.view);
  for (size_t k = 0; k < units_.size(); ++k) {
    Unit& u = *units_[k];
    const Camera& c = views[k].camera;
    const FrameConstants constants = frameConstants(u.frame, c, TraceSettings());
    const glm::dmat4 fromMain = c.view * mainToWorld;
    toRowMajor(fromMain, cameras[k].from_main);
    toRowMajor(glm::inverse(fromMain), cameras[k].to_main);
    std::copy(std::begin(constants.proj), std::end(constants.proj), cameras[k].proj);
    cameras[k].width = c.width;
    cameras[k].height = c.height;
    cameras[k].near_plane = constants.near_plane;
    cameras[k].far_plane = constants.far_plane;
    cameras[k].other_time = views[k].otherTime;

    u.setup.bind(u.resources);
    u.thickness.bind(u.resources);
    u.hzb.bind(q, u.resources);
    u.range.bind(u.resources);
    u.colors.bind(u.resources);
    auto view = [&](Role role) { return u.resources.read(viewAccess, role); };
    bindArgs(u.kernel, 1,
             "views, main_positions, main_normals, ray_list, pixel_rays, range, levels, positions, normals, "
             "planes, color_pyramid, ray_hit, ray_radiance, ray_state, ray_view_order",
             cameras_, in(Role::Positions), in(Role::Normals), in(Role::RayList), in(Role::PixelRays),
             view(Role::BackPyramid), view(Role::PyramidLevels), view(Role::Positions), view(Role::Normals),
             view(Role::Planes), view(Role::ColorPyramid), out(Role::RayHits), out(Role::RayRadiance),
             out(Role::RayStates), viewOrder_);
  }
  if (!cameras.empty())
    q.enqueueWriteBuffer(cameras_, CL_TRUE, 0, cameras.size() * sizeof(ViewCamera), cameras.data());
}

void ViewStage::prepare(cl::CommandQueue& q, std::vector<ViewSource>& views, const TraceSettings& s,
                        StageEvents& events) {
  for (size_t k = 0; k < units_.size(); ++k) {
    if (views[k].prepared) continue;
    Unit& u = *units_[k];
    PipelineInputs& in = views[k].inputs;
    const TraceSettings vs = viewSettings(views[k], s);
    const FrameConstants constants = frameConstants(u.frame, views[k].camera, vs);
    u.setup.enqueue(q,
                    {in.pixels("color"), in.pixels("depth"), in.pixels("normal"),
                     in.has("roughness") ? in.pixels("roughness") : nullptr},
                    SetupStage::params(constants, vs, colorChannels_[k]), events);
    u.hzb.enqueue(q, events);
    u.colors.reduce(q, events);
    u.thickness.enqueue(q, constants, vs, nullptr, false, events);
    u.range.enqueue(q, constants, events);
    views[k].prepared = true;
  }
}

void ViewStage::limitRadiance(const float* color, size_t pixels, int channels, float cap) {
  if (cap == 0.0f) {
    radianceLimit_ = INFINITY;
    return;
  }
  std::vector<float> means;
  means.reserve(pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const float* c = color + i * channels;
    const float m = (c[0] + c[1] + c[2]) / 3.0f;
    if (std::isfinite(m)) means.push_back(std::max(m, 0.0f));
  }
  if (means.empty()) {
    radianceLimit_ = 0.0f;
    return;
  }
  const auto at = means.begin() + means.size() * 99 / 100;
  std::nth_element(means.begin(), at, means.end());
  radianceLimit_ = cap * *at;
}

void ViewStage::trace(cl::CommandQueue& q, const TraceParams& batch, StageEvents& events) {
  ViewTraceParams p{};
  p.frame = batch.frame;
  p.listed = batch.listed;
  p.batch_size = batch.batch_size;
  p.first_sample = batch.first_sample;
  p.view_count = static_cast<cl_int>(units_.size());
  p.max_iterations = batch.max_iterations;
  p.cone_scale = batch.cone_scale;
  p.linear_step = batch.linear_step;
  p.edge_fade = batch.edge_fade;
  p.radiance_limit = radianceLimit_;
  // A work-item per SSRCL_TRACE_PIXELS listed pixels (kernels/view_trace.cl).
  const size_t range = roundUp((size_t(batch.listed) + SSRCL_TRACE_PIXELS - 1) / SSRCL_TRACE_PIXELS, 64);
  const int ranks = std::min<int>(SSRCL_VIEWS_PER_RAY, static_cast<int>(units_.size()));
  for (p.rank = 0; p.rank < ranks; ++p.rank) {
    for (size_t k = 0; k < units_.size(); ++k) {
      p.view = static_cast<cl_int>(k);
      p.rank_views = p.rank == 0 && k == 0;
      p.level_count = static_cast<cl_int>(units_[k]->frame.levels.size());
      units_[k]->kernel.setArg(0, p);
      q.enqueueNDRangeKernel(units_[k]->kernel, cl::NullRange, cl::NDRange(range), cl::NDRange(64), nullptr,
                             newEvent(events, "views"));
    }
  }
}

}  // namespace ssrcl::detail
