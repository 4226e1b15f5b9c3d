#pragma once
#include <optional>

#include "ssrcl/pipeline.hpp"

namespace ssrcl::detail {

// The traversal steps per ray the tracer takes (TraceSettings::maxIterations, 0 resolved).
int maxIterations(const TraceSettings& s);

// TraceSettings::constantRoughness's range, also where it is passed on its own (applyGlossyPassForm).
void validateConstantRoughness(std::optional<float> roughness);

}  // namespace ssrcl::detail
