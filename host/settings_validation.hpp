#pragma once
#include "ssrcl/pipeline.hpp"

namespace ssrcl::detail {

// The traversal steps per ray the tracer takes (TraceSettings::maxIterations, 0 resolved).
int maxIterations(const TraceSettings& s);

}  // namespace ssrcl::detail
