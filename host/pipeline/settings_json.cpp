#include <charconv>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "ssrcl/pipeline.hpp"

namespace ssrcl {
namespace {

// The option names of the enums (--tracer, --thickness-model, --roughness-mapping).
const char* name(Tracer t) { return t == Tracer::Linear ? "linear" : t == Tracer::DDA ? "dda" : "hiz"; }
const char* name(ThicknessModel m) { return m == ThicknessModel::Constant ? "constant" : "adaptive"; }
const char* name(RoughnessMapping m) { return m == RoughnessMapping::Linear ? "linear" : "squared"; }

// The shortest decimal that reads back as `f`, so the record says 0.002 rather than the
// float's exact binary value 0.0020000000949949026.
double decimal(float f) {
  char text[32];
  *std::to_chars(text, text + sizeof(text) - 1, f).ptr = '\0';
  return std::strtod(text, nullptr);
}

}  // namespace

std::string settingsJson(const TraceSettings& s) {
  nlohmann::ordered_json j;
  j["thicknessModel"] = name(s.thicknessModel);
  j["thicknessRelative"] = decimal(s.thicknessRelative);
  j["thicknessScale"] = decimal(s.thicknessScale);
  j["thicknessMinRelative"] = decimal(s.thicknessMinRelative);
  j["thicknessMaxRelative"] = decimal(s.thicknessMaxRelative);
  j["maxIterations"] = s.maxIterations;
  j["maxRoughness"] = decimal(s.maxRoughness);
  j["edgeFade"] = decimal(s.edgeFade);
  j["viewRadianceCap"] = decimal(s.viewRadianceCap);
  j["constantRoughness"] = s.constantRoughness ? nlohmann::ordered_json(decimal(*s.constantRoughness)) : nullptr;
  j["glossyHitRoughness"] = decimal(s.glossyHitRoughness);
  j["samplesPerPixel"] = s.samplesPerPixel;
  j["fullRaysRoughness"] = decimal(s.fullRaysRoughness);
  j["seed"] = s.seed;
  j["roughnessMapping"] = name(s.roughnessMapping);
  j["mirrorRoughness"] = decimal(s.mirrorRoughness);
  j["reuseRadius"] = s.reuseRadius;
  j["prefilter"] = s.prefilter;
  j["edgeColors"] = s.edgeColors;
  j["tracer"] = name(s.tracer);
  j["linearStepPixels"] = decimal(s.linearStepPixels);
  j["denoise"] = s.denoise;
  j["separableDenoise"] = s.separableDenoise;
  j["traceStride"] = s.traceStride;
  j["countWork"] = s.countWork;
  j["classifyWork"] = s.classifyWork;
  j["environmentRotation"] = decimal(s.environmentRotation);
  j["environmentIntensity"] = decimal(s.environmentIntensity);
  return j.dump();
}

}  // namespace ssrcl
