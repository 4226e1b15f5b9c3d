#include "gbuffer_input.hpp"

#include <filesystem>

#include "ssrcl/error.hpp"

namespace ssrcl::cli {

GBufferSource GBufferInputOptions::sourceFor(const std::string& file) const {
  GBufferSource s = source;
  s.file = file;
  if (roughness >= 0.0f) s.constantRoughness = roughness;
  return s;
}

TraceSettings GBufferInputOptions::applyTo(TraceSettings settings) const {
  settings.constantRoughness = roughness;
  return settings;
}

void addChannelOptions(CLI::App& cmd, GBufferInputOptions& o) {
  const char* in = "Input channels";
  cmd.add_option("--layer", o.source.layer, "Layer prefix of the default channel names; \"\" for plain R,G,B / Z / N.X")
      ->group(in)
      ->capture_default_str();
  cmd.add_option("--color-channels", o.source.colorChannels, "Color channel names, e.g. R,G,B")->group(in);
  cmd.add_option("--depth-channel", o.source.depthChannel, "Depth channel name (planar view depth)")->group(in);
  cmd.add_option("--normal-channels", o.source.normalChannels, "World-space normal channels, e.g. N.X,N.Y,N.Z")
      ->group(in);
  cmd.add_option("--roughness-channel", o.source.roughnessChannel, "Roughness channel name")->group(in);
  cmd.add_option("--roughness", o.roughness, "Constant roughness for every pixel instead of a channel")
      ->group(in)
      ->check(CLI::Range(0.0f, 1.0f));
}

void addPassFileOptions(CLI::App& cmd, GBufferInputOptions& o) {
  const char* in = "Input channels";
  cmd.add_option("--color", o.source.colorFile, "Read color from this EXR instead")->group(in);
  cmd.add_option("--depth", o.source.depthFile, "Read depth from this EXR instead")->group(in);
  cmd.add_option("--normal", o.source.normalFile, "Read normals from this EXR instead")->group(in);
  cmd.add_option("--roughness-file", o.source.roughnessFile, "Read roughness from this EXR instead")->group(in);
}

std::string sidecarCameraPath(const std::string& exr) {
  std::filesystem::path p(exr);
  return (p.parent_path() / (p.stem().string() + ".camera.json")).string();
}

Camera loadCameraFor(const std::string& path, const GBuffer& g) {
  Camera camera = loadCameraJson(path);
  if (camera.width != g.depth.width || camera.height != g.depth.height)
    throw Error(ErrorCode::InvalidInput, path + ": camera is " + std::to_string(camera.width) + "x" +
                                             std::to_string(camera.height) + " but the G-buffer is " +
                                             std::to_string(g.depth.width) + "x" + std::to_string(g.depth.height));
  return camera;
}

void setFrame(Pipeline& pipeline, const GBuffer& g, const Camera& camera) {
  pipeline.setGBuffer(g);
  pipeline.setCamera(camera);
}

}  // namespace ssrcl::cli
