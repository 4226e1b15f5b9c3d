// The back-face depth pass made the pipeline's: planar, 0 where unknown, and checked against the
// front depth it belongs to (a pass of another frame or camera is refused, not traced).
#include "back_depth.hpp"

#include <cmath>
#include <cstdio>

#include "conventions.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::detail {

void prepareBackDepth(GBuffer& g, const GBufferSource& source, const Camera& camera) {
  if (g.backDepth.empty()) return;
  const std::string& file = !source.backDepthFile.empty() ? source.backDepthFile
                            : !source.depthFile.empty()   ? source.depthFile
                                                          : source.file;
  if (g.backDepth.width != g.depth.width || g.backDepth.height != g.depth.height)
    throw Error(ErrorCode::InvalidInput, file + ": the back-face depth is " + std::to_string(g.backDepth.width) +
                                             "x" + std::to_string(g.backDepth.height) + " but the depth is " +
                                             std::to_string(g.depth.width) + "x" + std::to_string(g.depth.height));
  for (float& b : g.backDepth.data)
    if (!isSurfaceDepth(b)) b = 0.0f;  // NaN, negative, 1e10 and beyond: no back known
  if (source.depthKind == DepthKind::Radial) g.backDepth = planarFromRadial(g.backDepth, camera);
  // Behind the front by less than its float resolution, the visible surface is itself a back face
  // (its back is not known); in front of it by more, the pass is wrong there.
  long long surface = 0, inFront = 0, atFront = 0;
  for (size_t i = 0; i < g.backDepth.data.size(); ++i) {
    const float d = g.depth.data[i];
    float& b = g.backDepth.data[i];
    if (!isSurfaceDepth(d)) {
      b = 0.0f;
      continue;
    }
    ++surface;
    if (b > 0.0f && b < d * (1.0f - 1e-3f)) ++inFront;
    if (b >= d * (1.0f - 1e-3f) && !(b > d * (1.0f + 1e-5f))) ++atFront;
    if (!(b > d * (1.0f + 1e-5f))) b = 0.0f;
  }
  const auto share = [&](long long n) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f%%", 100.0 * double(n) / double(surface));
    return std::string(text);
  };
  if (inFront * 100 > surface)
    throw Error(ErrorCode::InvalidInput, file + ": the back-face depth lies in front of the depth on " +
                                             share(inFront) +
                                             " of the surface pixels (at most 1% may): not the back faces of this "
                                             "frame's camera and depth kind");
  // A visible surface is a back face only here and there: a pass equal to the front on most
  // pixels is the frame's own depth given by mistake.
  if (atFront * 2 > surface)
    throw Error(ErrorCode::InvalidInput, file + ": the back-face depth equals the depth on " + share(atFront) +
                                             " of the surface pixels: a front depth pass, not the back faces' "
                                             "(--back-depth-channel names another channel)");
}

}  // namespace ssrcl::detail
