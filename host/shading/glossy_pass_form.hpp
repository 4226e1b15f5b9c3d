#pragma once
#include "ssrcl/glossy_pass_form.hpp"

namespace ssrcl::detail {

class ExrFiles;

// defaultOutputForm(source), the material file's headers read through `files` (loadFrame reads
// its passes through the same).
DefaultOutputForm defaultOutputForm(const GBufferSource& source, ExrFiles& files);

}  // namespace ssrcl::detail
