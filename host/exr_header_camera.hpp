#pragma once
#include <OpenEXR/ImfHeader.h>

#include <optional>
#include <string>

#include "ssrcl/io.hpp"

namespace ssrcl::detail {

// The camera an EXR header holds (see HeaderCamera), nullopt when it holds none; `path` names
// the file in HeaderCamera::problem.
std::optional<HeaderCamera> cameraFromHeader(const Imf::Header& header, const std::string& path);

}  // namespace ssrcl::detail
