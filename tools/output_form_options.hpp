#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <ostream>
#include <string>

#include "ssrcl/frame.hpp"
#include "ssrcl/glossy_pass_form.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::cli {

struct GBufferInputOptions;

// --output-form and the material passes the glossy-pass form reads (docs/outputs.md).
struct OutputFormOptions {
  std::string form;  // "incident" or "glossy-pass"; empty when not given, until settleOutputForm
  std::string f0Channels, baseColorChannels, metallicChannel, materialFile;

  OutputForm resolved() const { return form == "glossy-pass" ? OutputForm::GlossyPass : OutputForm::Incident; }
};

void addOutputFormOptions(CLI::App& cmd, OutputFormOptions& o);

// Settles an --output-form not given, for frames like `file`: glossy-pass where material options
// are given, or where the --renderer preset takes it by default (Blender) and `file` holds the
// material passes (defaultOutputForm); incident otherwise. For that preset, returns one line
// saying which and why (empty otherwise), for the caller to print once the frame has loaded, so
// that a refused input still gets a one-line error. Throws Error(IoError) for an unreadable `file`.
std::string settleOutputForm(GBufferInputOptions& in, const std::string& file);

// The same for one frame, from the form loadFrame chose for it (Frame::outputForm), so that its
// file is not opened a second time to choose.
std::string settleOutputForm(GBufferInputOptions& in, const Frame& frame);

// The pass in the form asked for: unchanged for incident, else times E (applyGlossyPassForm).
// Returns how many pure metal pixels took their colour there.
std::size_t toOutputForm(const OutputFormOptions& o, Image& reflection, const GBuffer& gbuffer, const Camera& camera,
                         std::optional<float> constantRoughness);

}  // namespace ssrcl::cli
