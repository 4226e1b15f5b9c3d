#pragma once
#include <optional>
#include <string>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"

namespace ssrcl {

// Where each G-buffer pass comes from. File fields left empty use `file`. Channel names are full
// EXR names; empty means the default built from `layer` (Blender multilayer naming):
//   color     {layer}.Combined.R,G,B   depth {layer}.Depth.Z
//   normal    {layer}.Normal.X,Y,Z     roughness {layer}.roughness.X
// With layer == "" the defaults are plain names: R,G,B  Z  N.X,N.Y,N.Z  roughness
// In multi-part files a channel may also be found as part name + "." + channel name.
struct GBufferSource {
  std::string file;
  std::string colorFile, depthFile, normalFile, roughnessFile;
  std::string layer = "ViewLayer";
  std::string colorChannels;  // comma-separated "R,G,B" form
  std::string depthChannel;
  std::string normalChannels;  // comma-separated "X,Y,Z" form
  std::string roughnessChannel;
  std::optional<float> constantRoughness;  // when set, no roughness channel is read
};

struct GBuffer {
  Image color;      // 3 channels
  Image depth;      // 1 channel, planar view depth
  Image normal;     // 3 channels, world space
  Image roughness;  // 1 channel; empty when constantRoughness was given
};

// Reads and checks every pass (half or float, any compression, single- or multi-part).
// Throws Error(IoError) for unreadable files and Error(InvalidInput) for missing channels or
// mismatched sizes; the message starts with the file name and names the channel.
GBuffer loadGBuffer(const GBufferSource& source);

// Camera sidecar: {"view": 4x4 row-major world->camera, "projection": 4x4 row-major OpenGL clip,
// "width": W, "height": H, optional "near", "far"}. Validated; errors name the file and field.
Camera loadCameraJson(const std::string& path);
void saveCameraJson(const std::string& path, const Camera& camera);

// Writes the reflection pass (R,G,B,A from rgba, plus "distance") as float EXR with ZIP
// compression, through a temporary file in the same directory renamed over `path`, so a failure
// leaves any existing file untouched. Throws Error(IoError).
void writeReflectionExr(const std::string& path, const Image& rgba, const Image& distance);

}  // namespace ssrcl
