// Scores reflection passes that `ssrcl trace` or `ssrcl batch` wrote against the Cycles renders
// they were traced from (tests/support/cycles_reference.hpp: what is compared with what, the
// same as ssrcl_score_corpus): one line per render, then the mean.
//
//   ssrcl_score_passes --passes out/ render.0000.exr render.0004.exr ...
//       (each render's pass: <passes>/<render stem>.refl.exr, `ssrcl batch -o out/`'s naming)
#include <CLI/CLI.hpp>
#include <filesystem>
#include <iomanip>
#include <iostream>

#include "support/cycles_reference.hpp"
#include "support/exr_fixtures.hpp"

namespace {

ssrcl::Image readReflection(const std::string& path) {
  const ssrcl::test::ExrContents exr = ssrcl::test::readExr(path);
  ssrcl::Image pass(exr.width, exr.height, 4);
  const char* rgba[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    const auto it = exr.channels.find(rgba[c]);
    if (it == exr.channels.end()) throw std::runtime_error(path + ": no channel " + rgba[c]);
    for (size_t i = 0; i < it->second.values.size(); ++i) pass.data[4 * i + size_t(c)] = it->second.values[i];
  }
  return pass;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Scores ssrcl's reflection passes against the Cycles renders they were traced from"};
  std::vector<std::string> renders;
  std::string passes;
  app.add_option("renders", renders, "Cycles renders (samples/corpus layout: glossy passes, IndexOB)")->required();
  app.add_option("--passes", passes, "Directory of the passes: <stem>.refl.exr per render")->required();
  CLI11_PARSE(app, argc, argv);
  try {
    double sum = 0, low = 0;
    std::cout << std::fixed << std::setprecision(2) << "render\tPSNR (dB)\tlow-confidence share of error\n";
    for (const std::string& render : renders) {
      const ssrcl::test::CyclesReference ref = ssrcl::test::loadCyclesReference(render);
      const std::filesystem::path pass =
          std::filesystem::path(passes) / (std::filesystem::path(render).stem().string() + ".refl.exr");
      const ssrcl::test::ReferenceError e =
          ssrcl::test::referenceError(ref, readReflection(pass.string()), ref.groups.front().second);
      std::cout << std::filesystem::path(render).filename().string() << "\t" << e.psnr << "\t" << e.lowConfidence
                << "\n";
      sum += e.psnr;
      low += e.lowConfidence;
    }
    std::cout << "mean\t" << sum / double(renders.size()) << "\t" << low / double(renders.size()) << "\n";
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_score_passes: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
