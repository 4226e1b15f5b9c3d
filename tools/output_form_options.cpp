#include "output_form_options.hpp"

#include "gbuffer_input.hpp"
#include "renderer_presets.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::cli {

void OutputFormOptions::nameMaterialPasses(GBufferSource& source) const {
  if (resolved() != OutputForm::GlossyPass) {
    if (!f0Channels.empty() || !baseColorChannels.empty() || !metallicChannel.empty() || !materialFile.empty())
      throw Error(ErrorCode::InvalidArgument,
                  "--f0-channels, --base-color-channels, --metallic-channel and --material only apply with "
                  "--output-form glossy-pass");
    return;
  }
  source.materialFile = materialFile;
  if (!f0Channels.empty()) {
    if (!baseColorChannels.empty() || !metallicChannel.empty())
      throw Error(ErrorCode::InvalidArgument,
                  "give --f0-channels or --base-color-channels/--metallic-channel, not both");
    source.f0Channels = f0Channels;
    return;
  }
  const std::string prefix = source.layer.empty() ? "" : source.layer + ".";
  source.baseColorChannels = !baseColorChannels.empty()
                                 ? baseColorChannels
                                 : prefix + "base_color.R," + prefix + "base_color.G," + prefix + "base_color.B";
  source.metallicChannel = !metallicChannel.empty() ? metallicChannel
                           : prefix.empty()        ? std::string("metallic")
                                                   : prefix + "metallic.X";
}

void addOutputFormOptions(CLI::App& cmd, OutputFormOptions& o) {
  const char* g = "Output";
  cmd.add_option("--output-form", o.form,
                 "incident: radiance before the specular colour; glossy-pass: times the lobe's directional albedo "
                 "with the Fresnel (F0 from --f0-channels, or base colour + metallic), as Cycles' Glossy "
                 "Direct + Indirect. Default: glossy-pass where a --renderer blender file holds the base_color and "
                 "metallic AOVs (or material options are given), else incident (said on stderr)")
      ->group(g)
      ->check(CLI::IsMember({"incident", "glossy-pass"}));
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

void settleOutputForm(GBufferInputOptions& in, const std::string& file, std::ostream* tell) {
  OutputFormOptions& o = in.form;
  if (!o.form.empty()) return;
  const bool named = !o.f0Channels.empty() || !o.baseColorChannels.empty() || !o.metallicChannel.empty() ||
                     !o.materialFile.empty();
  const bool byDefault = rendererPreset(in.renderer).glossyPassByDefault;
  if (named || !byDefault) {  // naming the material passes asks for the form that reads them
    o.form = named ? "glossy-pass" : "incident";
    return;
  }
  GBufferInputOptions probe = in;
  probe.form.form = outputFormName(OutputForm::GlossyPass);
  const DefaultOutputForm chosen = defaultOutputForm(probe.sourceFor(file));
  o.form = outputFormName(chosen.form);
  if (!tell) return;
  if (chosen.form == OutputForm::GlossyPass)
    *tell << "ssrcl: output form glossy-pass (as Cycles' Glossy Direct + Indirect, Fresnel included): " << chosen.why
          << "; --output-form incident gives the radiance before the Fresnel\n";
  else
    *tell << "ssrcl: output form incident: the radiance reaching the surface over its specular lobe, before the "
             "Fresnel that Cycles' Glossy Direct + Indirect keep (several times brighter than them on dielectrics); "
          << chosen.why
          << ": add a base_color (Color) and a metallic (Value) AOV fed from each Principled BSDF (the ssrcl Blender "
             "add-on's Set Up does) for the glossy-pass form\n";
}

void toOutputForm(const OutputFormOptions& o, Image& reflection, const GBuffer& gbuffer, const Camera& camera,
                  std::optional<float> constantRoughness) {
  if (o.resolved() == OutputForm::GlossyPass) applyGlossyPassForm(reflection, gbuffer, camera, constantRoughness);
}

}  // namespace ssrcl::cli
