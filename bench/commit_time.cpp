// Commit time per frame of a sequence, as `ssrcl batch` runs one: each frame's images are new
// objects of the same size, set, committed and executed on one pipeline.
//   ssrcl_commit_time [width height frames]
// Prints the first commit (kernel builds, allocation) and the median of the others, in ms.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "ssrcl/ssrcl.hpp"
#include "support/simple_camera.hpp"

int main(int argc, char** argv) {
  const int w = argc > 3 ? std::atoi(argv[1]) : 1920, h = argc > 3 ? std::atoi(argv[2]) : 1080;
  const int frames = argc > 3 ? std::atoi(argv[3]) : 10;
  const ssrcl::Camera camera = ssrcl::test::perspectiveCamera(w, h);
  ssrcl::Device device(ssrcl::DeviceType::CPU);
  ssrcl::Pipeline pipeline(device);
  // Too rough to trace: execute() is setup and pyramids only, the frame loop is commit-bound.
  pipeline.settings().constantRoughness = 1.0f;
  pipeline.settings().maxRoughness = 0.5f;
  std::vector<double> commitMs;
  for (int f = 0; f < frames; ++f) {
    ssrcl::Image color(w, h, 3), depth(w, h, 1), normal(w, h, 3);
    std::fill(depth.data.begin(), depth.data.end(), 5.0f + f);
    for (size_t i = 2; i < normal.data.size(); i += 3) normal.data[i] = 1.0f;
    pipeline.setImage("color", color);
    pipeline.setImage("depth", depth);
    pipeline.setImage("normal", normal);
    pipeline.setCamera(camera);
    const auto start = std::chrono::steady_clock::now();
    pipeline.commit();
    commitMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    pipeline.execute();
  }
  std::vector<double> later(commitMs.begin() + 1, commitMs.end());
  std::sort(later.begin(), later.end());
  std::printf("%dx%d, %d frames: first commit %.3f ms, later commits median %.3f ms (min %.3f, max %.3f)\n", w, h,
              frames, commitMs[0], later.empty() ? 0.0 : later[later.size() / 2], later.empty() ? 0.0 : later.front(),
              later.empty() ? 0.0 : later.back());
  return 0;
}
