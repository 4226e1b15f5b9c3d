#include "ssrcl/error.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl {

TraceSettings qualityPreset(const std::string& name) {
  TraceSettings s;
  if (name == "medium") return s;
  if (name == "draft") {
    s.samplesPerPixel = 2;
    s.traceStride = 2;
    s.maxIterations = 64;
    s.separableDenoise = true;
    return s;
  }
  if (name == "high") {
    s.samplesPerPixel = 16;
    return s;
  }
  if (name == "reference") {
    s.tracer = Tracer::Linear;
    s.linearStepPixels = 0.5f;
    s.maxIterations = 1 << 20;
    s.samplesPerPixel = 256;
    s.reuseRadius = 0;
    s.denoise = false;
    return s;
  }
  throw Error(ErrorCode::InvalidArgument, "unknown quality '" + name + "' (expected draft, medium, high or reference)");
}

}  // namespace ssrcl
