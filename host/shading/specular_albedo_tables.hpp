#pragma once
// E's tables (ssrcl/specular_albedo.hpp), integrated at build time by
// specular_albedo_tables_gen.cpp: 17,794 integrals of 4,096 samples each, ~1.4 s of CPU that
// every process reading a glossy-pass frame spent before its first pixel when they were
// integrated at run time. Entries are (scale, bias).
#include <algorithm>

#include "ssrcl_shared.h"

namespace ssrcl::detail {

// specularAlbedo's table: roughness (alpha = roughness^2) in 1/64 steps, cos(theta_o) in 1/256.
constexpr int kAlbedoRoughSteps = 64, kAlbedoCosSteps = 256;
extern const double kSpecularAlbedoRows[kAlbedoRoughSteps + 1][kAlbedoCosSteps + 1][2];

// The trace kernel's table (ssrcl_shared.h): sqrt(alpha) rows, sqrt(cos theta_o) columns, exact at
// its nodes rather than read from the table above.
extern const double kSpecularAlbedoNodes[SSRCL_ALBEDO_STEPS + 1][SSRCL_ALBEDO_STEPS + 1][2];

// Where each table's entry (r, c) is integrated: (cos theta_o, alpha), cos 0 being the grazing
// limit nudged inside, and the kernel's alpha 0 likewise.
inline void albedoRowArgs(int r, int c, double* cosO, double* alpha) {
  const double rough = double(r) / kAlbedoRoughSteps, cosine = double(c) / kAlbedoCosSteps;
  *cosO = std::max(cosine, 1e-4);
  *alpha = rough * rough;
}
inline void albedoNodeArgs(int r, int c, double* cosO, double* alpha) {
  const double sqrtAlpha = double(r) / SSRCL_ALBEDO_STEPS, sqrtCos = double(c) / SSRCL_ALBEDO_STEPS;
  *cosO = std::max(sqrtCos * sqrtCos, 1e-4);
  *alpha = std::max(sqrtAlpha * sqrtAlpha, 1e-4);
}

}  // namespace ssrcl::detail
