// The loader's last step: a G-buffer in any supported convention becomes the pipeline's
// (planar depth, world-space normals), so the kernels see one convention only.
#include "back_depth.hpp"
#include "conventions.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl {

const char* depthKindName(DepthKind kind) { return kind == DepthKind::Radial ? "radial" : "planar"; }

const char* normalSpaceName(NormalSpace space) {
  switch (space) {
    case NormalSpace::World:
      return "world";
    case NormalSpace::Camera:
      return "camera";
    case NormalSpace::CameraGL:
      return "camera-gl";
    case NormalSpace::CameraCV:
      return "camera-cv";
  }
  return "?";
}

void applyInputConventions(GBuffer& g, const GBufferSource& source, const Camera& camera) {
  const Image& geometry = source.positionChannels.empty() ? g.depth : g.position;
  if (camera.width != geometry.width || camera.height != geometry.height)
    throw Error(ErrorCode::InvalidArgument, "applyInputConventions: the camera is " + std::to_string(camera.width) +
                                                "x" + std::to_string(camera.height) + " but the G-buffer is " +
                                                std::to_string(geometry.width) + "x" + std::to_string(geometry.height));
  if (!source.positionChannels.empty())
    g.depth = detail::planarFromPositions(g.position, camera);
  else if (source.depthKind == DepthKind::Radial)
    g.depth = detail::planarFromRadial(g.depth, camera);
  detail::toWorldNormals(g.normal, source.normalSpace, camera);
  detail::prepareBackDepth(g, source, camera);
}

}  // namespace ssrcl
