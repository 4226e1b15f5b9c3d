#pragma once
#include <map>
#include <memory>
#include <string>

#include "ssrcl/camera.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/image.hpp"

namespace ssrcl {

// Reflection-pass settings. Distances are in view-space units unless stated.
struct TraceSettings {
  // Hits count when the ray is at most this far behind the depth buffer, relative to the
  // surface's depth (scale-aware: 0.02 = 2% of the depth at the hit).
  float thicknessRelative = 0.02f;
  int maxIterations = 512;          // Hi-Z traversal steps per ray before it gives up
  float maxRoughness = 1.0f;        // pixels rougher than this get no ray and A = 0
  float edgeFade = 0.05f;           // fraction of the screen's smaller side over which A fades out
  float constantRoughness = -1.0f;  // >= 0 overrides the roughness image
};

// Per-stage device time of the last execute(), from OpenCL profiling events (milliseconds).
struct StageTimes {
  std::map<std::string, double> ms;  // "upload", "setup", "hzb", "trace", "resolve", "download"
  long long tracedRays = 0;
};

// The SSR pipeline, shaped like an OIDN filter:
//   Pipeline p(device);
//   p.setImage("color", img); p.setImage("depth", d); p.setImage("normal", n); p.setImage("roughness", r);
//   p.setCamera(cam); p.settings() = {...};
//   p.commit();   // validates, compiles kernels once per device, allocates
//   p.execute();  // runs setup, HZB, trace, resolve
//   const Image& out = p.output("reflection");  // RGBA premultiplied, A = confidence
//   const Image& dist = p.output("distance");   // view-space hit distance, 0 where no hit
// Input images: color 3 or 4 channels (only RGB used), depth 1 (planar view depth, values beyond
// the far plane or not finite mean "no surface"), normal 3 (world space), roughness 1 (optional
// when settings().constantRoughness >= 0).
class Pipeline {
 public:
  explicit Pipeline(const Device& device);
  ~Pipeline();
  Pipeline(Pipeline&&) noexcept;
  Pipeline& operator=(Pipeline&&) noexcept;

  // The image is copied at commit/execute time; it must stay alive until then.
  void setImage(const std::string& name, const Image& image);
  void setCamera(const Camera& camera);
  TraceSettings& settings();

  void commit();
  void execute();

  const Image& output(const std::string& name) const;
  const StageTimes& stageTimes() const;
  // The HZB mip chain of the last execute (level 0 = linear depth), for tests and tools.
  std::vector<Image> readHzb() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ssrcl
