// The CI subset of the Cycles corpus (samples/corpus, scored in full by scripts/score-corpus.sh):
// the defaults against Cycles' path-traced glossy passes on scenes that pull the surface model in
// opposite directions (tabletop_cm wants thick surfaces, thin_objects thin ones,
// mirror_glossy_tiles thin silhouettes) and on the speckle case (night_street). Bounds sit just
// under the figures measured on PoCL (in comments); a wrong thickness model, cone or resolve moves
// them by far more (docs/BENCHMARKS.md, corpus table).
#include <gtest/gtest.h>

#include <iostream>
#include <map>

#include "ssrcl/ssrcl.hpp"
#include "support/cycles_reference.hpp"
#include "support/test_device.hpp"

namespace {

using ssrcl::test::CyclesReference;
using ssrcl::test::ReferenceError;

const std::string kCorpus = std::string(SSRCL_SOURCE_DIR) + "/samples/corpus/";

struct Scored {
  CyclesReference ref;
  std::map<std::string, ReferenceError> errors;
};

// Each scene traced with the default settings and with a constant thickness of 0.2%, 1% and 5% of
// depth (everything else default).
const Scored& scored(const std::string& scene) {
  static std::map<std::string, Scored> cache;
  auto it = cache.find(scene);
  if (it != cache.end()) return it->second;
  Scored& s = cache[scene];
  s.ref = ssrcl::test::loadCyclesReference(kCorpus + scene + ".exr");
  ssrcl::Device device = ssrcl::test::testDevice();
  ssrcl::Pipeline p(device);
  p.setGBuffer(s.ref.gbuffer);  // with base and specular from the glossy passes, as `ssrcl trace`
  p.setCamera(s.ref.camera);
  auto run = [&](const std::string& name, const ssrcl::TraceSettings& settings) {
    p.settings() = settings;
    p.commit();
    p.execute();
    s.errors[name] = ssrcl::test::referenceError(s.ref, p.output("reflection"), s.ref.groups.front().second);
    std::cout << scene << " " << name << ": PSNR " << s.errors[name].psnr << " dB, p99 " << s.errors[name].p99 << "\n";
  };
  run("default", ssrcl::TraceSettings{});
  for (float t : {0.002f, 0.01f, 0.05f}) {
    ssrcl::TraceSettings c;
    c.thicknessModel = ssrcl::ThicknessModel::Constant;
    c.thicknessRelative = t;
    run("constant " + std::to_string(t).substr(0, 5), c);
  }
  ssrcl::TraceSettings unfiltered;
  unfiltered.prefilter = false;
  run("no prefilter", unfiltered);
  return s;
}

double bestConstant(const Scored& s) {
  double best = -1e9;
  for (const auto& [name, e] : s.errors)
    if (name.rfind("constant", 0) == 0) best = std::max(best, e.psnr);
  return best;
}

// The adaptive thickness model stays within 0.3 dB of the best constant on each scene (the issue's
// bound), and clearly above the old default of 0.2% where that one fails.
TEST(Corpus, AdaptiveThicknessHoldsAgainstEachScenesBestConstant) {
  for (const std::string scene : {"tabletop_cm", "thin_objects", "mirror_glossy_tiles"}) {
    const Scored& s = scored(scene);
    EXPECT_GE(s.errors.at("default").psnr, bestConstant(s) - 0.3) << scene;
  }
  // Measured: tabletop_cm 25.4 dB default against 20.7 at 0.2%; mirror_glossy_tiles 32.2 vs 30.0.
  EXPECT_GT(scored("tabletop_cm").errors.at("default").psnr,
            scored("tabletop_cm").errors.at("constant 0.002").psnr + 3.0);
  EXPECT_GT(scored("mirror_glossy_tiles").errors.at("default").psnr,
            scored("mirror_glossy_tiles").errors.at("constant 0.002").psnr + 1.5);
}

// Absolute floors at the measured PSNR (the defaults: medium with its filter), less 0.3 dB for
// device and driver differences.
TEST(Corpus, DefaultsMeetMeasuredAccuracy) {
  const std::map<std::string, double> measured = {
      {"tabletop_cm", 25.57}, {"thin_objects", 25.91}, {"mirror_glossy_tiles", 34.73}, {"night_street", 25.60}};
  for (const auto& [scene, psnr] : measured) EXPECT_GE(scored(scene).errors.at("default").psnr, psnr - 0.3) << scene;
}

// Speckle: rough ground reflecting small bright neon. The prefiltered lookup cuts the 99th
// percentile of per-pixel error and raises PSNR (measured: 0.169 -> 0.135 of the peak, 24.57 ->
// 28.32 dB). The plane-aware filter's wider radius removes part of the speckle by itself (with the
// narrower filter before it the prefilter took p99 from 0.267 to 0.164 and PSNR +4.7 dB).
TEST(Corpus, PrefilterRemovesSpeckle) {
  const Scored& s = scored("night_street");
  const ReferenceError on = s.errors.at("default"), off = s.errors.at("no prefilter");
  EXPECT_LT(on.p99, 0.85 * off.p99);
  EXPECT_GT(on.psnr, off.psnr + 3.0);
}

// ... without darkening the pass: the same rays read at full resolution are the unbiased pass
// (their mean signed error itself moves by 0.015 between seeds on this scene, so the two are
// compared, not each with 0). Pyramid weights from coverage alone put the prefiltered mean
// 0.0252 under the full-resolution one (1.25% of the peak, 2.02); weighted by where the batch's
// hits land (kernels/hit_prefilter.cl) 0.0035 under (seed 7: 0.0009) without the filter, 0.0041
// (0.0014) with it (the default). The filter is linear in the pass with weights from the geometry
// alone, so it keeps that difference; what moved it to 0.0102 (0.0042) was the cone of each ray's
// share of the lobe counting only the taps the filter's resolve takes (host/pipeline/stage_support.hpp,
// resolvedRays).
TEST(Corpus, PrefilterKeepsTheFullResolutionMean) {
  const Scored& s = scored("night_street");
  EXPECT_LT(std::abs(s.errors.at("default").bias - s.errors.at("no prefilter").bias), 0.003 * s.ref.peak);
}

// Specular pixels stay out of the colour pyramid (kernels/color_pyramid.cl). On a glossy table
// with lamps standing on it, averaging the table's own texels into the lamps' footprints spread
// their light where no ray collects it: measured on tabletop_cm, p99 of per-pixel error 0.147
// prefiltered against 0.106 at full resolution and mean signed error -0.183 against -0.163 before;
// 0.109 against 0.105 and -0.169 against -0.163 with the hit-weighted pyramid; since neighbours'
// rays are spread over their lobes (kernels/sequence.cl) 0.089 against 0.075, and 0.111 with the
// specular pixels averaged in (1.49x).
TEST(Corpus, PrefilterLeavesSpecularPixelsOut) {
  const Scored& s = scored("tabletop_cm");
  const ReferenceError on = s.errors.at("default"), off = s.errors.at("no prefilter");
  EXPECT_LT(on.p99, 1.35 * off.p99);
  EXPECT_LT(std::abs(on.bias - off.bias), 0.015);
}

}  // namespace
