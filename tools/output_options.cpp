#include "output_options.hpp"

#include <nlohmann/json.hpp>

#include "ssrcl/version.hpp"

namespace ssrcl::cli {

std::string OutputOptions::layerWritten() const {
  if (layerOption && layerOption->count() > 0) return layer;
  return append ? "reflection" : "";
}

void addOutputOptions(CLI::App& cmd, OutputOptions& o) {
  const char* g = "Output";
  o.layerOption = cmd.add_option("--output-layer", o.layer,
                                 "Write NAME.R, NAME.G, NAME.B, NAME.A, NAME.distance (default: plain names; "
                                 "\"reflection\" with --append)")
                      ->group(g);
  cmd.add_flag("--append", o.append,
               "Write a copy of the input EXR (every channel and attribute) with the reflection layer added")
      ->group(g);
  cmd.add_flag("--half", o.half, "Half-float reflection channels (default: float)")->group(g);
  cmd.add_option("--compression", o.compression,
                 "EXR compression (default: " + defaultExrCompression() + ", or the input's with --append)")
      ->group(g)
      ->check(CLI::IsMember(exrCompressionNames()));
}

ReflectionExrOptions writerOptions(const OutputOptions& o, const OutputRecord& record, const std::string& input,
                                   const GBufferSource& source, const Frame& frame) {
  ReflectionExrOptions w;
  w.layer = o.layerWritten();
  w.half = o.half;
  w.compression = o.compression;
  (o.append ? w.appendTo : w.headerFrom) = input;
  w.windows = frame.windows;
  w.camera = frame.displayCamera;

  nlohmann::ordered_json inputs;
  inputs["gbuffer"] = input;
  const std::pair<const char*, const std::string*> passFiles[] = {
      {"color", &source.colorFile},         {"depth", &source.depthFile},
      {"normal", &source.normalFile},       {"roughness", &source.roughnessFile},
      {"position", &source.positionFile}};
  for (const auto& [pass, file] : passFiles)
    if (!file->empty()) inputs[pass] = *file;
  const std::pair<const char*, const std::string*> material[] = {{"f0_channels", &source.f0Channels},
                                                                 {"base_color_channels", &source.baseColorChannels},
                                                                 {"metallic_channel", &source.metallicChannel},
                                                                 {"material", &source.materialFile}};
  for (const auto& [what, value] : material)
    if (!value->empty()) inputs[what] = *value;
  if (!frame.gbuffer.backDepth.empty()) {  // where the thickness came from, for a rerun
    inputs["back_depth"] = !source.backDepthFile.empty() ? source.backDepthFile : input;
    if (!source.backDepthChannel.empty()) inputs["back_depth_channel"] = source.backDepthChannel;
  }
  inputs["camera"] = frame.cameraSource;
  if (!record.environment.empty()) inputs["environment"] = record.environment;
  if (!record.views.empty()) inputs["views"] = record.views;
  if (!record.temporal.empty()) inputs["temporal"] = record.temporal;
  w.attributes = {{"ssrcl/version", SSRCL_VERSION},
                  {"ssrcl/preset", record.preset},
                  {"ssrcl/output_form", record.outputForm},
                  {"ssrcl/settings", settingsJson(record.settings)},
                  {"ssrcl/seed", std::to_string(record.settings.seed)},
                  {"ssrcl/inputs", inputs.dump()},
                  {"ssrcl/device", record.device}};
  return w;
}

}  // namespace ssrcl::cli
