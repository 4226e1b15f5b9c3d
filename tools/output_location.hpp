#pragma once
#include <string>

namespace ssrcl::cli {

// Checked before any frame is traced, so an unwritable output costs no trace: the output's
// directory exists (batch creates it, as it would for writing) and a temporary can be created in
// it. Returns why not, naming the path; empty when writable.
std::string outputLocationProblem(const std::string& output, bool createDirectory);

}  // namespace ssrcl::cli
