// Error of each quality setting against Cycles' path-traced glossy passes on a Blender sample:
//   ssrcl_compare_cycles <sample.exr> [camera.json] [specular]
// See tests/support/cycles_reference.hpp for what is compared with what.
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>

#include "ssrcl/ssrcl.hpp"
#include "support/cycles_reference.hpp"

namespace {

struct Setting {
  std::string name;
  ssrcl::TraceSettings settings;
};

std::vector<Setting> settingsToCompare() {
  std::vector<Setting> list;
  auto medium = ssrcl::qualityPreset("medium");
  auto draft = medium;
  draft.samplesPerPixel = 1;
  draft.reuseRadius = 0;
  list.push_back({"1 ray, no reuse", draft});
  list.push_back({"medium", medium});
  auto prefiltered = medium;
  prefiltered.prefilter = true;
  list.push_back({"medium + prefilter", prefiltered});
  auto denoised = medium;
  denoised.denoise = true;
  list.push_back({"medium + denoise", denoised});
  auto many = medium;
  many.samplesPerPixel = 16;
  list.push_back({"16 rays", many});
  auto reference = ssrcl::qualityPreset("reference");
  list.push_back({"reference (256)", reference});
  return list;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: ssrcl_compare_cycles <sample.exr> [camera.json] [specular]\n";
    return 2;
  }
  const std::string exr = argv[1];
  const std::string cameraPath = argc > 2 ? argv[2] : "";
  const double specular = argc > 3 ? std::atof(argv[3]) : 1.0;
  try {
    const ssrcl::test::CyclesFloorReference ref = ssrcl::test::loadCyclesFloorReference(exr, cameraPath, specular);
    const ssrcl::GBuffer& g = ref.gbuffer;
    ssrcl::Device device(ssrcl::DeviceType::Default);
    ssrcl::Pipeline pipeline(device);
    pipeline.setGBuffer(g);
    pipeline.setCamera(ref.camera);
    pipeline.commit();

    std::vector<Setting> settings = settingsToCompare();
    std::vector<ssrcl::Image> outputs;
    std::vector<double> deviceMs;
    for (const Setting& s : settings) {
      pipeline.settings() = s.settings;
      pipeline.execute();
      double ms = 0;
      for (const auto& [stage, t] : pipeline.stageTimes().ms) ms += t;
      deviceMs.push_back(ms);
      outputs.push_back(pipeline.output("reflection"));
    }
    std::cout << "sample: " << exr << " (" << g.depth.width << "x" << g.depth.height
              << "), device: " << device.info().name << "\n"
              << "floor pixels compared: " << ref.groups.front().second.size() << ", peak " << ref.peak
              << "; RMSE per group, PSNR (dB, peak / RMSE) and mean |error| over all\n"
              << std::left << std::setw(22) << "setting" << std::right << std::setw(11) << "device ms";
    for (auto& grp : ref.groups) std::cout << std::setw(11) << grp.first;
    std::cout << std::setw(9) << "PSNR" << std::setw(11) << "mean|err|"
              << "\n";
    for (size_t s = 0; s < settings.size(); ++s) {
      std::cout << std::left << std::setw(22) << settings[s].name << std::right << std::fixed << std::setprecision(1)
                << std::setw(11) << deviceMs[s];
      double rmseAll = 0, absAll = 0;
      for (auto& [name, ks] : ref.groups) {
        const ssrcl::test::FloorError err = ssrcl::test::floorError(ref, outputs[s], ks);
        if (name == "floor") {
          rmseAll = err.rmse;
          absAll = err.meanAbs;
        }
        std::cout << std::setprecision(4) << std::setw(11) << err.rmse;
      }
      std::cout << std::setprecision(2) << std::setw(9) << 20 * std::log10(ref.peak / rmseAll) << std::setprecision(4)
                << std::setw(11) << absAll << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_compare_cycles: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
