#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "output_form_options.hpp"
#include "ssrcl/io.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

// How `trace` and `batch` read one frame: where each pass and channel is, in which conventions
// (a --renderer preset, then each option given alone), where the camera is, and the check
// that the declared conventions fit the passes.
struct GBufferInputOptions {
  GBufferSource source;     // layer, channel names and pass files; `file` is set per frame
  std::optional<float> roughness;  // --roughness: TraceSettings::constantRoughness
  std::string renderer = "blender";
  std::string depthKind, normalSpace;  // empty: the renderer's
  std::optional<double> fov;  // --fov: completes a header camera with a pose and no projection (Karma's)
  bool inputCheck = true;
  OutputFormOptions form;  // names the material passes its glossy-pass form reads
  // The options a preset must not override once given (set by addChannelOptions).
  CLI::Option *layerOption = nullptr, *colorOption = nullptr, *depthOption = nullptr, *normalOption = nullptr;

  GBufferSource sourceFor(const std::string& file) const;
  // `settings` with the constant roughness applied, as the pipeline wants it.
  TraceSettings applyTo(TraceSettings settings) const;
};

// --renderer, --layer, --*-channel(s), --position, --depth-kind, --normal-space, --fov, --roughness,
// --no-input-check
void addChannelOptions(CLI::App& cmd, GBufferInputOptions& o);
// --color, --depth, --normal, --roughness-file, --position-file: passes read from files of their own
void addPassFileOptions(CLI::App& cmd, GBufferInputOptions& o);

// shot.exr -> shot.camera.json beside it.
std::string sidecarCameraPath(const std::string& exr);

// A frame ready for the pipeline: planar depth, world normals, the camera of its data window.
struct Frame {
  GBuffer gbuffer;
  Camera camera;
  ExrWindows windows;    // the input's, for the output
  Camera displayCamera;  // the camera of the display window, written into the output's header
  std::string cameraSource;  // the camera file, or which header attributes it came from
};

// Reads a frame's passes and its camera: the JSON at `cameraPath`, or, when that file does not
// exist and `headerFallback` is set (it is the default sidecar), the camera in the EXR header.
// The camera describes the display window; the frame covers the data window. Runs the input
// check unless disabled, then converts to the pipeline's conventions. Errors name the file.
Frame loadFrame(const GBufferInputOptions& o, const std::string& input, const std::string& cameraPath,
                bool headerFallback);

// Gives the pipeline a frame's images and camera; `frame` must stay alive until execute() is done.
void setFrame(Pipeline& pipeline, const Frame& frame);

// Auxiliary views (--view): G-buffers of the same scene from other cameras, read with the input's
// channel options (not its separate pass files or material passes). Each view's camera is
// cameras[k] when given, else its sidecar, else its EXR header. Errors name the view's file.
// The input's options as views are read with: no separate pass files, glossy or material passes.
GBufferInputOptions viewInputOptions(const GBufferInputOptions& o);
struct Views {
  std::vector<std::string> files;
  std::vector<Frame> frames;
};
Views loadViews(const GBufferInputOptions& o, const std::vector<std::string>& files,
                const std::vector<std::string>& cameras);
// --view (help `viewHelp`) and --view-camera.
void addViewOptions(CLI::App& cmd, std::vector<std::string>& files, std::vector<std::string>& cameras,
                    const std::string& viewHelp);
// Gives the pipeline the views, labelled by their files; `views` must stay alive until execute().
void setViews(Pipeline& pipeline, const Views& views);
// Adds them after the pipeline's views, rendered at `time` (ViewTime::Other: neighbouring frames).
void addViews(Pipeline& pipeline, const Views& views, ViewTime time);

}  // namespace ssrcl::cli
