// The pipeline orchestrates the stages (host/*_stage.cpp, one per kernels/*.cl file): commit plans
// and binds them, execute runs them in order.
#include "ssrcl/pipeline.hpp"

#include <cstring>

#include "color_pyramid_stage.hpp"
#include "environment_stage.hpp"
#include "filter_stage.hpp"
#include "frame_resources.hpp"
#include "back_pyramid_stage.hpp"
#include "host_backed_buffer.hpp"
#include "hzb_stage.hpp"
#include "image_views.hpp"
#include "io/conventions.hpp"
#include "pipeline_inputs.hpp"
#include "resolve_stage.hpp"
#include "settings_validation.hpp"
#include "setup_stage.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/specular_albedo.hpp"
#include "thickness_stage.hpp"
#include "trace_stage.hpp"
#include "view_stage.hpp"

namespace ssrcl {

using namespace detail;
static_assert(Pipeline::kMaxViews == SSRCL_MAX_VIEWS, "the API's view count is the kernels'");

struct Pipeline::Impl {
  Device device;
  PipelineInputs inputs;
  std::map<std::string, ImageView> outputViews;
  Camera camera;
  bool hasCamera = false;
  TraceSettings settings;
  ProgressMonitor progress;
  const EnvironmentMap* environment = nullptr;  // null: no environment fill
  bool environmentChanged = false;
  std::vector<ViewSource> views;

  // What the last commit planned: execute() replans when the settings differ.
  bool committed = false;  // false again after the camera, outputs or environment change
  bool configured = false;
  TraceSettings committedSettings;
  FrameShape frame;
  int colorChannels = 0;
  bool hasBase = false, hasMaterials = false, hasBackDepth = false;
  std::vector<float> hitF0;  // each pixel's F0 with material passes, packed for the trace
  std::map<std::string, PipelineInputs::Shape> committedInputs;  // new images of these shapes need no commit
  // Each view's images are uploaded and its setup, HZB, colours and thickness computed once, at
  // the first execute() after its setView or a commit that changed kernels or buffers: a batch's
  // frames share them, and replacing one view (a sliding window of frames) leaves the others.
  size_t committedViews = 0;

  DeviceBuffers buffers;
  FrameResources resources;  // the buffers the stages share, by role
  SetupStage setup;
  ThicknessStage thickness;
  HzbStage hzb;
  BackPyramidStage backPyramid;
  ColorPyramidStage colors;
  TraceStage trace;
  ResolveStage resolve;
  FilterStage filter;
  EnvironmentStage environmentFill;
  ViewStage viewStage;
  // The pipeline plans the outputs, clears what the resolve does not write and downloads them.
  static const StageAccess access;

  Image reflection, distance, view;
  StageTimes times;
  const char* stage = "setup";  // what run() is enqueuing: an OpenCL error names it

