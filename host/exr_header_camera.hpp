#pragma once
#include <OpenEXR/ImfHeader.h>

#include <optional>
#include <string>

#include "ssrcl/io.hpp"

namespace ssrcl::detail {

// The camera an EXR header holds (see HeaderCamera), nullopt when it holds none; `path` names
// the file in HeaderCamera::problem.
std::optional<HeaderCamera> cameraFromHeader(const Imf::Header& header, const std::string& path);

// Writes `camera` (of the header's display window) as the standard worldToCamera and worldToNDC,
// which cameraFromHeader reads back. The NDC z row holds OpenGL depth mapped to [0, 1], although
// readers discard it: the clip planes do not survive the trip.
void cameraToHeader(const Camera& camera, Imf::Header& header);

}  // namespace ssrcl::detail
