#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "device_option.hpp"
#include "exit_codes.hpp"
#include "settings_options.hpp"
#include "ssrcl/ssrcl.hpp"

namespace ssrcl::cli {
namespace {

struct TraceOptions {
  std::string input, output, camera, device;
  GBufferSource source;
  float roughness = -1.0f;
  SettingsOptions settings;
  bool stats = false;
};

// shot.exr -> shot.camera.json beside it.
std::string sidecarCamera(const std::string& exr) {
  std::filesystem::path p(exr);
  return (p.parent_path() / (p.stem().string() + ".camera.json")).string();
}

int runTrace(TraceOptions& o) {
  if (o.input.empty() && (o.source.colorFile.empty() || o.source.depthFile.empty() || o.source.normalFile.empty()))
    throw Error(ErrorCode::InvalidArgument, "trace: give a G-buffer EXR, or each of --color, --depth and --normal");
  o.source.file = o.input;
  if (o.roughness >= 0.0f) o.source.constantRoughness = o.roughness;
  const std::string cameraPath =
      !o.camera.empty() ? o.camera : sidecarCamera(o.input.empty() ? o.source.colorFile : o.input);
  std::error_code ec;
  if (std::filesystem::equivalent(o.output, o.input.empty() ? o.source.colorFile : o.input, ec))
    throw Error(ErrorCode::InvalidArgument, o.output + ": refusing to overwrite the input G-buffer");

  GBuffer g = loadGBuffer(o.source);
  Camera camera = loadCameraJson(cameraPath);
  if (camera.width != g.depth.width || camera.height != g.depth.height)
    throw Error(ErrorCode::InvalidInput, cameraPath + ": camera is " + std::to_string(camera.width) + "x" +
                                             std::to_string(camera.height) + " but the G-buffer is " +
                                             std::to_string(g.depth.width) + "x" + std::to_string(g.depth.height));

  Device device = openDevice(o.device);
  Pipeline pipeline(device);
  pipeline.setImage("color", g.color);
  pipeline.setImage("depth", g.depth);
  pipeline.setImage("normal", g.normal);
  if (!g.roughness.empty()) pipeline.setImage("roughness", g.roughness);
  pipeline.setCamera(camera);
  pipeline.settings() = o.settings.resolve();
  pipeline.settings().constantRoughness = o.roughness;
  pipeline.commit();
  pipeline.execute();

  try {
    writeReflectionExr(o.output, pipeline.output("reflection"), pipeline.output("distance"));
  } catch (const Error& e) {
    std::cerr << "ssrcl: " << e.what() << "\n";
    return kExitOutput;
  }
  if (o.stats) {
    const StageTimes& t = pipeline.stageTimes();
    std::cerr << "device: " << device.info().name << "\n"
              << "pixels traced: " << t.tracedPixels << " of " << size_t(camera.width) * camera.height
              << ", rays: " << t.tracedRays << "\n";
    for (const auto& [stage, ms] : t.ms)
      std::cerr << "  " << std::left << std::setw(9) << stage << std::right << std::fixed << std::setprecision(3)
                << std::setw(10) << ms << " ms\n";
  }
  return kExitOk;
}

}  // namespace

Action addTraceCommand(CLI::App& app) {
  auto o = std::make_shared<TraceOptions>();
  CLI::App* cmd = app.add_subcommand("trace", "Compute the reflection pass of one G-buffer");
  cmd->add_option("input", o->input, "G-buffer EXR (Blender multilayer by default)");
  cmd->add_option("-o,--output", o->output, "Output EXR: R,G,B,A (premultiplied, A = confidence), distance")
      ->required();
  cmd->add_option("--camera", o->camera, "Camera JSON (default: <input stem>.camera.json beside the input)");
  cmd->add_option("--device", o->device, "OpenCL device: index from `ssrcl devices`, cpu, gpu or default");
  auto* in = "Input channels";
  cmd->add_option("--layer", o->source.layer,
                  "Layer prefix of the default channel names; \"\" for plain R,G,B / Z / N.X")
      ->group(in)
      ->capture_default_str();
  cmd->add_option("--color", o->source.colorFile, "Read color from this EXR instead")->group(in);
  cmd->add_option("--depth", o->source.depthFile, "Read depth from this EXR instead")->group(in);
  cmd->add_option("--normal", o->source.normalFile, "Read normals from this EXR instead")->group(in);
  cmd->add_option("--roughness-file", o->source.roughnessFile, "Read roughness from this EXR instead")->group(in);
  cmd->add_option("--color-channels", o->source.colorChannels, "Color channel names, e.g. R,G,B")->group(in);
  cmd->add_option("--depth-channel", o->source.depthChannel, "Depth channel name (planar view depth)")->group(in);
  cmd->add_option("--normal-channels", o->source.normalChannels, "World-space normal channels, e.g. N.X,N.Y,N.Z")
      ->group(in);
  cmd->add_option("--roughness-channel", o->source.roughnessChannel, "Roughness channel name")->group(in);
  cmd->add_option("--roughness", o->roughness, "Constant roughness for every pixel instead of a channel")
      ->group(in)
      ->check(CLI::Range(0.0f, 1.0f));
  addSettingsOptions(*cmd, o->settings);
  cmd->add_flag("--stats", o->stats, "Print per-stage device times (OpenCL profiling) to stderr");
  return [o] { return runTrace(*o); };
}

}  // namespace ssrcl::cli
