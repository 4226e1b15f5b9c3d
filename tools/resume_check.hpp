#pragma once
#include <string>

#include "output_options.hpp"

namespace ssrcl::cli {

// Whether the existing `output` of a frame traced from `input` was made as asked now: its
// recorded preset, output form, environment file, then each setting, then its layer, channel type and compression. Returns why
// not, naming the file and the first difference; empty when it was. Outputs without ssrcl's
// record (older versions, other tools) are reported as such.
std::string resumeMismatch(const std::string& output, const std::string& input, const OutputOptions& o,
                           const OutputRecord& asked);

}  // namespace ssrcl::cli
