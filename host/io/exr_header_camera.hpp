#pragma once
#include <OpenEXR/ImfHeader.h>

#include <optional>
#include <string>

#include "ssrcl/io.hpp"

namespace ssrcl::detail {

// The camera an EXR header holds (see HeaderCamera), nullopt when it holds none; `path` names
// the file in HeaderCamera::problem.
std::optional<HeaderCamera> cameraFromHeader(const Imf::Header& header, const std::string& path);

// A pinhole with its axis at the window's centre and `fovDegrees` across it (horizontally), looking
// as `view` says; placeholder clip planes (near 1, far infinity). Throws Error(InvalidInput), "`where`
// must be in (0, 180) degrees", for a field of view outside that.
Camera pinholeCamera(const glm::dmat4& view, double fovDegrees, const PixelBox& display, const std::string& where);

// Writes `camera` (of the header's display window) as the standard worldToCamera and worldToNDC,
// which cameraFromHeader reads back. The NDC z row holds OpenGL depth mapped to [0, 1], although
// readers discard it: the clip planes do not survive the trip.
void cameraToHeader(const Camera& camera, Imf::Header& header);

}  // namespace ssrcl::detail
