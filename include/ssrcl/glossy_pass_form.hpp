#pragma once
#include <cstddef>
#include <optional>
#include <string>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl {

// The two forms of the reflection pass (docs/outputs.md):
//   Incident    incident radiance averaged over the specular lobe, before any specular colour
//   GlossyPass  that times the lobe's directional albedo E(view, roughness, F0) (specular_albedo.hpp):
//               the quantity of Cycles' Glossy Direct + Indirect passes
enum class OutputForm { Incident, GlossyPass };
const char* outputFormName(OutputForm form);  // "incident", "glossy-pass": the --output-form values

// The form a G-buffer's pass takes when none is asked for: glossy-pass where the file holds the
// material passes `source` names (f0Channels, or baseColorChannels and metallicChannel, read from
// materialFile or else file), incident otherwise, and when it names none. `why` says which, in a
// clause naming the file and channels ("shot.exr holds ..." / "shot.exr has no ..."). Throws
// Error(IoError) naming the file when it is not a readable EXR.
struct DefaultOutputForm {
  OutputForm form = OutputForm::Incident;
  std::string why;
};
DefaultOutputForm defaultOutputForm(const GBufferSource& source);

// Turns a reflection pass (rgb premultiplied by A, as the pipeline writes it) into the glossy-pass
// form: rgb times E(view, roughness, F0) per pixel and channel, A unchanged. A pixel of pure metal
// (metallic pass >= 0.999, with base colour and metallic passes; not with an F0 pass, which does
// not tell metal from dielectric) takes its colour (over gbuffer.specular, Glossy Color, where
// given), A 1: its render holds no light but its glossy reflection, so that is the pass exactly;
// not where gbuffer.base (from the glossy passes) holds over 1% of the colour (a shader mixed in,
// emission). `gbuffer` holds the
// pipeline's conventions (planar depth, world normals) and either an F0 pass or base colour and
// metallic passes; `camera` is that of its pixels; constantRoughness, when set (as
// TraceSettings::constantRoughness), replaces the roughness pass. Throws Error(InvalidArgument) when the gbuffer has
// neither or constantRoughness is outside [0, 1]. Output finite for any input. Returns how many
// pixels took their colour.
std::size_t applyGlossyPassForm(Image& reflection, const GBuffer& gbuffer, const Camera& camera,
                                std::optional<float> constantRoughness);

}  // namespace ssrcl
