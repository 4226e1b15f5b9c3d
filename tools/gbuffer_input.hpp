#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "output_form_options.hpp"
#include "ssrcl/frame.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

// How `trace` and `batch` read one frame (ssrcl::loadFrame): where each pass and channel is, in
// which conventions (a --renderer preset, then each option given alone), where the camera is,
// and the check that the declared conventions fit the passes.
struct GBufferInputOptions {
  FrameSource source;  // what the options set; `file` and `camera` are set per frame
  std::optional<float> roughness;  // --roughness: TraceSettings::constantRoughness
  OutputFormOptions form;  // names the material passes its glossy-pass form reads

  // The frame of `file` with `camera` (empty: its sidecar, else its EXR header).
  FrameSource sourceFor(const std::string& file, const std::string& camera) const;
  // `settings` with the constant roughness applied, as the pipeline wants it.
  TraceSettings applyTo(TraceSettings settings) const;
};

// --renderer, --layer, --*-channel(s), --position, --depth-kind, --normal-space, --fov, --roughness,
// --no-input-check
void addChannelOptions(CLI::App& cmd, GBufferInputOptions& o);
// --color, --depth, --normal, --roughness-file, --position-file: passes read from files of their own
void addPassFileOptions(CLI::App& cmd, GBufferInputOptions& o);

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
