#pragma once
#include <nlohmann/json.hpp>

#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

// Every TraceSettings field by its C++ name, in declaration order: the `ssrcl/settings` record of
// an output, compared field by field when a batch resumes. A field added to TraceSettings must
// be added here, or resumes will not see it change.
nlohmann::ordered_json settingsJson(const TraceSettings& s);

}  // namespace ssrcl::cli
