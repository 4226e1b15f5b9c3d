#pragma once
#include <map>
#include <string>
#include <vector>

#include "bench_inputs.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::cli {

struct BenchConfig {
  std::string name;
  TraceSettings settings;
};

struct StageStats {
  double minMs = 0, medianMs = 0;
};
// Min and median of a stage's times (milliseconds, at least one).
StageStats stageStats(std::vector<double> ms);

// Error of a pass against the reference pass over the pixels that reflect (a surface, not above
// the maximum roughness): RMSE of premultiplied RGB, PSNR against the reference's brightest
// channel, and the fraction of pixels whose luminance is off by more than 5% (relative, with a
// floor of 1% of that peak so black pixels do not count as infinitely wrong).
struct BenchError {
  double rmse = 0, psnr = 0, fractionOver5Percent = 0;
};

struct BenchResult {
  std::string input, config;
  int width = 0, height = 0;
  std::map<std::string, StageStats> stages;  // per stage from profiling events, and "total"
  long long pixelsTraced = 0, rays = 0, tilesResolved = 0;
  double raysPerSecond = 0;  // rays / median trace time
  double fetchesPerRay = 0;  // from one extra run in counting mode
  std::vector<long long> iterationHistogram;
  double deviceMiBPerMegapixel = 0;
  bool hasError = false;
  BenchError error;
};

// The yardstick pass: the reference preset with `spp` rays per pixel.
Image referencePass(const Device& device, const BenchInput& input, int spp);

// Each configuration: one warm-up run, `repetitions` timed runs, one counting run; error against
// `reference` when given.
std::vector<BenchResult> runBench(const Device& device, const BenchInput& input,
                                  const std::vector<BenchConfig>& configs, int repetitions, const Image* reference);

}  // namespace ssrcl::cli
