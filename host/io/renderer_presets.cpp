#include "renderer_presets.hpp"

#include "ssrcl/error.hpp"
#include "ssrcl/frame.hpp"

namespace ssrcl {
namespace {

using detail::RendererPreset;

// Empty channel fields keep the loader's defaults for the layer; "a|b" lists the layouts a
// renderer is known to write, tried in order. Sources and what is unverified: docs/renderers.md.
// Only Blender defaults to the glossy-pass form: the others' specular passes keep the Fresnel too,
// but they write its albedo (Arnold's and Karma's specular_albedo, V-Ray's Reflection Filter),
// which an incident pass is multiplied by with the renderer's own Fresnel (docs/renderers.md).
const std::vector<RendererPreset>& presets() {
  static const std::vector<RendererPreset> all = {
      {"blender", "ViewLayer", "", "", "", DepthKind::Planar, NormalSpace::World, true},
      {"arnold", "", "R,G,B", "Z", "N.X,N.Y,N.Z", DepthKind::Planar, NormalSpace::World},
      // ILM's driver names variable z "Z"; RenderMan 22's names every variable but r, g, b, a as itself,
      // a colour output NAME as NAME.r/.g/.b (RenderMan 26, Gaffer's tests), R,G,B,A under `asrgba`;
      // RenderMan for Blender names its depth output z_depth.
      {"renderman", "", "R,G,B|Ci.r,Ci.g,Ci.b", "Z|z|z_depth", "Nn.x,Nn.y,Nn.z|Nn.r,Nn.g,Nn.b", DepthKind::Planar,
       NormalSpace::Camera},
      // Mantra's single-part planes (N.x), and Houdini's multi-part files: one part per render var,
      // channels R, G, B.
      {"karma", "", "R,G,B|C.R,C.G,C.B", "depth", "N.x,N.y,N.z|N.R,N.G,N.B", DepthKind::Planar, NormalSpace::World},
      // A V-Ray for Maya 3.6 file's Normals element: normals.X/.Y/.Z, y down and +z forward.
      {"vray", "", "R,G,B", "Z", "normals.X,normals.Y,normals.Z", DepthKind::Planar, NormalSpace::CameraCV},
  };
  return all;
}

}  // namespace

std::vector<std::string> rendererNames() {
  std::vector<std::string> names;
  for (const RendererPreset& p : presets()) names.push_back(p.name);
  return names;
}

const detail::RendererPreset& detail::rendererPreset(const std::string& name) {
  std::string known;
  for (const RendererPreset& p : presets()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  throw Error(ErrorCode::InvalidArgument, "--renderer: unknown renderer '" + name + "' (known: " + known + ")");
}

}  // namespace ssrcl
