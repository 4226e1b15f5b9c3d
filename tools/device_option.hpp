#pragma once
#include <string>

#include "ssrcl/device.hpp"

namespace ssrcl::cli {

// `--device` accepts an index from `ssrcl devices`, or cpu, gpu, default.
Device openDevice(const std::string& option);

}  // namespace ssrcl::cli
