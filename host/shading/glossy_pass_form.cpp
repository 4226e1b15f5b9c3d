#include "ssrcl/glossy_pass_form.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>
#include <vector>

#include "shading/glossy_pass_form.hpp"
#include "io/exr_files.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/specular_albedo.hpp"
#include "pipeline/settings_validation.hpp"

namespace ssrcl {

const char* outputFormName(OutputForm form) { return form == OutputForm::GlossyPass ? "glossy-pass" : "incident"; }

DefaultOutputForm defaultOutputForm(const GBufferSource& source) {
  detail::ExrFiles files;
  return detail::defaultOutputForm(source, files);
}

DefaultOutputForm detail::defaultOutputForm(const GBufferSource& source, ExrFiles& files) {
  const std::string& file = source.materialFile.empty() ? source.file : source.materialFile;
  std::vector<std::string> passes = {source.f0Channels};  // each a channel list, alternatives kept apart
  if (source.f0Channels.empty()) passes = {source.baseColorChannels, source.metallicChannel};
  if (std::any_of(passes.begin(), passes.end(), [](const std::string& p) { return p.empty(); }))
    return {OutputForm::Incident, "no material passes are named"};
  if (file.empty()) return {OutputForm::Incident, "no file to read material passes from"};
  std::string held, missing;
  for (const std::string& p : passes) {
    std::string& list = files.holds(file, p) ? held : missing;
    list += (list.empty() ? "" : " and ") + p;
  }
  if (missing.empty()) return {OutputForm::GlossyPass, file + " holds " + held};
  return {OutputForm::Incident, file + " has no " + missing};
}

void applyGlossyPassForm(Image& reflection, const GBuffer& g, const Camera& camera,
                         std::optional<float> constantRoughness) {
  const bool fromF0 = !g.f0.empty(), fromBase = !g.baseColor.empty() && !g.metallic.empty();
  if (!fromF0 && !fromBase)
    throw Error(ErrorCode::InvalidArgument,
                "glossy-pass output form: needs an F0 pass, or base colour and metallic passes");
  detail::validateConstantRoughness(constantRoughness);
  const int w = reflection.width, h = reflection.height;
  const std::size_t pixels = std::size_t(w) * h;
  if (g.normal.data.size() != 3 * pixels || (!constantRoughness && g.roughness.data.size() != pixels) ||
      (fromF0 ? g.f0.data.size() != 3 * pixels
              : g.baseColor.data.size() != 3 * pixels || g.metallic.data.size() != pixels))
    throw Error(ErrorCode::InvalidArgument, "glossy-pass output form: the passes are not the reflection's size");

  // The view direction through each pixel, from two points on its ray (perspective and
  // orthographic alike, any depth layout), in world space.
  const glm::dmat4 inverseProjection = glm::inverse(camera.projection);
  const glm::dmat4 cameraToWorld = glm::inverse(camera.view);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const std::size_t i = std::size_t(y) * w + x;
      const glm::dvec3 nearPoint = cameraPointAt(inverseProjection, camera, x + 0.5, y + 0.5, 1.0);
      const glm::dvec3 farPoint = cameraPointAt(inverseProjection, camera, x + 0.5, y + 0.5, 2.0);
      const glm::dvec3 toEye = glm::dvec3(cameraToWorld * glm::dvec4(nearPoint - farPoint, 0.0));
      const glm::dvec3 n(g.normal.data[3 * i], g.normal.data[3 * i + 1], g.normal.data[3 * i + 2]);
      const double nLength = glm::length(n), eyeLength = glm::length(toEye);
      // Pixels without a usable normal have no reflection (rgb 0): any finite E keeps them so.
      const double cosO = std::isfinite(nLength) && nLength > 0 && eyeLength > 0
                              ? glm::dot(n, toEye) / (nLength * eyeLength)
                              : 0.0;
      const double roughness = constantRoughness ? *constantRoughness : g.roughness.data[i];
      const SpecularAlbedo e = specularAlbedo(roughness, cosO);
      // An F0 pass reads as metallic 1: F0 as given, clamped to [0, 1].
      const glm::dvec3 f0 =
          fromF0 ? principledF0({g.f0.data[3 * i], g.f0.data[3 * i + 1], g.f0.data[3 * i + 2]}, 1.0)
                 : principledF0({g.baseColor.data[3 * i], g.baseColor.data[3 * i + 1], g.baseColor.data[3 * i + 2]},
                                g.metallic.data[i]);
      for (int c = 0; c < 3; ++c) {
        float& v = reflection.data[i * reflection.channels + c];
        v = float(v * e(f0[c]));
      }
    }
}

}  // namespace ssrcl
