#pragma once
#include <string>

#include "ssrcl/io.hpp"

namespace ssrcl::detail {

// What a renderer writes by default: channel names, depth kind, normal space, and where its
// camera is (README, Input: the table and its sources). Options given alone override each field.
struct RendererPreset {
  std::string name;
  std::string layer, colorChannels, depthChannel, normalChannels;
  DepthKind depthKind;
  NormalSpace normalSpace;
};

// Throws Error(InvalidArgument) naming the known renderers for an unknown name.
const RendererPreset& rendererPreset(const std::string& name);

}  // namespace ssrcl::detail
