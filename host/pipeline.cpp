#include "ssrcl/pipeline.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <glm/gtc/matrix_inverse.hpp>

#include "device_impl.hpp"
#include "environment_fill.hpp"
#include "kernel_args.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl {
namespace {

using detail::roundUp;
using detail::setArgs;
using detail::toFloat16RowMajor;

constexpr std::array<const char*, 6> kInputNames = {"color", "depth", "normal", "roughness", "base", "specular"};

// Mirror SSRCL_FETCH_SLOTS and the histogram in kernels/trace.cl.
constexpr size_t kFetchSlots = 1024;
constexpr size_t kHistogramBins = 33;
// Mirror SSRCL_TILE in kernels/common.cl (the 2D work-group size) and ray_count in kernels/setup.cl.
constexpr int kTile = 8;
constexpr size_t kRayCounts = 4;

// Mirrors HzbLevel in kernels/common.cl.
struct HzbLevel {
  cl_int offset, width, height, pad;
};

std::vector<HzbLevel> hzbLevels(int width, int height) {
  std::vector<HzbLevel> levels;
  int offset = 0, w = width, h = height;
  for (;;) {
    levels.push_back({offset, w, h, 0});
    offset += w * h;
    if (w == 1 && h == 1) break;
    w = (w + 1) / 2;
    h = (h + 1) / 2;
  }
  return levels;
}

double eventMs(const cl::Event& e) {
  auto start = e.getProfilingInfo<CL_PROFILING_COMMAND_START>();
  auto end = e.getProfilingInfo<CL_PROFILING_COMMAND_END>();
  return (end - start) * 1e-6;
}

}  // namespace

struct Pipeline::Impl {
  Device device;
  std::map<std::string, const Image*> inputs;
  Camera camera;
  bool hasCamera = false;
  TraceSettings settings;

  bool committed = false;
  int width = 0, height = 0, colorChannels = 0, tilesX = 0, tilesY = 0;
  std::vector<HzbLevel> levels;

  cl::Kernel setup, hzbReduce, colorReduce, thickness, trace, accumulate, finalize, denoise;
  cl::Buffer colorIn, depthIn, normalIn, roughnessIn, baseIn, specularIn;
  bool hasBase = false;
  cl::Buffer hzb, levelBuffer, positions, normals, colorPyramid, pixelRays, rayList, tileList, rayCount;
  cl::Buffer surfaceExtent, surfaceThickness;  // adaptive thickness: row runs and chords, then thickness
  cl::Buffer accRadiance, accWeight, resolvedRgba, resolvedDistance, outRgba, outDistance;
  cl::Buffer rayHit, rayRadiance;  // one batch of ray records; sized on first use
  int batchCapacity = 0;
  cl::Buffer workCounters;  // counting mode: kFetchSlots texel-read sums, then kHistogramBins
  size_t fixedBytes = 0;    // everything but the ray records

  Image reflection, distance;
  StageTimes times;
  const EnvironmentMap* environment = nullptr;  // environment fill (host/environment_fill.cpp)
  detail::EnvironmentFill environmentFill;

  explicit Impl(const Device& d) : device(d) {}

  bool hasInput(const std::string& name) const {
    auto it = inputs.find(name);
    return it != inputs.end() && !it->second->empty();
  }
  void validateSettings() const;
  void validate();
  void allocate();
  int samplesPerBatch() const;
  size_t rayRecordBytes(int samples) const;
  int batchSize();
  void run();
  cl::CommandQueue& queue() { return device.impl().queue; }
};

Pipeline::Pipeline(const Device& device) : impl_(std::make_unique<Impl>(device)) {}
Pipeline::~Pipeline() = default;
Pipeline::Pipeline(Pipeline&&) noexcept = default;
Pipeline& Pipeline::operator=(Pipeline&&) noexcept = default;

void Pipeline::setImage(const std::string& name, const Image& image) {
  if (std::find(kInputNames.begin(), kInputNames.end(), name) == kInputNames.end())
    throw Error(ErrorCode::InvalidArgument,
                "unknown input image '" + name + "' (expected color, depth, normal, roughness, base or specular)");
  impl_->inputs[name] = &image;
  impl_->committed = false;
}

