#include "output_form_options.hpp"

namespace ssrcl::cli {

void addOutputFormOptions(CLI::App& cmd, OutputFormOptions& o) {
  const char* g = "Output";
  cmd.add_option("--output-form", o.form,
                 "incident: radiance before the specular colour; glossy-pass: times the lobe's directional albedo "
                 "with the Fresnel (F0 from --f0-channels, or base colour + metallic), as Cycles' Glossy "
                 "Direct + Indirect")
      ->group(g)
      ->check(CLI::IsMember({"incident", "glossy-pass"}))
      ->capture_default_str();
  cmd.add_option("--f0-channels", o.f0Channels, "glossy-pass: specular colour at normal incidence, e.g. F0.R,F0.G,F0.B")
      ->group(g);
  cmd.add_option("--base-color-channels", o.baseColorChannels,
                 "glossy-pass: Principled base colour (default: the layer's base_color AOV, R,G,B)")
      ->group(g);
  cmd.add_option("--metallic-channel", o.metallicChannel,
                 "glossy-pass: Principled metallic (default: the layer's metallic AOV, X)")
      ->group(g);
  cmd.add_option("--material", o.materialFile, "glossy-pass: read those passes from this EXR instead")->group(g);
}

void toOutputForm(const OutputFormOptions& o, Image& reflection, const GBuffer& gbuffer, const Camera& camera,
                  std::optional<float> constantRoughness) {
  if (o.resolved() == OutputForm::GlossyPass) applyGlossyPassForm(reflection, gbuffer, camera, constantRoughness);
}

}  // namespace ssrcl::cli
