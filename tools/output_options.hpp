#pragma once
#include <CLI/CLI.hpp>
#include <string>

#include "gbuffer_input.hpp"
#include "ssrcl/exr_output.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

// How `trace` and `batch` write a pass: --output-layer, --append, --half, --compression.
struct OutputOptions {
  std::string layer;  // given or not: see layerWritten()
  CLI::Option* layerOption = nullptr;
  bool append = false, half = false;
  std::string compression;  // empty: zip, or the appended file's

  // The layer given; else "" (plain R,G,B,A,distance), or "reflection" when appending, as the
  // input's own R,G,B,A would collide with plain names.
  std::string layerWritten() const;
};

void addOutputOptions(CLI::App& cmd, OutputOptions& o);

// How a pass was made, recorded in its `ssrcl/*` attributes.
struct OutputRecord {
  std::string preset;  // --quality
  TraceSettings settings;
  std::string device;
  std::string outputForm = "incident";  // --output-form
  std::string environment;              // --environment file, "" without
  std::vector<std::string> views;       // --view files
  std::vector<std::string> temporal;    // the frames the pass was blended with (batch --temporal)
};

// The writer's options for one frame traced from `input` (the G-buffer file: appended to with
// --append, its header carried over otherwise) with `source`'s passes.
ReflectionExrOptions writerOptions(const OutputOptions& o, const OutputRecord& record, const std::string& input,
                                   const GBufferSource& source, const Frame& frame);

}  // namespace ssrcl::cli
