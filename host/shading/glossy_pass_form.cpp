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

namespace {

// Mixed (edge) pixels: Cycles writes the Normal pass as the mean over a pixel's samples and Depth
// from its first sample (kernels/setup.cl), so a pixel holding a floor and an object's edge has
// the depth of one and a normal shorter than 1 that faces neither. E read along that mean is
// neither surface's: at a grazing wet floor, where the Fresnel falls steeply with the angle, half
// the floor's, and it flips with the pixel's coverage from frame to frame. Its source is the
// surface its depth is on, as setup.cl's mixed_pixel_source picks it (whose lobe the environment
// fill reads): of the eight neighbours with a full-length normal whose plane passes within 1% of
// the depth of the pixel's point, the one nearest the mean in direction. Its share of the pixel
// is the mean's component along it (the rest taken at right angles to it: an object standing on
// or in front of a floor).
class MixedPixels {
 public:
  static constexpr double kFullNormal = 0.9, kOnPlane = 0.01;  // setup.cl's SSRCL_FULL_NORMAL, SSRCL_ON_PLANE

  MixedPixels(const GBuffer& g, const Camera& camera, const glm::dmat4& inverseProjection)
      : g_(g), camera_(camera), inverseProjection_(inverseProjection), w_(g.normal.width), h_(g.normal.height) {}

  glm::dvec3 normal(std::size_t i) const {
    return {g_.normal.data[3 * i], g_.normal.data[3 * i + 1], g_.normal.data[3 * i + 2]};
  }
  glm::dvec3 unitNormal(std::size_t i) const { return glm::normalize(normal(i)); }

  // The source neighbour's index of mixed pixel (x, y), or -1 (not mixed, or no neighbour explains it).
  int source(int x, int y) const {
    const std::size_t i = std::size_t(y) * w_ + x;
    const double length = glm::length(normal(i));
    if (!(length > 0 && length < kFullNormal) || g_.depth.data.size() != std::size_t(w_) * h_ ||
        !surface(g_.depth.data[i]))
      return -1;
    const glm::dvec3 mean = normal(i) / length, p = point(x, y);
    int best = -1;
    double bestShare = -INFINITY;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int qx = x + dx, qy = y + dy;
        if ((dx == 0 && dy == 0) || qx < 0 || qy < 0 || qx >= w_ || qy >= h_) continue;
        const std::size_t j = std::size_t(qy) * w_ + qx;
        const double lj = glm::length(normal(j));
        if (!surface(g_.depth.data[j]) || !(lj >= kFullNormal && lj <= 1 / kFullNormal)) continue;
        const glm::dvec3 nj = normal(j) / lj;
        const glm::dvec3 njView = glm::dvec3(camera_.view * glm::dvec4(nj, 0.0));
        if (!(std::abs(glm::dot(p - point(qx, qy), njView)) <= kOnPlane * -p.z)) continue;
        const double share = glm::dot(mean, nj);
        if (share > bestShare) best = int(j), bestShare = share;
      }
    return best;
  }

 private:
  // setup.cl's surface_depth: within the clip planes, short of the background's 1e10.
  bool surface(float d) const {
    return std::isfinite(d) && d >= camera_.nearPlane && d <= camera_.farPlane && d < 1e10f;
  }
  glm::dvec3 point(int x, int y) const {
    return cameraPointAt(inverseProjection_, camera_, x + 0.5, y + 0.5, g_.depth.data[std::size_t(y) * w_ + x]);
  }

  const GBuffer& g_;
  const Camera& camera_;
  const glm::dmat4& inverseProjection_;
  int w_, h_;
};

