#pragma once
// The back-face depth pass (GBuffer::backDepth) in the pipeline's convention (host/io/back_depth.cpp).
#include "ssrcl/camera.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::detail {

// Turns `g.backDepth` (when there is one) into planar depth, 0 where no back is known or the
// front has no surface; run after the front depth is planar. Throws Error(InvalidInput) naming
// the file when the back lies in front of the front on more than 1% of the surface pixels.
void prepareBackDepth(GBuffer& g, const GBufferSource& source, const Camera& camera);

}  // namespace ssrcl::detail
