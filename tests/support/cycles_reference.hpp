#pragma once
// Cycles' path-traced answer for the floor of a Blender sample (samples/blender), in the units of
// our reflection pass. Cycles' Glossy Direct + Indirect on a floor of F0 = `specular` is
//   specular * E(o, alpha) * (lobe-weighted mean incident radiance),
// E being GGX's directional albedo with the separable Smith term Cycles 3.4 uses, while our pass
// holds that mean times the found fraction A and nothing for the rest. The glossy sample's sky is
// invisible to glossy rays, so the rest is black there too and every floor pixel compares.
#include <string>
#include <utility>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::test {

struct CyclesFloorReference {
  GBuffer gbuffer;
  Camera camera;
  std::vector<int> floor;      // pixel indices: upward normal, a surface, Cycles' glossy colour 1
  std::vector<double> scale;   // per floor pixel: specular * E, what turns our rgb into Cycles'
  std::vector<double> cycles;  // per floor pixel, 3 channels: GlossDir + GlossInd
  double peak = 0;             // brightest Cycles channel on the floor
  // "floor" (every roughness stripe of more than 1000 pixels), then each stripe ("r=0.2500").
  std::vector<std::pair<std::string, std::vector<size_t>>> groups;
};

// Reads the sample and its camera sidecar (<stem>.camera.json beside it unless given).
CyclesFloorReference loadCyclesFloorReference(const std::string& exr, const std::string& cameraJson = {},
                                              double specular = 1.0);

// RMSE and mean |error| of specular * E * our rgb against Cycles over a group's floor pixels.
struct FloorError {
  double rmse = 0, meanAbs = 0;
};
FloorError floorError(const CyclesFloorReference& ref, const Image& reflection, const std::vector<size_t>& group);

// E(o) of single-scatter GGX with separable Smith shadowing, for cos(theta_o) and alpha.
double directionalAlbedoSeparable(double cosO, double alpha);

}  // namespace ssrcl::test
