#pragma once
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "ssrcl/glossy_pass_form.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::cli {

// --output-form and the material passes the glossy-pass form reads (docs/outputs.md).
struct OutputFormOptions {
  std::string form = "incident";
  std::string f0Channels, baseColorChannels, metallicChannel, materialFile;

  OutputForm resolved() const { return form == "glossy-pass" ? OutputForm::GlossyPass : OutputForm::Incident; }
  // Names the material passes in `source` (whose layer is resolved): the F0 channels given, or
  // the base colour and metallic channels, by default Blender AOVs named base_color (colour) and
  // metallic (value). Throws Error(InvalidArgument) for material options without the glossy-pass form.
  void nameMaterialPasses(GBufferSource& source) const;
};

void addOutputFormOptions(CLI::App& cmd, OutputFormOptions& o);

// The pass in the form asked for: unchanged for incident, else times E (applyGlossyPassForm).
void toOutputForm(const OutputFormOptions& o, Image& reflection, const GBuffer& gbuffer, const Camera& camera,
                  std::optional<float> constantRoughness);

}  // namespace ssrcl::cli