// A pixel of a pure metal (Principled metallic 1 over the whole pixel): it has no diffuse,
// subsurface, sheen or transmission lobe, so all the light its render shows is its glossy
// reflection (Blender: Combined = GlossDir + GlossInd + Emit), off-screen content and every bounce
// included: its glossy pass is its colour, exact where a screen-space trace only estimates it.
// Edge pixels that are partly metal (a metallic AOV under 1) keep the trace. Where the file has
// the glossy passes, its light that is not glossy (GBuffer::base) must be nil too: the AOV tells
// only of the first Principled BSDF (or a Glossy BSDF, metallic 1) of a material, which a Mix
// Shader may blend with a diffuse one, and an emissive metal's pass would hold its emission.
constexpr float kPureMetal = 0.999f;
constexpr double kNotGlossyShare = 0.01;  // of the colour: the passes' rounding, not light

bool pureMetalColor(const GBuffer& g, std::size_t i, double cosO, float rgb[3]) {
  if (g.metallic.data.empty() || !(g.metallic.data[i] >= kPureMetal) || !(cosO > 0) ||
      g.color.data.size() != 3 * g.metallic.data.size())
    return false;
  if (g.base.data.size() == g.color.data.size()) {
    double notGlossy = 0, all = 0;
    for (int c = 0; c < 3; ++c) notGlossy += std::abs(g.base.data[3 * i + c]), all += g.color.data[3 * i + c];
    if (!(notGlossy <= kNotGlossyShare * all)) return false;
  }
  // The form's quantity is Glossy Direct + Indirect: the colour over Glossy Color, which is 1 on a
  // Principled BSDF and a Glossy BSDF's own colour (the add-on marks those metallic 1 as well).
  const bool glossyColour = g.specular.data.size() == g.color.data.size();
  for (int c = 0; c < 3; ++c) {
    const float weight = glossyColour ? g.specular.data[3 * i + c] : 1.0f;
    if (!(weight > 1e-4f)) return false;  // a lobe that reflects nothing there: the pass has no value to give
    rgb[c] = g.color.data[3 * i + c] / weight;
    if (!std::isfinite(rgb[c])) return false;
    rgb[c] = std::clamp(rgb[c], 0.0f, 1e20f);  // the pass's radiance rule (kernels/common.cl sanitize_radiance)
  }
  return true;
}

}  // namespace

std::size_t applyGlossyPassForm(Image& reflection, const GBuffer& g, const Camera& camera,
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
  const MixedPixels mixed(g, camera, inverseProjection);
  std::size_t metals = 0;
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
      float metal[3];
      if (!fromF0 && pureMetalColor(g, i, cosO, metal)) {
        for (int c = 0; c < 3; ++c) reflection.data[i * reflection.channels + c] = metal[c];
        if (reflection.channels > 3) reflection.data[i * reflection.channels + 3] = 1.0f;  // all of it known
        ++metals;
        continue;
      }
      const SpecularAlbedo e = specularAlbedo(roughness, cosO);
      // A mixed pixel's E: its source surface's by that surface's share, the mean's for the rest.
      const int source = eyeLength > 0 ? mixed.source(x, y) : -1;
      double share = 0;
      SpecularAlbedo eSource = e;
      if (source >= 0) {
        const glm::dvec3 ns = mixed.unitNormal(std::size_t(source));
        share = std::clamp(glm::dot(n, ns), 0.0, 1.0);
        eSource = specularAlbedo(roughness, glm::dot(ns, toEye) / eyeLength);
      }
      // An F0 pass reads as metallic 1: F0 as given, clamped to [0, 1].
      const glm::dvec3 f0 =
          fromF0 ? principledF0({g.f0.data[3 * i], g.f0.data[3 * i + 1], g.f0.data[3 * i + 2]}, 1.0)
                 : principledF0({g.baseColor.data[3 * i], g.baseColor.data[3 * i + 1], g.baseColor.data[3 * i + 2]},
                                g.metallic.data[i]);
      for (int c = 0; c < 3; ++c) {
        float& v = reflection.data[i * reflection.channels + c];
        v = float(v * (share * eSource(f0[c]) + (1 - share) * e(f0[c])));
      }
    }
  return metals;
}

}  // namespace ssrcl
