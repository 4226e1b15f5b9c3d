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
  std::optional<float> viewRadianceCap;
  std::optional<int> maxIterations, spp, reuseRadius, traceStride;
  std::optional<uint32_t> seed;
  std::optional<std::string> roughnessMapping, tracer, thicknessModel;
  std::optional<bool> prefilter, edgeColors, denoise, separableDenoise;
  std::string environment;  // --environment FILE.exr: misses take this HDR's radiance
  std::optional<float> environmentRotation, environmentIntensity;

  TraceSettings resolve() const;
  // The --environment map, prefiltered; empty without the option. Throws Error naming the file.
  EnvironmentMap loadEnvironment() const;
};

void addSettingsOptions(CLI::App& cmd, SettingsOptions& o);

// Sets the tracer by its option name (hiz, dda, linear). The step-by-step tracers march until the
// ray leaves the screen: maxIterations bounds Hi-Z's traversal, which spans a screen in ~log2 steps,
// and would cut DDA and linear rays short at that many pixels.
void selectTracer(TraceSettings& s, const std::string& name);

}  // namespace ssrcl::cli
