// Per-stage device time (OpenCL profiling events) of the mirror pipeline on an analytic scene:
//   ssrcl_stage_times [scene] [width] [height] [repetitions] [device] [roughness] [quality]
// roughness >= 0 makes every surface that rough (the analytic scenes are mirrors).
// Prints min and median over the repetitions after one warm-up run (kernel compilation).
#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <vector>

#include "ssrcl/ssrcl.hpp"
#include "scenes/analytic_scene.hpp"

int main(int argc, char** argv) {
  const std::string sceneName = argc > 1 ? argv[1] : "spheres_on_mirror";
  const int width = argc > 2 ? std::atoi(argv[2]) : 1920;
  const int height = argc > 3 ? std::atoi(argv[3]) : 1080;
  const int repetitions = argc > 4 ? std::max(1, std::atoi(argv[4])) : 5;
  const std::string deviceChoice = argc > 5 ? argv[5] : "default";
  const float roughness = argc > 6 ? float(std::atof(argv[6])) : -1.0f;
  const std::string quality = argc > 7 ? argv[7] : "medium";
  try {
    ssrcl::test::Scene scene = ssrcl::test::makeScene(sceneName);
    ssrcl::Camera camera = ssrcl::test::makeCamera(scene.view, width, height);
    ssrcl::test::AnalyticGBuffer g = ssrcl::test::renderGBuffer(scene, camera);

    ssrcl::Device device = deviceChoice == "cpu"   ? ssrcl::Device(ssrcl::DeviceType::CPU)
                           : deviceChoice == "gpu" ? ssrcl::Device(ssrcl::DeviceType::GPU)
                                                   : ssrcl::Device(ssrcl::DeviceType::Default);
    ssrcl::Pipeline p(device);
    p.setImage("color", g.color);
    p.setImage("depth", g.depth);
    p.setImage("normal", g.normal);
    p.setImage("roughness", g.roughness);
    p.setCamera(camera);
    p.settings() = ssrcl::qualityPreset(quality);
    p.settings().constantRoughness = roughness;
    p.commit();
    p.execute();  // warm-up

    std::map<std::string, std::vector<double>> samples;
    for (int r = 0; r < repetitions; ++r) {
      p.execute();
      double total = 0;
      for (const auto& [stage, ms] : p.stageTimes().ms) {
        samples[stage].push_back(ms);
        total += ms;
      }
      samples["total"].push_back(total);
    }
    std::cout << "device: " << device.info().name << "\nscene: " << sceneName << " " << width << "x" << height
              << ", quality " << quality << ", roughness "
              << (roughness >= 0 ? std::to_string(roughness) : std::string("as rendered"))
              << ", pixels traced: " << p.stageTimes().tracedPixels << ", rays: " << p.stageTimes().tracedRays
              << ", repetitions: " << repetitions << "\n"
              << std::left << std::setw(10) << "stage" << std::right << std::setw(12) << "min ms" << std::setw(12)
              << "median ms"
              << "\n";
    for (auto& [stage, v] : samples) {
      std::sort(v.begin(), v.end());
      std::cout << std::left << std::setw(10) << stage << std::right << std::fixed << std::setprecision(3)
                << std::setw(12) << v.front() << std::setw(12) << v[v.size() / 2] << "\n";
    }
    const double traceMs = samples["trace"][samples["trace"].size() / 2];
    if (traceMs > 0)
      std::cout << "trace rays/s (median): " << std::setprecision(0) << p.stageTimes().tracedRays / (traceMs * 1e-3)
                << "\n";
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_stage_times: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
