// The OpenCL mirror pass against its native C++ roofline, per input (bench/roofline.hpp):
//   ssrcl_roofline [inputs] [--sample mirror|glossy] [--scene S --size WxH] [--repetitions N] [--device D]
// with the inputs `ssrcl bench` takes. A measurement: it reports figures, it does not judge them.
#include <CLI/CLI.hpp>
#include <iostream>

#include "bench_inputs.hpp"
#include "roofline.hpp"
#include "ssrcl/ssrcl.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Time the OpenCL mirror pass against a native C++ implementation of the same rays"};
  ssrcl::cli::BenchInputOptions inputs;
  int repetitions = 3;
  std::string device;
  ssrcl::cli::addBenchInputOptions(app, inputs);
  app.add_option("--repetitions", repetitions, "Timed runs of each, alternated (after one warm-up)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  app.add_option("--device", device, "OpenCL device: index from `ssrcl devices`, cpu, gpu or default");
  CLI11_PARSE(app, argc, argv);
  try {
    const ssrcl::Device dev = ssrcl::openDevice(device);
    std::vector<ssrcl::cli::RooflineResult> results;
    for (const ssrcl::cli::BenchInput& input : ssrcl::cli::loadBenchInputs(inputs)) {
      std::cerr << "roofline: " << input.name << "..." << std::endl;
      results.push_back(ssrcl::cli::runRoofline(dev, input, repetitions));
    }
    std::cout << "device: " << dev.info().name << "\n";
    ssrcl::cli::printRoofline(std::cout, results);
  } catch (const ssrcl::Error& e) {
    std::cerr << "ssrcl_roofline: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
