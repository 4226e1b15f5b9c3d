#pragma once
// The directional albedo E of the specular lobe Blender 3.4's Cycles renders for a Principled
// BSDF with the GGX distribution: what turns the reflection pass (incident radiance averaged over
// the lobe, docs/outputs.md) into Cycles' Glossy Direct + Indirect, which keep the Fresnel inside.
//
//   E(o) = integral of D G1(o) G1(l) F(o.h) / (4 n.o) over l   (separable Smith, as Cycles 3.4)
//   F    = F0 (1 - FH) + FH,  FH = (Fd(o.h) - Fd(1)) / (1 - Fd(1))
// Fd is the dielectric Fresnel of the IOR Cycles derives from the Specular input, 1.5 at its
// default 0.5 (Fd(1) = 0.04); F0 is the specular colour at normal incidence. F is linear in F0,
// so E = F0 * scale + bias with two scalars per (roughness, angle).
#include <glm/vec3.hpp>

namespace ssrcl {

struct SpecularAlbedo {
  double scale = 0, bias = 0;
  double operator()(double f0) const { return f0 * scale + bias; }
};

// The integral for cos(theta_o) in (0, 1] and GGX alpha, by visible-normal quadrature on a
// strata x strata grid of stratum midpoints (deterministic; ~5e-5 at 128, ~2e-4 at 64).
SpecularAlbedo integrateSpecularAlbedo(double cosO, double alpha, int strata = 128);

// The same from a table over roughness (alpha = roughness^2, 1/64 steps) and cos(theta_o) (1/256
// steps) integrated at 64 strata when the library is built, read bilinearly. Inputs clamped to
// [0, 1]; cos 0 is the grazing limit.
SpecularAlbedo specularAlbedo(double roughness, double cosO);

// F0 of Cycles 3.4's Principled BSDF at Specular 0.5 and Specular Tint 0 (the defaults):
// mix(0.04, base colour, metallic), each clamped to [0, 1] (NaN reads as 0).
glm::dvec3 principledF0(const glm::dvec3& baseColor, double metallic);

}  // namespace ssrcl