  explicit Impl(const Device& d) : device(d) {}
  void plan();
  void run();
  void drainQueue() noexcept;
  void report(double fraction);
  const float* packHitF0();
  static void download(cl::CommandQueue& q, const cl::Buffer& buffer, Image& image, bool hostMemory,
                       StageEvents& events);
};

const StageAccess Pipeline::Impl::access{"pipeline", {}, {Role::Reflection, Role::Distance, Role::ViewShare}};

// Each pixel's F0 for the trace's hits on glossy pixels: the "f0" image clamped to [0, 1], or
// Principled's from "base_color" and "metallic", as the glossy-pass form reads them.
const float* Pipeline::Impl::packHitF0() {
  const size_t pixels = frame.pixels();
  const bool given = inputs.has("f0");
  const float* color = inputs.pixels(given ? "f0" : "base_color");
  const float* metallic = given ? nullptr : inputs.pixels("metallic");
  hitF0.resize(3 * pixels);
  for (size_t i = 0; i < pixels; ++i) {
    const glm::dvec3 f0 =
        principledF0({color[3 * i], color[3 * i + 1], color[3 * i + 2]}, metallic ? metallic[i] : 1.0);
    for (int c = 0; c < 3; ++c) hitF0[3 * i + c] = float(f0[c]);
  }
  return hitF0.data();
}

// Whether `a` needs the stages configured and planned again after `b`: not for the seed alone,
// which run() hands the trace as it is (a batch blending its frames gives each its own seed).
namespace {
bool sameButSeed(TraceSettings a, const TraceSettings& b) {
  a.seed = b.seed;
  return a == b;
}
}  // namespace

// Validates, then configures the stages (kernels of the settings' variants), plans and allocates
// their buffers (reusing what an earlier commit allocated at the same sizes) and binds them.
void Pipeline::Impl::plan() {
  if (!hasCamera) throw Error(ErrorCode::InvalidArgument, "pipeline: no camera set");
  validateCamera(camera, "camera");
  validateSettings(settings);
  inputs.validate(camera, settings);
  for (size_t k = 0; k < views.size(); ++k) ViewStage::validate(views[k], static_cast<int>(k), settings);

  Device::Impl& d = DeviceAccess::impl(device);
  const int channels = inputs.view("color").channels;
  const bool base = inputs.has("base");
  const bool materials = inputs.has("f0") || inputs.has("base_color");
  const bool back = inputs.has("back_depth");
  const bool reconfigure = !configured || !sameButSeed(settings, committedSettings) || base != hasBase ||
                           materials != hasMaterials || back != hasBackDepth || environmentChanged ||
                           views.size() != committedViews;
  const int viewCount = static_cast<int>(views.size());
  if (reconfigure) {
    setup.configure(d);
    thickness.configure(d, settings, back);
    hzb.configure(d);
    backPyramid.configure(d, settings.tracer == Tracer::HiZ, back);
    colors.configure(d, settings);
    trace.configure(d, settings, base, materials, viewCount > 0, back);
    resolve.configure(d, settings, viewCount);
    viewStage.configure(d, settings, views.size());
    filter.configure(d, settings);
    environmentFill.configure(d, settings, environment);
    configured = true;
    environmentChanged = false;
  }
  const bool reshaped = frame.width != camera.width || frame.height != camera.height;
  frame = FrameShape(camera.width, camera.height);
  colorChannels = channels;
  hasBase = base;
  hasMaterials = materials;
  hasBackDepth = back;
  committedSettings = settings;
  committedInputs = inputs.shapes();
  committedViews = views.size();

  resources.beginPlan();
  setup.plan(resources, buffers, frame, colorChannels, !settings.constantRoughness, environment != nullptr);
  thickness.plan(resources, buffers, frame);
  hzb.plan(resources, buffers, frame);
  backPyramid.plan(resources, buffers, frame);
  colors.plan(resources, buffers, frame);
  trace.plan(resources, buffers, frame);
  resolve.plan(resources, buffers, frame);
  filter.plan(resources, buffers, frame);
  environmentFill.plan(buffers, frame);
  resources.plan(access, buffers, Role::Reflection, frame.pixels() * sizeof(cl_float4), CL_MEM_WRITE_ONLY);
  resources.plan(access, buffers, Role::Distance, frame.pixels() * sizeof(float), CL_MEM_WRITE_ONLY);
  viewStage.plan(buffers, views, frame.pixels() * size_t(trace.batchSize()));
  resources.plan(access, buffers, Role::ViewShare, viewCount > 0 ? frame.pixels() * sizeof(cl_float2) : 0,
                 CL_MEM_WRITE_ONLY);
  std::string what = "a " + std::to_string(frame.width) + "x" + std::to_string(frame.height) + " frame";
  for (size_t k = 0; k < views.size(); ++k)
    what += (k == 0 ? " with views " : ", ") + ViewStage::name(views[k], static_cast<int>(k)) + " (" +
            std::to_string(views[k].camera.width) + "x" + std::to_string(views[k].camera.height) + ")";
  buffers.check(d, what);  // before the outputs' images take memory of the frame's size
  // The outputs' images, which the device writes in place where it works in host memory.
  if (reflection.width != frame.width || reflection.height != frame.height) {
    reflection = Image(frame.width, frame.height, 4);
    distance = Image(frame.width, frame.height, 1);
  }
  if (viewCount == 0) view = Image();
  else if (view.width != frame.width || view.height != frame.height) view = Image(frame.width, frame.height, 2);
  buffers.placeIn(resources.write(access, Role::Reflection), reflection.data.data());
  buffers.placeIn(resources.write(access, Role::Distance), distance.data.data());
  buffers.placeIn(resources.write(access, Role::ViewShare), view.data.data());
  const bool reallocated = buffers.allocate(d, what);
  if (reconfigure || reallocated)
    for (ViewSource& v : views) v.prepared = false;
  // Views' cameras are written at bind: with views, every commit binds.
  if (!reconfigure && !reshaped && !reallocated && views.empty()) return;  // the same kernels and buffers, bound

  setup.bind(resources);
  thickness.bind(resources);
  hzb.bind(d.queue, resources);
  backPyramid.bind(resources);
  colors.bind(resources);
  trace.bind(resources);
  // With the square filter on, the resolve writes to an intermediate the filter reads.
  resolve.bind(resources, filter.readsResolved());
  filter.bind(resources);
  environmentFill.bind(d.queue, resources);
  viewStage.bind(d.queue, camera, views, resources);
}

void Pipeline::Impl::report(double fraction) {
  if (progress && !progress(fraction))
    throw Error(ErrorCode::Cancelled, "pipeline: execute() cancelled by the progress monitor");
}

// Before an error leaves commit() or execute(): the commands already enqueued read and write host
// memory in place on a CPU device (the caller's images, the pipeline's own), which the unwinding
// may free under them. A download that failed with the whole frame still in flight corrupted the
// heap as the CLI exited (test_opencl_faults, under load). A queue that cannot finish has nothing
// left to run.
void Pipeline::Impl::drainQueue() noexcept {
  try {
    DeviceAccess::impl(device).queue.finish();
  } catch (...) {
  }
}

// An output into its image: read back from a device's own memory; mapped where the device works
// in host memory (OpenCL asks for a map before the host reads there), copied only where the buffer
// is not the image itself (pixels off the device's alignment).
void Pipeline::Impl::download(cl::CommandQueue& q, const cl::Buffer& buffer, Image& image, bool hostMemory,
                              StageEvents& events) {
  const size_t bytes = image.data.size() * sizeof(float);
  if (!hostMemory) {
    q.enqueueReadBuffer(buffer, CL_FALSE, 0, bytes, image.data.data(), nullptr, newEvent(events, "download"));
    return;
  }
  void* mapped = q.enqueueMapBuffer(buffer, CL_TRUE, CL_MAP_READ, 0, bytes);
  if (mapped != image.data.data()) std::memcpy(image.data.data(), mapped, bytes);
  q.enqueueUnmapMemObject(buffer, mapped, nullptr, newEvent(events, "download"));
}

void Pipeline::Impl::run() {
  cl::CommandQueue& q = DeviceAccess::impl(device).queue;
  const TraceSettings& s = settings;
  const FrameConstants constants = frameConstants(frame, camera, s);  // every stage's parameters begin with it
  StageEvents events;
  const cl::Buffer& outRgba = resources.write(access, Role::Reflection);
  const cl::Buffer& outDistance = resources.write(access, Role::Distance);
  const cl::Buffer& outView = resources.write(access, Role::ViewShare);

  const bool roughnessImage = !s.constantRoughness;
  stage = "setup";
  setup.enqueue(q,
                {inputs.pixels("color"), inputs.pixels("depth"), inputs.pixels("normal"),
                 roughnessImage ? inputs.pixels("roughness") : nullptr},
                SetupStage::params(constants, s, colorChannels), events);
  trace.upload(q, hasBase ? inputs.pixels("base") : nullptr, hasBase ? inputs.pixels("specular") : nullptr,
               hasBase && hasMaterials ? packHitF0() : nullptr, events);
  stage = "hzb";
  hzb.enqueue(q, events);
  stage = "color_mips";
  colors.enqueue(q, events);
  stage = "thickness";
  thickness.enqueue(q, constants, s, hasBackDepth ? inputs.pixels("back_depth") : nullptr,
                    !detail::isPerspective(camera), events);
  stage = "hzb";
  backPyramid.enqueue(q, constants, events);
  stage = "views";
  viewStage.prepare(q, views, s, events);
  if (!views.empty()) viewStage.limitRadiance(inputs.pixels("color"), frame.pixels(), colorChannels, s.viewRadianceCap);
  stage = "setup";
  const SetupStage::Counts counts = setup.readCounts(q);
  const int tiles = counts.listedTiles, batch = trace.batchSize();
  report(0.1);

  TraceParams traceParams = TraceStage::params(constants, frame, s, hasBase);
  ResolveParams resolveParams = ResolveStage::params(constants, s, static_cast<int>(views.size()));
  traceParams.listed = counts.listedPixels;
  traceParams.batch_size = resolveParams.batch_size = batch;
  for (int first = 0; tiles > 0 && first < s.samplesPerPixel; first += batch) {
    traceParams.first_sample = resolveParams.first_sample = first;
    // Tiles can hold reflecting pixels with no ray of their own (strided tracing): the resolve
    // still runs, to start their sums.
    stage = "trace";
    if (counts.listedPixels > 0) {
      trace.enqueue(q, traceParams, events);
      // The frame's prefiltered hits are looked up before the views may replace doubtful ones.
      stage = "color_mips";
      colors.prefilterHits(q, traceParams, events);
      stage = "views";
      viewStage.trace(q, traceParams, events);
    }
    stage = "resolve";
    resolve.accumulate(q, resolveParams, tiles, events);
    if (progress) q.finish();  // the fraction reported is work done, not work queued
    report(0.1 + 0.85 * std::min(1.0, double(first + batch) / s.samplesPerPixel));
  }
  // The resolve and filter write the listed tiles only; the rest of the pass is cleared.
  if (tiles < frame.tilesX * frame.tilesY) {
    q.enqueueFillBuffer(outRgba, cl_float4{{0, 0, 0, 0}}, 0, frame.pixels() * sizeof(cl_float4), nullptr,
                        newEvent(events, "resolve"));
    q.enqueueFillBuffer(outDistance, 0.0f, 0, frame.pixels() * sizeof(float), nullptr, newEvent(events, "resolve"));
    if (!views.empty())
      q.enqueueFillBuffer(outView, cl_float2{{-1.0f, 0.0f}}, 0, frame.pixels() * sizeof(cl_float2), nullptr,
                          newEvent(events, "resolve"));
  }
  if (tiles > 0) resolve.finalize(q, resolveParams, tiles, events);
  stage = "filter";
  filter.enqueue(q, constants, tiles, events);
  stage = "environment";
  environmentFill.enqueue(q, constants, camera.view, s, events);
  stage = "download";
  const bool hostMemory = sharesHostMemory(DeviceAccess::impl(device));
  download(q, outRgba, reflection, hostMemory, events);
  download(q, outDistance, distance, hostMemory, events);
  if (!views.empty()) download(q, outView, view, hostMemory, events);
  q.finish();

  trace.readWork(q, times);
  times.tracedRays = counts.rays;
  times.tracedPixels = counts.tracedPixels;
  times.resolvedTiles = tiles;
  times.ms.clear();
  for (const char* stage :
       {"upload", "setup", "hzb", "color_mips", "thickness", "trace", "views", "resolve", "denoise", "environment",
        "download"})
    times.ms[stage] = 0.0;
  for (const auto& [stage, list] : events)
    for (const cl::Event& e : list) times.ms[stage] += eventMs(e);
  for (const auto& [name, view] : outputViews) writeView(name == "reflection" ? reflection : distance, view);
  report(1.0);
}

Pipeline::Pipeline(const Device& device) : impl_(std::make_unique<Impl>(device)) {}
Pipeline::~Pipeline() = default;
Pipeline::Pipeline(Pipeline&&) noexcept = default;
Pipeline& Pipeline::operator=(Pipeline&&) noexcept = default;

// A new image keeps the commit: execute() checks that the inputs still have the committed shapes.
void Pipeline::setImage(const std::string& name, const Image& image) { impl_->inputs.set(name, image); }

void Pipeline::setImage(const std::string& name, const ImageView& view) { impl_->inputs.set(name, view); }

void Pipeline::setOutput(const std::string& name, const ImageView& view) {
  const int channels = name == "reflection" ? 4 : name == "distance" ? 1 : 0;
  if (channels == 0)
    throw Error(ErrorCode::InvalidArgument, "unknown output image '" + name + "' (expected reflection or distance)");
  if (!emptyView(view) && view.channels != channels)
    throw Error(ErrorCode::InvalidArgument, "pipeline: output image '" + name + "' must have " +
                                                std::to_string(channels) + " channels, not " +
                                                std::to_string(view.channels));
  impl_->outputViews.erase(name);
  if (!emptyView(view)) impl_->outputViews[name] = view;
  impl_->committed = false;
}

void Pipeline::setGBuffer(const GBuffer& gbuffer) {
  // The optional passes too, empty or not: an empty image unsets its input, so a pipeline reused
  // for the next frame keeps none of the previous frame's (whose images may be gone by then).
  for (const auto& [name, image] : pipelinePasses(gbuffer)) setImage(name, *image);
}

void Pipeline::setView(int index, const GBuffer& gbuffer, const Camera& camera, const std::string& label,
                       ViewTime time) {
  if (index < 0 || index > viewCount() || index >= SSRCL_MAX_VIEWS)
    throw Error(ErrorCode::InvalidArgument, "pipeline: view index " + std::to_string(index) + " out of range (0.." +
                                                std::to_string(std::min(viewCount(), SSRCL_MAX_VIEWS - 1)) + ")");
  ViewSource source;
  source.inputs.set("color", gbuffer.color);
  source.inputs.set("depth", gbuffer.depth);
  source.inputs.set("normal", gbuffer.normal);
  if (!gbuffer.roughness.empty()) source.inputs.set("roughness", gbuffer.roughness);
  source.camera = camera;
  source.label = label;
  source.otherTime = time == ViewTime::Other;
  if (index == viewCount()) impl_->views.push_back(std::move(source));
  else impl_->views[index] = std::move(source);
  impl_->committed = false;
}

void Pipeline::clearViews() {
  impl_->views.clear();
  impl_->committed = false;
}

int Pipeline::viewCount() const { return static_cast<int>(impl_->views.size()); }

void Pipeline::setCamera(const Camera& camera) {
  impl_->camera = camera;
  impl_->hasCamera = true;
  impl_->committed = false;
}

TraceSettings& Pipeline::settings() { return impl_->settings; }

void Pipeline::setEnvironment(const EnvironmentMap& environment) {
  if (!environment.empty()) EnvironmentStage::validate(environment);
  impl_->environment = environment.empty() ? nullptr : &environment;
  impl_->environmentChanged = true;
  impl_->committed = false;
}

void Pipeline::setProgressMonitor(ProgressMonitor monitor) { impl_->progress = std::move(monitor); }

void Pipeline::commit() {
  impl_->committed = false;
  try {
    impl_->plan();
  } catch (const cl::Error& e) {
    impl_->drainQueue();
    rethrowClError(e, "allocating device buffers for " + std::to_string(impl_->camera.width) + "x" +
                          std::to_string(impl_->camera.height));
  } catch (...) {
    impl_->drainQueue();
    throw;
  }
  for (const auto& [name, view] : impl_->outputViews)
    if (view.width != impl_->camera.width || view.height != impl_->camera.height)
      throw Error(ErrorCode::InvalidInput, "pipeline: output image '" + name + "' is not the camera's size");
  impl_->committed = true;
}

void Pipeline::execute() {
  if (!impl_->committed)
    throw Error(ErrorCode::InvalidOperation,
                "pipeline: execute() before commit() (or the camera, an output or the environment changed since)");
  impl_->inputs.checkUnchanged(impl_->committedInputs);
  try {
    impl_->stage = "planning";
    if (!sameButSeed(impl_->settings, impl_->committedSettings))
      impl_->plan();  // settings changed after commit
    else
      impl_->inputs.validate(impl_->camera, impl_->settings);  // an Image's data may no longer fit its shape
    impl_->run();
  } catch (const cl::Error& e) {
    impl_->drainQueue();
    rethrowClError(e, std::string("executing the SSR pipeline (") + impl_->stage + " stage)");
  } catch (...) {
    impl_->drainQueue();
    throw;
  }
}

const Image& Pipeline::output(const std::string& name) const {
  if (name == "reflection") return impl_->reflection;
  if (name == "distance") return impl_->distance;
  if (name == "view") return impl_->view;
  throw Error(ErrorCode::InvalidArgument,
              "unknown output image '" + name + "' (expected reflection, distance or view)");
}

const StageTimes& Pipeline::stageTimes() const { return impl_->times; }

size_t Pipeline::deviceBytes() const { return impl_->buffers.bytes(); }

}  // namespace ssrcl
