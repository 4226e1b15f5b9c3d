#pragma once
#include <CLI/CLI.hpp>
#include <string>

#include "ssrcl/io.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

// How `trace` and `batch` read one frame: where each pass and channel is, the camera sidecar
// beside the EXR, and the checks that pair a camera with a G-buffer.
struct GBufferInputOptions {
  GBufferSource source;     // layer, channel names and pass files; `file` is set per frame
  float roughness = -1.0f;  // >= 0: this roughness everywhere, no roughness channel read

  GBufferSource sourceFor(const std::string& file) const;
  // `settings` with the constant roughness applied, as the pipeline wants it.
  TraceSettings applyTo(TraceSettings settings) const;
};

// --layer, --color-channels, --depth-channel, --normal-channels, --roughness-channel, --roughness
void addChannelOptions(CLI::App& cmd, GBufferInputOptions& o);
// --color, --depth, --normal, --roughness-file: passes read from files of their own
void addPassFileOptions(CLI::App& cmd, GBufferInputOptions& o);

// shot.exr -> shot.camera.json beside it.
std::string sidecarCameraPath(const std::string& exr);

// The camera at `path`, checked against the G-buffer's size; Error(InvalidInput) names the file.
Camera loadCameraFor(const std::string& path, const GBuffer& g);

// Gives the pipeline a frame's images and camera; `g` must stay alive until execute() is done.
void setFrame(Pipeline& pipeline, const GBuffer& g, const Camera& camera);

}  // namespace ssrcl::cli
