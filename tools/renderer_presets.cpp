#include "renderer_presets.hpp"

#include "ssrcl/error.hpp"

namespace ssrcl::cli {
namespace {

// Empty channel fields keep the loader's defaults for the layer. Sources and what is unverified:
// README, Input.
const std::vector<RendererPreset>& presets() {
  static const std::vector<RendererPreset> all = {
      {"blender", "ViewLayer", "", "", "", DepthKind::Planar, NormalSpace::World},
      {"arnold", "", "R,G,B", "Z", "N.X,N.Y,N.Z", DepthKind::Planar, NormalSpace::World},
      {"renderman", "", "R,G,B", "Z", "Nn.x,Nn.y,Nn.z", DepthKind::Planar, NormalSpace::Camera},
      {"karma", "", "R,G,B", "depth", "N.x,N.y,N.z", DepthKind::Planar, NormalSpace::World},
      {"vray", "", "R,G,B", "Z", "normals.R,normals.G,normals.B", DepthKind::Planar, NormalSpace::CameraGL},
  };
  return all;
}

}  // namespace

std::vector<std::string> rendererNames() {
  std::vector<std::string> names;
  for (const RendererPreset& p : presets()) names.push_back(p.name);
  return names;
}

const RendererPreset& rendererPreset(const std::string& name) {
  std::string known;
  for (const RendererPreset& p : presets()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  throw Error(ErrorCode::InvalidArgument, "--renderer: unknown renderer '" + name + "' (known: " + known + ")");
}

}  // namespace ssrcl::cli
