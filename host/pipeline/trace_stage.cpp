#include "trace_stage.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "settings_validation.hpp"
#include "shading/specular_albedo_tables.hpp"

namespace ssrcl::detail {

std::string tracerDefine(Tracer t) {
  return t == Tracer::Linear ? "SSRCL_TRACER=SSRCL_TRACER_LINEAR"
         : t == Tracer::DDA  ? "SSRCL_TRACER=SSRCL_TRACER_DDA"
                             : "SSRCL_TRACER=SSRCL_TRACER_HIZ";
}

namespace {

// trace_rays's arguments after its parameters; the material passes are set again each frame.
const KernelArgList kTraceArgs{
    1,
    "range, levels, positions, normals, ray_list, pixel_rays, planes, guess, work_counters, color_pyramid, "
    "base, specular, f0, albedo, ray_hit, ray_radiance, ray_state"};

// Ray records of all samples when they fit in this budget, else fewer samples per batch (the
// resolve accumulates across batches; prefiltered hits are weighted by their own batch's hits,
// kernels/hit_prefilter.cl).
constexpr size_t kRayRecordBudget = size_t(512) << 20;

constexpr size_t kAlbedoEntries = (SSRCL_ALBEDO_STEPS + 1) * (SSRCL_ALBEDO_STEPS + 1);

// E's (scale, bias) at the table's nodes (ssrcl_shared.h), as the kernel reads them. Read
// bilinearly it is within 1.5% of the integral everywhere (the worst at roughness 0.05, cos 0.01),
// within 0.5% at cos >= 0.1.
const std::vector<cl_float2>& albedoTable() {
  static const std::vector<cl_float2> table = [] {
    std::vector<cl_float2> t;
    t.reserve(kAlbedoEntries);
    for (const auto& row : detail::kSpecularAlbedoNodes)
      for (const auto& e : row) t.push_back({{float(e[0]), float(e[1])}});
    return t;
  }();
  return table;
}

}  // namespace

const StageAccess TraceStage::access{"trace",
                                     {Role::BackPyramid, Role::PyramidLevels, Role::Positions, Role::Normals,
                                      Role::RayList, Role::PixelRays, Role::Planes, Role::BackGuess,
                                      Role::ColorPyramid},
                                     {Role::RayHits, Role::RayRadiance, Role::RayStates}};

void TraceStage::configure(Device::Impl& device, const TraceSettings& s, bool hasBase, bool materials, bool views,
                           bool backDepth) {
  device_ = &device;
  hasBase_ = hasBase;
  materials_ = hasBase && materials;
  counting_ = s.countWork;
  views_ = views;
  std::vector<std::string> defines = {tracerDefine(s.tracer), roughnessMappingDefine(s.roughnessMapping),
                                      std::string("SSRCL_COUNT_WORK=") + (s.countWork ? "1" : "0")};
  if (views) defines.push_back("SSRCL_VIEWS=1");  // only then: programs without views stay as they were
  if (materials_) defines.push_back("SSRCL_MATERIAL_HITS=1");  // likewise without materials
  if (backDepth) defines.push_back("SSRCL_BACK_KNOWN=1");  // likewise without a back-face pass
  const cl::Program& program = device.program({"ssrcl_shared.h", "common.cl", "sequence.cl", "ggx.cl", "ggx_lanes.cl",
                                               "color_lookup.cl", "surface_plane.cl", "trace.cl"},
                                              defines);
  kernel_ = cl::Kernel(program, "trace_rays");
  samples_ = s.samplesPerPixel;
}

void TraceStage::plan(FrameResources& resources, DeviceBuffers& buffers, const FrameShape& frame) {
  frame_ = frame;
  const size_t pixels = frame.pixels();
  const size_t perSample = pixels * sizeof(cl_float4);  // of each of the two record buffers
  // Each frame's own: a pipeline reused for a smaller frame takes all its rays at once again.
  batch_ = std::min(samples_, static_cast<int>(std::max<size_t>(1, kRayRecordBudget / (2 * perSample))));
  resources.plan(access, buffers, Role::RayHits, perSample * batch_);
  resources.plan(access, buffers, Role::RayRadiance, perSample * batch_);
  resources.plan(access, buffers, Role::RayStates, views_ ? pixels * batch_ : 0);
  baseIn_.plan(*device_, buffers, hasBase_ ? pixels * 3 * sizeof(float) : 0);
  specularIn_.plan(*device_, buffers, hasBase_ ? pixels * 3 * sizeof(float) : 0);
  f0In_.plan(*device_, buffers, materials_ ? pixels * 3 * sizeof(float) : 0);
  buffers.add(albedoTable_, materials_ ? kAlbedoEntries * sizeof(cl_float2) : 0, CL_MEM_READ_ONLY);
  buffers.add(workCounters_, counting_ ? (SSRCL_FETCH_SLOTS + SSRCL_HISTOGRAM_BINS) * sizeof(cl_int) : 0);
}

void TraceStage::bind(const FrameResources& resources) {
  auto in = [&](Role role) { return resources.read(access, role); };
  auto out = [&](Role role) { return resources.write(access, role); };
  bindArgs(kernel_, kTraceArgs, in(Role::BackPyramid), in(Role::PyramidLevels), in(Role::Positions), in(Role::Normals), in(Role::RayList),
           in(Role::PixelRays), in(Role::Planes), in(Role::BackGuess), workCounters_, in(Role::ColorPyramid), baseIn_.own(),
           specularIn_.own(), f0In_.own(), albedoTable_, out(Role::RayHits), out(Role::RayRadiance), out(Role::RayStates));
}

TraceParams TraceStage::params(const FrameConstants& constants, const FrameShape& frame, const TraceSettings& s,
                               bool hasBase) {
  TraceParams p{};
  p.frame = constants;
  p.level_count = static_cast<shared::ssrcl_int>(frame.levels.size());
  p.seed = s.seed;
  // Each ray's cone covers its share of the lobe among all N rays the resolve combines: a
  // reflected GGX lobe spans about 2 alpha, so a share is a cone of half-angle 2 alpha / sqrt(N).
  p.cone_scale = s.prefilter ? 2.0f / std::sqrt(float(resolvedRays(s))) : 0.0f;
  p.linear_step = s.linearStepPixels;
  p.max_iterations = maxIterations(s);
  p.edge_fade = s.edgeFade;
  p.glossy_hit_roughness = s.glossyHitRoughness;
  p.has_base = hasBase;
  return p;  // listed, batch_size and first_sample are per batch
}

void TraceStage::upload(cl::CommandQueue& q, const float* base, const float* specular, const float* f0,
                        StageEvents& events) {
  if (counting_)
    q.enqueueFillBuffer(workCounters_, cl_int(0), 0, (SSRCL_FETCH_SLOTS + SSRCL_HISTOGRAM_BINS) * sizeof(cl_int),
                        nullptr, newEvent(events, "upload"));
  if (!hasBase_) return;
  // This frame's passes.
  const size_t bytes = frame_.pixels() * 3 * sizeof(float);
  kernel_.setArg(kTraceArgs["base"], baseIn_.put(q, base, bytes, events));
  kernel_.setArg(kTraceArgs["specular"], specularIn_.put(q, specular, bytes, events));
  if (!materials_) return;
  kernel_.setArg(kTraceArgs["f0"], f0In_.put(q, f0, bytes, events));
  q.enqueueWriteBuffer(albedoTable_, CL_FALSE, 0, kAlbedoEntries * sizeof(cl_float2), albedoTable().data(), nullptr,
                       newEvent(events, "upload"));
}

void TraceStage::enqueue(cl::CommandQueue& q, const TraceParams& params, StageEvents& events) {
  kernel_.setArg(0, params);
  // A work-item per SSRCL_TRACE_PIXELS listed pixels (kernels/trace.cl).
  const size_t items = (size_t(params.listed) + SSRCL_TRACE_PIXELS - 1) / SSRCL_TRACE_PIXELS;
  q.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(roundUp(items, 64)), cl::NDRange(64), nullptr,
                         newEvent(events, "trace"));
}

void TraceStage::readWork(cl::CommandQueue& q, StageTimes& times) {
  times.depthFetches = 0;
  times.iterationHistogram.clear();
  if (!counting_) return;
  std::vector<cl_int> counters(SSRCL_FETCH_SLOTS + SSRCL_HISTOGRAM_BINS);
  q.enqueueReadBuffer(workCounters_, CL_TRUE, 0, counters.size() * sizeof(cl_int), counters.data());
  for (size_t k = 0; k < SSRCL_FETCH_SLOTS; ++k) times.depthFetches += static_cast<unsigned>(counters[k]);
  times.iterationHistogram.assign(counters.begin() + SSRCL_FETCH_SLOTS, counters.end());
  while (!times.iterationHistogram.empty() && times.iterationHistogram.back() == 0)
    times.iterationHistogram.pop_back();
}

}  // namespace ssrcl::detail
