#include "ssrcl/error.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl {

TraceSettings qualityPreset(const std::string& name) {
  TraceSettings s;
  if (name == "medium") return s;
  if (name == "reference") {
    s.tracer = Tracer::Linear;
    s.linearStepPixels = 0.5f;
    s.samplesPerPixel = 256;
    s.reuseRadius = 0;
    s.prefilter = false;
    s.denoise = false;
    return s;
  }
  throw Error(ErrorCode::InvalidArgument, "unknown quality '" + name + "' (expected medium or reference)");
}

}  // namespace ssrcl
