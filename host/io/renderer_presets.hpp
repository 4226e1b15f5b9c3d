#pragma once
#include <string>

#include "ssrcl/io.hpp"

namespace ssrcl::detail {

// What a renderer writes by default: channel names, depth kind, normal space, and where its
// camera is (docs/renderers.md: the table and its sources). Options given alone override each field.
struct RendererPreset {
  std::string name;
  std::string layer, colorChannels, depthChannel, normalChannels;
  DepthKind depthKind;
  NormalSpace normalSpace;
  // The glossy-pass output form is the default where a file holds the material passes: the
  // renderer's glossy passes keep the Fresnel and it writes no specular albedo that an incident
  // pass could be composited with (docs/renderers.md, "Output forms per renderer").
  bool glossyPassByDefault = false;
};

// Throws Error(InvalidArgument) naming the known renderers for an unknown name.
const RendererPreset& rendererPreset(const std::string& name);

}  // namespace ssrcl::detail