void Pipeline::setGBuffer(const GBuffer& gbuffer) {
  setImage("color", gbuffer.color);
  setImage("depth", gbuffer.depth);
  setImage("normal", gbuffer.normal);
  if (!gbuffer.roughness.empty()) setImage("roughness", gbuffer.roughness);
  if (!gbuffer.base.empty()) setImage("base", gbuffer.base);
  if (!gbuffer.specular.empty()) setImage("specular", gbuffer.specular);
}

void Pipeline::setCamera(const Camera& camera) {
  impl_->camera = camera;
  impl_->hasCamera = true;
  impl_->committed = false;
}

TraceSettings& Pipeline::settings() { return impl_->settings; }

void Pipeline::setEnvironment(const EnvironmentMap& environment) {
  if (!environment.empty()) detail::EnvironmentFill::validate(environment);
  impl_->environment = environment.empty() ? nullptr : &environment;
  impl_->committed = false;
}

void Pipeline::Impl::validateSettings() const {
  const TraceSettings& s = settings;
  if (!(s.thicknessRelative > 0.0f) || !std::isfinite(s.thicknessRelative))
    throw Error(ErrorCode::InvalidArgument, "parameter thickness must be a positive number");
  if (!(s.thicknessScale > 0.0f) || !std::isfinite(s.thicknessScale))
    throw Error(ErrorCode::InvalidArgument, "parameter thickness-scale must be a positive number");
  if (!(s.thicknessMinRelative > 0.0f && s.thicknessMinRelative <= s.thicknessMaxRelative) ||
      !std::isfinite(s.thicknessMaxRelative))
    throw Error(ErrorCode::InvalidArgument,
                "parameters thickness-min and thickness-max must be positive numbers, min <= max");
  if (!(s.glossyHitRoughness >= 0.0f && s.glossyHitRoughness <= 1.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter glossy-hit-roughness must be in [0, 1]");
  if (s.maxIterations < 1) throw Error(ErrorCode::InvalidArgument, "parameter max-iterations must be at least 1");
  if (!(s.maxRoughness >= 0.0f)) throw Error(ErrorCode::InvalidArgument, "parameter max-roughness must be >= 0");
  if (!(s.edgeFade >= 0.0f && s.edgeFade <= 0.5f))
    throw Error(ErrorCode::InvalidArgument, "parameter edge-fade must be in [0, 0.5]");
  if (!(s.environmentIntensity >= 0.0f && s.environmentIntensity <= 1e6f))
    throw Error(ErrorCode::InvalidArgument, "parameter environment-intensity must be in [0, 1e6]");
  if (!std::isfinite(s.environmentRotation))
    throw Error(ErrorCode::InvalidArgument, "parameter environment-rotation must be a finite number of degrees");
  if (std::isnan(s.constantRoughness)) throw Error(ErrorCode::InvalidArgument, "parameter roughness is NaN");
  if (s.samplesPerPixel < 1 || s.samplesPerPixel > 65536)
    throw Error(ErrorCode::InvalidArgument, "parameter spp must be in [1, 65536]");
  if (!(s.fullRaysRoughness >= 0.0f && s.fullRaysRoughness <= 1.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter full-rays-roughness must be in [0, 1]");
  if (!(s.mirrorRoughness >= 0.0f && s.mirrorRoughness <= 1.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter mirror-roughness must be in [0, 1]");
  if (s.reuseRadius < 0 || s.reuseRadius > 8)
    throw Error(ErrorCode::InvalidArgument, "parameter reuse-radius must be in [0, 8]");
  if (!(s.linearStepPixels >= 0.05f && s.linearStepPixels <= 8.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter linear-step must be in [0.05, 8] pixels");
  if (s.traceStride != 1 && s.traceStride != 2)
    throw Error(ErrorCode::InvalidArgument, "parameter trace-stride must be 1 or 2");
  if (s.traceStride == 2 && s.reuseRadius < 1)
    throw Error(ErrorCode::InvalidArgument,
                "parameter trace-stride 2 needs reuse-radius >= 1 (untraced pixels borrow rays)");
}

void Pipeline::Impl::validate() {
  if (!hasCamera) throw Error(ErrorCode::InvalidArgument, "pipeline: no camera set");
  validateCamera(camera, "camera");
  validateSettings();
  const TraceSettings& s = settings;

  const bool needRoughness = s.constantRoughness < 0.0f;
  const std::array<int, 6> expectedChannels = {3, 1, 3, 1, 3, 3};
  if (hasInput("base") != hasInput("specular"))
    throw Error(ErrorCode::InvalidArgument, "pipeline: input images 'base' and 'specular' go together");
  for (size_t k = 0; k < kInputNames.size(); ++k) {
    const std::string name = kInputNames[k];
    if (!hasInput(name)) {
      if ((name == "roughness" && !needRoughness) || name == "base" || name == "specular") continue;
      throw Error(ErrorCode::InvalidArgument, "pipeline: input image '" + name + "' not set");
    }
    const Image& img = *inputs.at(name);
    bool channelsOk = name == "color" ? (img.channels == 3 || img.channels == 4) : img.channels == expectedChannels[k];
    if (!channelsOk)
      throw Error(ErrorCode::InvalidArgument,
                  "pipeline: input image '" + name + "' has " + std::to_string(img.channels) + " channels");
    if (img.width != camera.width || img.height != camera.height)
      throw Error(ErrorCode::InvalidInput, "pipeline: input image '" + name + "' is " + std::to_string(img.width) +
                                               "x" + std::to_string(img.height) + " but the camera is " +
                                               std::to_string(camera.width) + "x" + std::to_string(camera.height));
    if (img.data.size() != size_t(img.width) * img.height * img.channels)
      throw Error(ErrorCode::InvalidArgument,
                  "pipeline: input image '" + name + "' data size does not match its shape");
  }
}

void Pipeline::Impl::allocate() {
  const cl::Program& program = device.impl().program();
  const cl::Context& ctx = device.impl().context;
  width = camera.width;
  height = camera.height;
  colorChannels = inputs.at("color")->channels;
  hasBase = hasInput("base");
  levels = hzbLevels(width, height);
  tilesX = (width + kTile - 1) / kTile;
  tilesY = (height + kTile - 1) / kTile;
  const size_t pixels = size_t(width) * height;
  const size_t hzbSize = size_t(levels.back().offset) + 1;

  setup = cl::Kernel(program, "setup");
  hzbReduce = cl::Kernel(program, "hzb_reduce");
  colorReduce = cl::Kernel(program, "color_reduce");
  thickness = cl::Kernel(program, "surface_thickness");
  trace = cl::Kernel(program, "trace_rays");
  accumulate = cl::Kernel(program, "resolve_accumulate");
  finalize = cl::Kernel(program, "resolve_finalize");
  denoise = cl::Kernel(program, "denoise");

  // Sizes first: a frame the device cannot hold fails here with the sizes named, not later with an
  // OpenCL status from whichever buffer or kernel meets the limit first.
  struct Planned {
    cl::Buffer* buffer;
    cl_mem_flags flags;
    size_t bytes;
  };
  const std::vector<Planned> plan = {
      {&colorIn, CL_MEM_READ_ONLY, pixels * colorChannels * sizeof(float)},
      {&depthIn, CL_MEM_READ_ONLY, pixels * sizeof(float)},
      {&normalIn, CL_MEM_READ_ONLY, pixels * 3 * sizeof(float)},
      {&roughnessIn, CL_MEM_READ_ONLY, pixels * sizeof(float)},
      {&baseIn, CL_MEM_READ_ONLY, hasBase ? pixels * 3 * sizeof(float) : 4},
      {&specularIn, CL_MEM_READ_ONLY, hasBase ? pixels * 3 * sizeof(float) : 4},
      {&hzb, CL_MEM_READ_WRITE, hzbSize * sizeof(float)},
      {&workCounters, CL_MEM_READ_WRITE, (kFetchSlots + kHistogramBins) * sizeof(cl_int)},
      {&positions, CL_MEM_READ_WRITE, pixels * sizeof(cl_float4)},
      {&normals, CL_MEM_READ_WRITE, pixels * sizeof(cl_float4)},
      {&colorPyramid, CL_MEM_READ_WRITE, hzbSize * sizeof(cl_float4)},
      {&pixelRays, CL_MEM_READ_WRITE, pixels * sizeof(cl_int)},
      {&rayList, CL_MEM_READ_WRITE, pixels * sizeof(cl_int)},
      {&tileList, CL_MEM_READ_WRITE, size_t(tilesX) * tilesY * sizeof(cl_int)},
      {&rayCount, CL_MEM_READ_WRITE, kRayCounts * sizeof(cl_int)},
      {&surfaceExtent, CL_MEM_READ_WRITE, pixels * sizeof(cl_float2)},
      {&surfaceThickness, CL_MEM_READ_WRITE, pixels * sizeof(float)},
      {&accRadiance, CL_MEM_READ_WRITE, pixels * sizeof(cl_float4)},
      {&accWeight, CL_MEM_READ_WRITE, pixels * sizeof(cl_float2)},
      {&resolvedRgba, CL_MEM_READ_WRITE, pixels * sizeof(cl_float4)},
      {&resolvedDistance, CL_MEM_READ_WRITE, pixels * sizeof(float)},
      {&outRgba, CL_MEM_WRITE_ONLY, pixels * sizeof(cl_float4)},
      {&outDistance, CL_MEM_WRITE_ONLY, pixels * sizeof(float)},
  };
  const size_t records = rayRecordBytes(samplesPerBatch());  // each of the two, allocated at execute()
  fixedBytes = 0;
  size_t largest = records;
  for (const Planned& b : plan) {
    fixedBytes += std::max<size_t>(b.bytes, 4);
    largest = std::max(largest, b.bytes);
  }
  if (environment) fixedBytes += detail::EnvironmentFill::deviceBytes(*environment);
  detail::checkDeviceMemory(device.impl(), largest, fixedBytes + 2 * records,
                            "a " + std::to_string(width) + "x" + std::to_string(height) + " frame");
  for (const Planned& b : plan) *b.buffer = cl::Buffer(ctx, b.flags, std::max<size_t>(b.bytes, 4));
  if (environment) environmentFill.upload(ctx, program, *environment);
  levelBuffer =
      cl::Buffer(ctx, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, levels.size() * sizeof(HzbLevel), levels.data());
  batchCapacity = 0;
  reflection = Image(width, height, 4);
  distance = Image(width, height, 1);
}

void Pipeline::commit() {
  impl_->validate();
  try {
    impl_->allocate();
  } catch (const cl::Error& e) {
    detail::rethrowClError(e, "allocating device buffers for " + std::to_string(impl_->camera.width) + "x" +
                                  std::to_string(impl_->camera.height));
  }
  impl_->committed = true;
}

// Samples traced per pass: all of them when the ray records fit in kRayRecordBudget, else fewer
// passes' worth at a time (the resolve accumulates across passes, so the result is the same).
int Pipeline::Impl::samplesPerBatch() const {
  constexpr size_t kRayRecordBudget = size_t(512) << 20;
  const size_t perSample = 2 * rayRecordBytes(1);
  const int fit = static_cast<int>(std::max<size_t>(1, kRayRecordBudget / perSample));
  return std::min(settings.samplesPerPixel, fit);
}

// One of the two ray-record buffers (hit, radiance) for `samples` samples of every pixel.
size_t Pipeline::Impl::rayRecordBytes(int samples) const {
  return size_t(width) * height * sizeof(cl_float4) * size_t(samples);
}

int Pipeline::Impl::batchSize() {
  const int batch = samplesPerBatch();
  if (batch > batchCapacity) {
    const cl::Context& ctx = device.impl().context;
    rayHit = cl::Buffer(ctx, CL_MEM_READ_WRITE, rayRecordBytes(batch));
    rayRadiance = cl::Buffer(ctx, CL_MEM_READ_WRITE, rayRecordBytes(batch));
    batchCapacity = batch;
  }
  return batch;
}

void Pipeline::Impl::run() {
  validateSettings();
  cl::CommandQueue& q = queue();
  const size_t pixels = size_t(width) * height;
  const cl_int2 size = {{width, height}};
  const cl::NDRange local2d(kTile, kTile);
  const cl::NDRange global2d(roundUp(width, kTile), roundUp(height, kTile));
  const TraceSettings& s = settings;

  // Normals go to view space with the inverse transpose, which stays right for scaled views.
  const glm::dmat3 normalMatrix = glm::inverseTranspose(glm::dmat3(camera.view));
  const cl_float16 normalMatrix16 = toFloat16RowMajor(glm::dmat4(normalMatrix));
  const cl_float16 proj = toFloat16RowMajor(camera.projection);
  const cl_float16 invProj = toFloat16RowMajor(glm::inverse(camera.projection));
  const float nearPlane = static_cast<float>(camera.nearPlane);
  const float farPlane = static_cast<float>(std::min(camera.farPlane, double(std::numeric_limits<float>::max())));
  const cl_int mapping = s.roughnessMapping == RoughnessMapping::Linear ? 1 : 0;
  const cl_int tracer = s.tracer == Tracer::Linear ? 1 : s.tracer == Tracer::DDA ? 2 : 0;
  const cl_uint seed = s.seed;
  const int batch = batchSize();
  // Each ray's cone covers its share of the lobe among all N rays the resolve combines: a
  // reflected GGX lobe spans about 2 alpha, so a share is a cone of half-angle 2 alpha / sqrt(N).
  const int reused = s.samplesPerPixel * (2 * s.reuseRadius + 1) * (2 * s.reuseRadius + 1);
  const float coneScale = s.prefilter ? 2.0f / std::sqrt(float(reused)) : 0.0f;

  std::vector<cl::Event> uploads(4);
  const bool useRoughnessImage = s.constantRoughness < 0.0f;
  q.enqueueWriteBuffer(colorIn, CL_FALSE, 0, pixels * colorChannels * sizeof(float), inputs.at("color")->data.data(),
                       nullptr, &uploads[0]);
  q.enqueueWriteBuffer(depthIn, CL_FALSE, 0, pixels * sizeof(float), inputs.at("depth")->data.data(), nullptr,
                       &uploads[1]);
  q.enqueueWriteBuffer(normalIn, CL_FALSE, 0, pixels * 3 * sizeof(float), inputs.at("normal")->data.data(), nullptr,
                       &uploads[2]);
  q.enqueueFillBuffer(rayCount, cl_int(0), 0, kRayCounts * sizeof(cl_int), nullptr, &uploads[3]);
  if (s.countWork) {
    uploads.emplace_back();
    q.enqueueFillBuffer(workCounters, cl_int(0), 0, (kFetchSlots + kHistogramBins) * sizeof(cl_int), nullptr,
                        &uploads.back());
  }
  if (hasBase) {
    for (const auto& [buffer, name] : {std::pair{&baseIn, "base"}, std::pair{&specularIn, "specular"}}) {
      uploads.emplace_back();
      q.enqueueWriteBuffer(*buffer, CL_FALSE, 0, pixels * 3 * sizeof(float), inputs.at(name)->data.data(), nullptr,
                           &uploads.back());
    }
  }
  if (useRoughnessImage) {
    uploads.emplace_back();
    q.enqueueWriteBuffer(roughnessIn, CL_FALSE, 0, pixels * sizeof(float), inputs.at("roughness")->data.data(), nullptr,
                         &uploads.back());
  }

  // HZB level 0 and colour pyramid level 0 start at offset 0 of their buffers.
  setArgs(setup, size, nearPlane, farPlane, normalMatrix16, invProj, colorIn, colorChannels, depthIn, normalIn,
          roughnessIn, useRoughnessImage ? -1.0f : s.constantRoughness, s.maxRoughness, s.mirrorRoughness,
          cl_int(s.samplesPerPixel), s.fullRaysRoughness, cl_int(s.traceStride), cl_int(s.classifyWork),
          s.thicknessRelative, cl_int(s.thicknessModel == ThicknessModel::Adaptive), positions, hzb, normals,
          colorPyramid, pixelRays, rayList, tileList, rayCount, surfaceThickness);
  cl::Event setupEvent;
  q.enqueueNDRangeKernel(setup, cl::NullRange, global2d, local2d, nullptr, &setupEvent);

  std::vector<cl::Event> hzbEvents(levels.size() - 1), colorEvents(levels.size() - 1);
  for (size_t l = 1; l < levels.size(); ++l) {
    const cl::NDRange levelRange(roundUp(levels[l].width, 8), roundUp(levels[l].height, 8));
    setArgs(hzbReduce, hzb, levelBuffer, static_cast<cl_int>(l));
    q.enqueueNDRangeKernel(hzbReduce, cl::NullRange, levelRange, local2d, nullptr, &hzbEvents[l - 1]);
    setArgs(colorReduce, colorPyramid, levelBuffer, static_cast<cl_int>(l));
    q.enqueueNDRangeKernel(colorReduce, cl::NullRange, levelRange, local2d, nullptr, &colorEvents[l - 1]);
  }

  std::vector<cl::Event> thicknessEvents;
  if (s.thicknessModel == ThicknessModel::Adaptive) {
    for (cl_int axis = 0; axis < 2; ++axis) {
      setArgs(thickness, size, axis, positions, s.thicknessScale, s.thicknessMinRelative,
              s.thicknessMaxRelative, surfaceExtent, surfaceThickness);
      thicknessEvents.emplace_back();
      q.enqueueNDRangeKernel(thickness, cl::NullRange, cl::NDRange(roundUp(axis ? width : height, 16)),
                             cl::NDRange(16), nullptr, &thicknessEvents.back());
    }
  }

  cl_int counts[kRayCounts] = {};  // listed pixels, rays, listed tiles, pixels with rays
  q.enqueueReadBuffer(rayCount, CL_TRUE, 0, sizeof(counts), counts);
  const cl_int listed = counts[0], tiles = counts[2];
  const cl::NDRange tileRange(size_t(tiles) * kTile, kTile);

  std::vector<cl::Event> traceEvents, resolveEvents;
  for (int first = 0; tiles > 0 && first < s.samplesPerPixel; first += batch) {
    // Tiles can hold reflecting pixels with no ray of their own (strided tracing): the resolve
    // still runs, to start their sums.
    if (listed > 0) {
      setArgs(trace, size, proj, invProj, nearPlane, farPlane, hzb, levelBuffer, static_cast<cl_int>(levels.size()),
              positions, normals, rayList, listed, pixelRays, cl_int(batch), cl_int(first), seed, s.mirrorRoughness,
              mapping, coneScale, tracer, s.linearStepPixels, surfaceThickness, s.maxIterations, s.edgeFade,
              cl_int(s.countWork), workCounters, colorPyramid, s.glossyHitRoughness,
              cl_int(hasBase), baseIn,
              specularIn, rayHit, rayRadiance);
      traceEvents.emplace_back();
      q.enqueueNDRangeKernel(trace, cl::NullRange, cl::NDRange(roundUp(size_t(listed) * batch, 64)), cl::NDRange(64),
                             nullptr, &traceEvents.back());
    }
    setArgs(accumulate, size, tileList, cl_int(tilesX), invProj, positions, normals, pixelRays, cl_int(batch),
            cl_int(first), s.mirrorRoughness, mapping, cl_int(s.reuseRadius), rayHit, rayRadiance, accRadiance,
            accWeight);
    resolveEvents.emplace_back();
    q.enqueueNDRangeKernel(accumulate, cl::NullRange, tileRange, local2d, nullptr, &resolveEvents.back());
  }
  // The resolve and filter write the listed tiles only; the rest of the pass is cleared.
  if (tiles < tilesX * tilesY) {
    resolveEvents.emplace_back();
    q.enqueueFillBuffer(outRgba, cl_float4{{0, 0, 0, 0}}, 0, pixels * sizeof(cl_float4), nullptr,
                        &resolveEvents.back());
    resolveEvents.emplace_back();
    q.enqueueFillBuffer(outDistance, 0.0f, 0, pixels * sizeof(float), nullptr, &resolveEvents.back());
  }
  cl::Event denoiseEvent;
  if (tiles > 0) {
    // With the filter on, the resolve writes to an intermediate the filter reads.
    setArgs(finalize, size, tileList, cl_int(tilesX), accRadiance, accWeight, s.denoise ? resolvedRgba : outRgba,
            s.denoise ? resolvedDistance : outDistance);
    resolveEvents.emplace_back();
    q.enqueueNDRangeKernel(finalize, cl::NullRange, tileRange, local2d, nullptr, &resolveEvents.back());
    if (s.denoise) {
      setArgs(denoise, size, tileList, cl_int(tilesX), s.mirrorRoughness, positions, normals, pixelRays, resolvedRgba,
              resolvedDistance, outRgba, outDistance);
      q.enqueueNDRangeKernel(denoise, cl::NullRange, tileRange, local2d, nullptr, &denoiseEvent);
    }
  }

  // Environment fill (host/environment_fill.cpp): the lobe the screen did not hold takes the environment.
  cl::Event environmentEvent;
  if (environment) environmentEvent = environmentFill.enqueue(q, size, camera.view, s, positions, normals, outRgba);

  std::vector<cl::Event> downloads(2);
  q.enqueueReadBuffer(outRgba, CL_FALSE, 0, pixels * sizeof(cl_float4), reflection.data.data(), nullptr, &downloads[0]);
  q.enqueueReadBuffer(outDistance, CL_FALSE, 0, pixels * sizeof(float), distance.data.data(), nullptr, &downloads[1]);
  q.finish();

  auto sum = [](const std::vector<cl::Event>& events) {
    double ms = 0;
    for (const auto& e : events) ms += eventMs(e);
    return ms;
  };
  times.tracedRays = counts[1];
  times.depthFetches = 0;
  times.iterationHistogram.clear();
  if (s.countWork) {
    std::vector<cl_int> counters(kFetchSlots + kHistogramBins);
    q.enqueueReadBuffer(workCounters, CL_TRUE, 0, counters.size() * sizeof(cl_int), counters.data());
    for (size_t k = 0; k < kFetchSlots; ++k) times.depthFetches += static_cast<unsigned>(counters[k]);
    times.iterationHistogram.assign(counters.begin() + kFetchSlots, counters.end());
    while (!times.iterationHistogram.empty() && times.iterationHistogram.back() == 0)
      times.iterationHistogram.pop_back();
  }
  times.tracedPixels = counts[3];
  times.resolvedTiles = tiles;
  times.ms.clear();
  times.ms["upload"] = sum(uploads);
  times.ms["setup"] = eventMs(setupEvent);
  times.ms["hzb"] = sum(hzbEvents);
  times.ms["color_mips"] = sum(colorEvents);
  times.ms["thickness"] = sum(thicknessEvents);
  times.ms["trace"] = sum(traceEvents);
  times.ms["resolve"] = sum(resolveEvents);
  times.ms["denoise"] = s.denoise && tiles > 0 ? eventMs(denoiseEvent) : 0.0;
  times.ms["environment"] = environment ? eventMs(environmentEvent) : 0.0;
  times.ms["download"] = sum(downloads);
}

void Pipeline::execute() {
  if (!impl_->committed) throw Error(ErrorCode::InvalidArgument, "pipeline: execute() before commit()");
  try {
    impl_->run();
  } catch (const cl::Error& e) {
    detail::rethrowClError(e, "executing the SSR pipeline");
  }
}

const Image& Pipeline::output(const std::string& name) const {
  if (name == "reflection") return impl_->reflection;
  if (name == "distance") return impl_->distance;
  throw Error(ErrorCode::InvalidArgument, "unknown output image '" + name + "' (expected reflection or distance)");
}

const StageTimes& Pipeline::stageTimes() const { return impl_->times; }

size_t Pipeline::deviceBytes() const { return impl_->fixedBytes + 2 * impl_->rayRecordBytes(impl_->batchCapacity); }

std::vector<Image> Pipeline::readHzb() const {
  if (!impl_->committed) throw Error(ErrorCode::InvalidArgument, "pipeline: readHzb() before commit()");
  std::vector<Image> mips;
  try {
    for (const HzbLevel& l : impl_->levels) {
      mips.emplace_back(l.width, l.height, 1);
      impl_->queue().enqueueReadBuffer(impl_->hzb, CL_TRUE, l.offset * sizeof(float),
                                       mips.back().data.size() * sizeof(float), mips.back().data.data());
    }
  } catch (const cl::Error& e) {
    detail::rethrowClError(e, "reading the HZB");
  }
  return mips;
}

}  // namespace ssrcl
