#include "settings_validation.hpp"

#include <cmath>
#include <tuple>

#include "ssrcl/error.hpp"

namespace ssrcl {
namespace detail {

void validateConstantRoughness(std::optional<float> roughness) {
  if (roughness && !(*roughness >= 0.0f && *roughness <= 1.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter roughness must be in [0, 1]");
}

int maxIterations(const TraceSettings& s) {
  if (s.maxIterations > 0) return s.maxIterations;
  return s.tracer == Tracer::HiZ ? 512 : 1 << 20;
}

}  // namespace detail

namespace {
auto fields(const TraceSettings& s) {
  return std::tie(s.thicknessModel, s.thicknessRelative, s.thicknessScale, s.thicknessMinRelative,
                  s.thicknessMaxRelative, s.maxIterations, s.maxRoughness, s.edgeFade, s.viewRadianceCap,
                  s.constantRoughness, s.glossyHitRoughness, s.samplesPerPixel, s.fullRaysRoughness, s.seed,
                  s.roughnessMapping, s.mirrorRoughness, s.reuseRadius, s.prefilter, s.edgeColors, s.tracer,
                  s.linearStepPixels, s.denoise, s.separableDenoise, s.traceStride, s.countWork, s.classifyWork,
                  s.environmentRotation, s.environmentIntensity);
}
}  // namespace

void validateSettings(const TraceSettings& s) {
  if (!(s.thicknessRelative > 0.0f) || !std::isfinite(s.thicknessRelative))
    throw Error(ErrorCode::InvalidArgument, "parameter thickness must be a positive number");
  if (!(s.thicknessScale > 0.0f) || !std::isfinite(s.thicknessScale))
    throw Error(ErrorCode::InvalidArgument, "parameter thickness-scale must be a positive number");
  if (!(s.thicknessMinRelative > 0.0f && s.thicknessMinRelative <= s.thicknessMaxRelative) ||
      !std::isfinite(s.thicknessMaxRelative))
    throw Error(ErrorCode::InvalidArgument,
                "parameters thickness-min and thickness-max must be positive numbers, min <= max");
  if (!(s.glossyHitRoughness >= 0.0f && s.glossyHitRoughness <= 1.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter glossy-hit-roughness must be in [0, 1]");
  if (s.maxIterations < 0)
    throw Error(ErrorCode::InvalidArgument, "parameter max-iterations must be >= 0 (0: the tracer's own)");
  if (!(s.maxRoughness >= 0.0f && s.maxRoughness <= 1.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter max-roughness must be in [0, 1]");
  if (!(s.edgeFade >= 0.0f && s.edgeFade <= 0.5f))
    throw Error(ErrorCode::InvalidArgument, "parameter edge-fade must be in [0, 0.5]");
  if (!(s.viewRadianceCap >= 0.0f && s.viewRadianceCap <= 1e6f))
    throw Error(ErrorCode::InvalidArgument, "parameter view-radiance-cap must be in [0, 1e6] (0: no cap)");
  if (!(s.environmentIntensity >= 0.0f && s.environmentIntensity <= 1e6f))
    throw Error(ErrorCode::InvalidArgument, "parameter environment-intensity must be in [0, 1e6]");
  if (!std::isfinite(s.environmentRotation))
    throw Error(ErrorCode::InvalidArgument, "parameter environment-rotation must be a finite number of degrees");
  detail::validateConstantRoughness(s.constantRoughness);
  if (s.samplesPerPixel < 1 || s.samplesPerPixel > 65536)
    throw Error(ErrorCode::InvalidArgument, "parameter spp must be in [1, 65536]");
  if (!(s.fullRaysRoughness >= 0.0f && s.fullRaysRoughness <= 1.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter full-rays-roughness must be in [0, 1]");
  if (!(s.mirrorRoughness >= 0.0f && s.mirrorRoughness <= 1.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter mirror-roughness must be in [0, 1]");
  if (s.reuseRadius < 0 || s.reuseRadius > 8)
    throw Error(ErrorCode::InvalidArgument, "parameter reuse-radius must be in [0, 8]");
  if (!(s.linearStepPixels >= 0.05f && s.linearStepPixels <= 8.0f))
    throw Error(ErrorCode::InvalidArgument, "parameter linear-step must be in [0.05, 8] pixels");
  if (s.traceStride != 1 && s.traceStride != 2)
    throw Error(ErrorCode::InvalidArgument, "parameter trace-stride must be 1 or 2");
  if (s.traceStride == 2 && s.reuseRadius < 1)
    throw Error(ErrorCode::InvalidArgument,
                "parameter trace-stride 2 needs reuse-radius >= 1 (untraced pixels borrow rays)");
}

bool operator==(const TraceSettings& a, const TraceSettings& b) { return fields(a) == fields(b); }
bool operator!=(const TraceSettings& a, const TraceSettings& b) { return !(a == b); }

}  // namespace ssrcl
