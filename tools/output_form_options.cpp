#include "output_form_options.hpp"

#include "gbuffer_input.hpp"

namespace ssrcl::cli {

void addOutputFormOptions(CLI::App& cmd, OutputFormOptions& o) {
  const char* g = "Output";
  cmd.add_option("--output-form", o.form,
                 "incident: radiance before the specular colour; glossy-pass: times the lobe's directional albedo "
                 "with the Fresnel (F0 from --f0-channels, or base colour + metallic), as Cycles' Glossy "
                 "Direct + Indirect. Default: glossy-pass where a --renderer blender file holds the base_color and "
                 "metallic AOVs (or material options are given), else incident (said on stderr)")
      ->group(g)
      ->check(CLI::IsMember({"incident", "glossy-pass"}));
  // Material passes: the glossy-pass form's Fresnel, and in either form the hits on glossy pixels.
  cmd.add_option("--f0-channels", o.f0Channels, "Specular colour at normal incidence, e.g. F0.R,F0.G,F0.B")
      ->group(g);
  cmd.add_option("--base-color-channels", o.baseColorChannels,
                 "Principled base colour (default: the layer's base_color AOV, R,G,B)")
      ->group(g);
  cmd.add_option("--metallic-channel", o.metallicChannel,
                 "Principled metallic (default: the layer's metallic AOV, X)")
      ->group(g);
  cmd.add_option("--material", o.materialFile, "Read those material passes from this EXR instead")->group(g);
}

namespace {

// Sets the form and returns the line saying why (empty where no preset chose it).
std::string settle(OutputFormOptions& form, const OutputFormChoice& chosen) {
  form.form = outputFormName(chosen.form);
  if (chosen.why.empty()) return "";
  if (chosen.form == OutputForm::GlossyPass)
    return "ssrcl: output form glossy-pass (as Cycles' Glossy Direct + Indirect, Fresnel included): " + chosen.why +
           "; --output-form incident gives the radiance before the Fresnel\n";
  return "ssrcl: output form incident: the radiance reaching the surface over its specular lobe, before the Fresnel "
         "that Cycles' Glossy Direct + Indirect keep (several times brighter than them on dielectrics); " +
         chosen.why +
         ": add a base_color (Color) and a metallic (Value) AOV fed from each Principled BSDF (the ssrcl Blender "
         "add-on's Set Up does) for the glossy-pass form\n";
}

}  // namespace

std::string settleOutputForm(GBufferInputOptions& in, const std::string& file) {
  if (!in.form.form.empty()) return "";
  return settle(in.form, chooseOutputForm(in.sourceFor(file, "")));
}

std::string settleOutputForm(GBufferInputOptions& in, const Frame& frame) {
  if (!in.form.form.empty()) return "";
  return settle(in.form, {frame.outputForm, frame.outputFormWhy});
}

std::size_t toOutputForm(const OutputFormOptions& o, Image& reflection, const GBuffer& gbuffer, const Camera& camera,
                         std::optional<float> constantRoughness) {
  if (o.resolved() != OutputForm::GlossyPass) return 0;
  return applyGlossyPassForm(reflection, gbuffer, camera, constantRoughness);
}

}  // namespace ssrcl::cli
