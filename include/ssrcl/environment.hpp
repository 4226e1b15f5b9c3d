#pragma once
#include <string>
#include <vector>

#include "ssrcl/image.hpp"

namespace ssrcl {

// An equirectangular (latitude-longitude) HDR environment, prefiltered for GGX lobes: what fills
// the part of a reflection the screen does not hold (Pipeline::setEnvironment).
//
// Mapping: Blender's world mapping for an Environment Texture node with its default vector
// (Cycles' direction_to_equirectangular), world +Z up. A world direction d = (x, y, z) reads
//   u = 0.5 - atan2(y, x) / (2 pi)        (u = 0 the left column: +X at the centre, +Y at u = 0.25)
//   v = 0.5 - atan2(z, hypot(x, y)) / pi  (v = 0 the top row, as EXR stores it: +Z at the top)
// TraceSettings::environmentRotation (degrees about +Z) reads d rotated by that angle first, as a
// Mapping node (Rotation Z) between Texture Coordinate "Generated" and the texture would.
struct EnvironmentMap {
  std::string source;  // the file it came from ("" for one built in memory)
  // RGB, each 2:1. Level k holds the radiance averaged over the GGX lobe (Blender's roughness
  // k / (levels - 1), alpha = roughness^2) around each texel's direction, with the split-sum
  // assumption normal = view = reflection (Karis 2013): level 0 the map itself, the rough levels
  // smaller.
  std::vector<Image> levels;
  bool empty() const { return levels.empty(); }
};

// Prefilters an equirectangular RGB (or RGBA, A ignored) image as above. Non-finite and negative
// radiance becomes 0, and radiance is kept within the pipeline's radiance limit. Throws
// Error(InvalidInput) naming `source` when the image is not 2:1 or has fewer than 3 channels.
EnvironmentMap prefilterEnvironment(const Image& equirect, const std::string& source = "");

// Reads an equirectangular EXR (channels R, G, B; half or float, any compression) and
// prefilters it. Throws Error(IoError) for a missing or unreadable file and Error(InvalidInput)
// for one that is not 2:1 or has no R, G, B channels; messages start with the file name.
EnvironmentMap loadEnvironmentMap(const std::string& path);

}  // namespace ssrcl
