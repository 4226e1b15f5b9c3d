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
#include "support/shot_metric.hpp"

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
          ssrcl::test::referenceError(ref, ssrcl::test::readReflectionPass(pass.string()), ref.groups.front().second);
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
