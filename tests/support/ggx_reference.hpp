#pragma once
// Textbook GGX (Trowbridge-Reitz, isotropic) in double precision, local frame with the normal = +Z,
// as the reference the kernels' float GGX is tested against (Walter et al. 2007; Heitz 2014, 2018).
#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace ssrcl::test::ggx {

constexpr double kPi = 3.14159265358979323846;

// NDF alpha^2 / (pi (cos^2 (alpha^2 - 1) + 1)^2), with cos^2 (alpha^2 - 1) + 1 written as
// alpha^2 cos^2 + sin^2 and sin^2 = h.x^2 + h.y^2, so it stays exact for alpha -> 0. h unit.
inline double ndf(const glm::dvec3& h, double alpha) {
  if (!(h.z > 0)) return 0;
  const double a2 = alpha * alpha;
  const double k = a2 * h.z * h.z + (h.x * h.x + h.y * h.y);
  return a2 / (kPi * k * k);
}

// Smith G1 = 1 / (1 + Lambda), Lambda = (sqrt(1 + alpha^2 tan^2) - 1) / 2. w unit.
inline double smithG1(const glm::dvec3& w, double alpha) {
  if (!(w.z > 0)) return 0;
  const double tan2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
  return 2.0 / (1.0 + std::sqrt(1.0 + alpha * alpha * tan2));
}

// Density (solid angle) of l = reflect(o) about h with h drawn from the visible normals of o,
// D_o(h) = G1(o) max(0, o.h) D(h) / o.z, times the reflection Jacobian 1 / (4 o.h):
// G1(o) D(h) / (4 o.z), h = normalize(o + l). Integrates to 1 over the whole sphere (l may point
// below the horizon). o, l unit.
inline double vndfReflectionPdf(const glm::dvec3& o, const glm::dvec3& l, double alpha) {
  const glm::dvec3 s = o + l;
  const double len = glm::length(s);
  if (!(len > 0) || !(o.z > 0)) return 0;
  return smithG1(o, alpha) * ndf(s / len, alpha) / (4.0 * o.z);
}

inline glm::dvec3 mirror(const glm::dvec3& o) { return {-o.x, -o.y, o.z}; }

}  // namespace ssrcl::test::ggx
