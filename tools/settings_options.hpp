#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

// The tracing knobs as command-line options: a --quality preset, then any knob given alone
// overrides that preset's value.
struct SettingsOptions {
  std::string quality = "medium";
  std::optional<float> maxRoughness, thickness, edgeFade, mirrorRoughness, linearStep, fullRaysRoughness;
  std::optional<int> maxIterations, spp, reuseRadius, traceStride;
  std::optional<uint32_t> seed;
  std::optional<std::string> roughnessMapping, tracer;
  std::optional<bool> prefilter, denoise;

  TraceSettings resolve() const;
};

void addSettingsOptions(CLI::App& cmd, SettingsOptions& o);

}  // namespace ssrcl::cli
