#include "ssrcl/specular_albedo.hpp"

#include <algorithm>
#include <cmath>

#include "shading/specular_albedo_tables.hpp"

namespace ssrcl {

SpecularAlbedo specularAlbedo(double roughness, double cosO) {
  // NaN reads as rough and grazing, as the pipeline reads a NaN roughness.
  const double rClamped = std::isnan(roughness) ? 1.0 : std::clamp(roughness, 0.0, 1.0);
  const double cClamped = std::isnan(cosO) ? 0.0 : std::clamp(cosO, 0.0, 1.0);
  const double r = rClamped * detail::kAlbedoRoughSteps, c = cClamped * detail::kAlbedoCosSteps;
  const int r0 = std::min(int(r), detail::kAlbedoRoughSteps - 1), c0 = std::min(int(c), detail::kAlbedoCosSteps - 1);
  const double fr = r - r0, fc = c - c0;
  const auto& a = detail::kSpecularAlbedoRows[r0];
  const auto& b = detail::kSpecularAlbedoRows[r0 + 1];
  auto lerp = [](double x, double y, double t) { return x + t * (y - x); };
  auto at = [&](int field) {
    const double lo = lerp(a[c0][field], a[c0 + 1][field], fc), hi = lerp(b[c0][field], b[c0 + 1][field], fc);
    return lerp(lo, hi, fr);
  };
  return {at(0), at(1)};
}

glm::dvec3 principledF0(const glm::dvec3& baseColor, double metallic) {
  auto unit = [](double v) { return std::isnan(v) ? 0.0 : std::clamp(v, 0.0, 1.0); };
  const double m = unit(metallic);
  glm::dvec3 f0;
  for (int c = 0; c < 3; ++c) f0[c] = 0.04 * (1 - m) + unit(baseColor[c]) * m;  // 0.08 * Specular = 0.04
  return f0;
}

}  // namespace ssrcl
