// The temporal blend's host time on traced frames, as `ssrcl batch --temporal K` runs it: each
// frame traced with the defaults (its own seed), then every frame's statistics and the blend of
// the middle frame with all the others, timed apart.
//   ssrcl_temporal_blend_time [--repetitions N] frame.exr...
// Prints CPU and wall ms of the statistics (per frame) and of each blend, and a digest of the
// blended pass (FNV-1a of its floats), the same for two builds that blend alike.
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "ssrcl/ssrcl.hpp"
#include "ssrcl/temporal.hpp"

namespace {

double cpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double wallSeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace

int main(int argc, char** argv) {
  int repetitions = 3;
  std::vector<std::string> files;
  for (int k = 1; k < argc; ++k) {
    if (std::strcmp(argv[k], "--repetitions") == 0 && k + 1 < argc)
      repetitions = std::max(1, std::atoi(argv[++k]));
    else
      files.push_back(argv[k]);
  }
  if (files.size() < 2) {
    std::fprintf(stderr, "usage: ssrcl_temporal_blend_time [--repetitions N] frame.exr frame.exr...\n");
    return 2;
  }
  ssrcl::Device device(ssrcl::DeviceType::CPU);
  ssrcl::Pipeline pipeline(device);
  const size_t n = files.size();
  std::vector<ssrcl::Frame> frames(n);
  std::vector<ssrcl::Image> reflection(n), distance(n);
  for (size_t i = 0; i < n; ++i) {
    ssrcl::FrameSource source;
    source.file = files[i];
    frames[i] = ssrcl::loadFrame(source);
    ssrcl::setFrame(pipeline, frames[i]);
    pipeline.settings().seed = uint32_t(i);
    pipeline.commit();
    pipeline.execute();
    reflection[i] = pipeline.output("reflection");
    distance[i] = pipeline.output("distance");
  }
  std::vector<ssrcl::TemporalFrame> window;
  for (size_t i = 0; i < n; ++i) {
    const ssrcl::GBuffer& g = frames[i].gbuffer;
    window.push_back({&reflection[i], &distance[i], &g.depth, &g.normal, g.roughness.empty() ? nullptr : &g.roughness,
                      frames[i].camera, nullptr});
  }
  ssrcl::TemporalSettings settings;
  settings.mirrorRoughness = pipeline.settings().mirrorRoughness;
  const double cpu0 = cpuSeconds(), wall0 = wallSeconds();
  for (ssrcl::TemporalFrame& f : window) f.statistics = ssrcl::temporalFrameStatistics(f);
  std::printf("statistics: %.1f ms CPU, %.1f ms wall a frame\n", 1e3 * (cpuSeconds() - cpu0) / double(n),
              1e3 * (wallSeconds() - wall0) / double(n));
  ssrcl::Image blended;
  for (int r = 0; r < repetitions; ++r) {
    const double cpu = cpuSeconds(), wall = wallSeconds();
    blended = ssrcl::temporalBlend(window, n / 2, settings);
    std::printf("blend of frame %zu with %zu others: %.1f ms CPU, %.1f ms wall\n", n / 2, n - 1,
                1e3 * (cpuSeconds() - cpu), 1e3 * (wallSeconds() - wall));
  }
  uint64_t digest = 14695981039346656037ull;
  for (float v : blended.data) {
    uint32_t bits;
    std::memcpy(&bits, &v, 4);
    digest = (digest ^ bits) * 1099511628211ull;
  }
  std::printf("digest %016llx\n", static_cast<unsigned long long>(digest));
  return 0;
}
