#include "bench_runner.hpp"

#include <algorithm>
#include <cmath>

namespace ssrcl::cli {
namespace {

Pipeline makePipeline(const Device& device, const BenchInput& input) {
  Pipeline p(device);
  p.setGBuffer(input.gbuffer);
  p.setCamera(input.camera);
  return p;
}

double luminance(const float* rgb) { return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2]; }

BenchError compare(const BenchInput& input, float maxRoughness, const Image& pass, const Image& reference) {
  const GBuffer& g = input.gbuffer;
  std::vector<size_t> reflecting;
  double peak = 0;
  for (size_t i = 0; i < g.depth.data.size(); ++i) {
    const float d = g.depth.data[i];
    const float r = g.roughness.empty() ? 0.0f : g.roughness.data[i];
    if (!(std::isfinite(d) && d >= input.camera.nearPlane && d <= input.camera.farPlane && r <= maxRoughness)) continue;
    reflecting.push_back(i);
    for (int c = 0; c < 3; ++c) peak = std::max(peak, double(reference.data[4 * i + c]));
  }
  BenchError e;
  if (reflecting.empty() || peak <= 0) return e;
  double se = 0;
  size_t over = 0;
  for (size_t i : reflecting) {
    for (int c = 0; c < 3; ++c) {
      const double diff = double(pass.data[4 * i + c]) - reference.data[4 * i + c];
      se += diff * diff;
    }
    const double ref = luminance(&reference.data[4 * i]), ours = luminance(&pass.data[4 * i]);
    over += std::abs(ours - ref) > 0.05 * std::max(ref, 0.01 * peak);
  }
  e.rmse = std::sqrt(se / (3.0 * reflecting.size()));
  e.psnr = e.rmse > 0 ? 20 * std::log10(peak / e.rmse) : INFINITY;
  e.fractionOver5Percent = double(over) / reflecting.size();
  return e;
}

}  // namespace

StageStats stageStats(std::vector<double> ms) {
  std::sort(ms.begin(), ms.end());
  return {ms.front(), ms[ms.size() / 2]};
}

Image referencePass(const Device& device, const BenchInput& input, int spp) {
  Pipeline p = makePipeline(device, input);
  p.settings() = qualityPreset("reference");
  p.settings().samplesPerPixel = spp;
  p.commit();
  p.execute();
  return p.output("reflection");
}

std::vector<BenchResult> runBench(const Device& device, const BenchInput& input,
                                  const std::vector<BenchConfig>& configs, int repetitions, const Image* reference) {
  std::vector<BenchResult> results;
  for (const BenchConfig& config : configs) {
    // A pipeline of its own, so its device memory is what this configuration needs.
    Pipeline p = makePipeline(device, input);
    p.commit();
    BenchResult r;
    r.input = input.name;
    r.config = config.name;
    r.width = input.camera.width;
    r.height = input.camera.height;
    p.settings() = config.settings;
    p.execute();  // warm-up: kernel compilation, first-touch allocations
    std::map<std::string, std::vector<double>> samples;
    for (int k = 0; k < repetitions; ++k) {
      p.execute();
      double total = 0;
      for (const auto& [stage, ms] : p.stageTimes().ms) {
        samples[stage].push_back(ms);
        total += ms;
      }
      samples["total"].push_back(total);
    }
    for (auto& [stage, v] : samples) r.stages[stage] = stageStats(v);
    r.pixelsTraced = p.stageTimes().tracedPixels;
    r.tilesResolved = p.stageTimes().resolvedTiles;
    r.rays = p.stageTimes().tracedRays;
    const double traceMs = r.stages["trace"].medianMs;
    r.raysPerSecond = traceMs > 0 ? r.rays / (traceMs * 1e-3) : 0;
    r.deviceMiBPerMegapixel = p.deviceBytes() / 1048576.0 / (r.width * double(r.height) * 1e-6);
    if (reference) {
      r.hasError = true;
      r.error = compare(input, config.settings.maxRoughness, p.output("reflection"), *reference);
    }
    p.settings().countWork = true;
    p.execute();
    r.fetchesPerRay = r.rays > 0 ? double(p.stageTimes().depthFetches) / r.rays : 0;
    r.iterationHistogram = p.stageTimes().iterationHistogram;
    results.push_back(std::move(r));
  }
  return results;
}

}  // namespace ssrcl::cli
