#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "ssrcl/glossy_pass_form.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::cli {

// --output-form and the material passes the glossy-pass form reads (README, Output).
struct OutputFormOptions {
  std::string form = "incident";
  std::string f0Channels, baseColorChannels, metallicChannel, materialFile;

  OutputForm resolved() const { return form == "glossy-pass" ? OutputForm::GlossyPass : OutputForm::Incident; }
};

void addOutputFormOptions(CLI::App& cmd, OutputFormOptions& o);

// The pass in the form asked for: unchanged for incident, else times E (applyGlossyPassForm).
void toOutputForm(const OutputFormOptions& o, Image& reflection, const GBuffer& gbuffer, const Camera& camera,
                  std::optional<float> constantRoughness);

}  // namespace ssrcl::cli
