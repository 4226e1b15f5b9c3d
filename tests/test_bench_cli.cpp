// `ssrcl bench` as a user runs it: a table, JSON with every measurement, an SVG plot, and the
// work counters agreeing with what the configurations ask for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

namespace {

using ssrcl::test::runCommand;
using ssrcl::test::shellQuote;

std::string cli(const std::string& args) { return shellQuote(SSRCL_CLI) + " " + args; }

TEST(BenchCli, GeneratedSceneTableJsonAndPlot) {
  ssrcl::test::TempDir dir("ssrcl-bench");
  const std::string json = dir.file("bench.json"), svg = dir.file("bench.svg");
  auto r =
      runCommand(cli("bench --scene half_sky --size 96x54 --repetitions 2 --reference-spp 8 --quality draft medium "
                     "--tracers hiz linear --spp 8 --json " +
                     shellQuote(json) + " --plot " + shellQuote(svg)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* row : {"draft", "medium", "medium, linear tracer", "medium, 8 rays"})
    EXPECT_NE(r.output.find(row), std::string::npos) << row << "\n" << r.output;

  const auto j = nlohmann::json::parse(ssrcl::test::readBytes(json));
  ASSERT_EQ(j["results"].size(), 4u);
  std::map<std::string, nlohmann::json> byConfig;
  for (const auto& e : j["results"]) byConfig[e["config"]] = e;
  for (const auto& [name, e] : byConfig) {
    SCOPED_TRACE(name);
    EXPECT_EQ(e["width"], 96);
    for (const char* stage : {"setup", "hzb", "trace", "resolve", "total"}) {
      EXPECT_GE(e["stages_ms"][stage]["median"].get<double>(), e["stages_ms"][stage]["min"].get<double>()) << stage;
    }
    EXPECT_GT(e["rays_per_second"].get<double>(), 0);
    EXPECT_GT(e["depth_fetches_per_ray"].get<double>(), 0);
    EXPECT_GT(e["device_mib_per_megapixel"].get<double>(), 0);
    const double rmse = e["error_vs_reference"]["rmse"];
    EXPECT_TRUE(std::isfinite(rmse) && rmse >= 0);
    // The histogram counts every ray that was marched: never more than the rays launched.
    long long counted = 0;
    for (long long n : e["iteration_histogram"]) counted += n;
    EXPECT_GT(counted, 0);
    EXPECT_LE(counted, e["rays"].get<long long>());
  }
  // Half the frame is sky, and sky pixels get no rays.
  const long long pixels = 96 * 54;
  EXPECT_LT(byConfig["medium"]["pixels_traced"].get<long long>(), pixels * 3 / 4);
  EXPECT_EQ(byConfig["medium"]["rays"].get<long long>(), 4 * byConfig["medium"]["pixels_traced"].get<long long>());
  EXPECT_EQ(byConfig["medium, 8 rays"]["rays"].get<long long>(), 2 * byConfig["medium"]["rays"].get<long long>());
  // Draft traces one pixel of each 2x2 block, 2 rays each: about an eighth of medium's rays.
  EXPECT_LT(byConfig["draft"]["rays"].get<long long>(), byConfig["medium"]["rays"].get<long long>() / 6);
  // The linear march reads far more texels per ray than the hierarchy.
  EXPECT_GT(byConfig["medium, linear tracer"]["depth_fetches_per_ray"].get<double>(),
            3 * byConfig["medium"]["depth_fetches_per_ray"].get<double>());

  const std::string plot = ssrcl::test::readBytes(svg);
  EXPECT_EQ(plot.rfind("<svg", 0), 0u);
  for (const char* label : {"draft", "medium", "half_sky"}) EXPECT_NE(plot.find(label), std::string::npos) << label;
}

// The adaptive-work and equal-error rows: classification changes the work dispatched, not the
// output; ray counts follow roughness; coarser linear steps read fewer texels.
TEST(BenchCli, AdaptiveWorkAndLinearStepRows) {
  ssrcl::test::TempDir dir("ssrcl-bench");
  const std::string json = dir.file("bench.json");
  auto r =
      runCommand(cli("bench --scene half_sky --size 97x55 --scene-roughness 0.3 --repetitions 1 --reference-spp 8 "
                     "--quality medium --tracers hiz --unclassified --full-rays-roughness 0.6 --linear-steps 0.5 2 "
                     "--json " +
                     shellQuote(json)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto j = nlohmann::json::parse(ssrcl::test::readBytes(json));
  std::map<std::string, nlohmann::json> byConfig;
  for (const auto& e : j["results"]) byConfig[e["config"]] = e;
  ASSERT_EQ(byConfig.size(), 5u) << r.output;
  const auto& medium = byConfig["medium"];
  const auto& unclassified = byConfig["medium, unclassified"];
  const auto& adaptive = byConfig["medium, full rays at r0.6"];
  EXPECT_EQ(unclassified["tiles_resolved"].get<long long>(), 13 * 7);  // every tile of 97x55
  EXPECT_LT(medium["tiles_resolved"].get<long long>(), 13 * 7);
  EXPECT_EQ(unclassified["rays"], medium["rays"]);
  EXPECT_EQ(unclassified["error_vs_reference"]["rmse"], medium["error_vs_reference"]["rmse"]);
  // Roughness 0.3 of full rays at 0.6: ceil(4 * 0.5) = 2 rays per pixel instead of 4.
  EXPECT_EQ(2 * adaptive["rays"].get<long long>(), medium["rays"].get<long long>());
  EXPECT_GT(byConfig["medium, linear 0.5 px"]["depth_fetches_per_ray"].get<double>(),
            1.5 * byConfig["medium, linear 2 px"]["depth_fetches_per_ray"].get<double>());
}

// The RMSE, PSNR and >5% columns (which docs/BENCHMARKS.md quotes) against the same measures
// computed here, in double, from the pass and the reference the library gives for the same
// generated scene: the bench must score the preset's pass, against the reference preset, over
// the pixels that reflect.
TEST(BenchCli, ErrorColumnsMeasureThePassAgainstTheReference) {
  ssrcl::test::TempDir dir("ssrcl-bench");
  const std::string json = dir.file("bench.json");
  const int w = 96, h = 54, spp = 16;
  const float roughness = 0.3f;
  auto r = runCommand(cli("bench --scene spheres_on_mirror --size 96x54 --scene-roughness 0.3 --repetitions 1 "
                          "--reference-spp 16 --quality medium --tracers hiz --json " +
                          shellQuote(json)));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const auto j = nlohmann::json::parse(ssrcl::test::readBytes(json));
  ASSERT_EQ(j["results"].size(), 1u);
  const auto& error = j["results"][0]["error_vs_reference"];

  const ssrcl::test::Scene scene = ssrcl::test::makeScene("spheres_on_mirror");
  const ssrcl::Camera camera = ssrcl::test::makeCamera(scene.view, w, h);
  ssrcl::GBuffer g = ssrcl::test::renderGBuffer(scene, camera);
  for (float& v : g.roughness.data) v = roughness;
  ssrcl::Device device = ssrcl::test::testDevice();
  const auto run = [&](const char* preset, int samples) {
    ssrcl::Pipeline p(device);
    p.setGBuffer(g);
    p.setCamera(camera);
    p.settings() = ssrcl::qualityPreset(preset);
    if (samples) p.settings().samplesPerPixel = samples;
    p.commit();
    p.execute();
    return p.output("reflection");
  };
  const ssrcl::Image pass = run("medium", 0), reference = run("reference", spp);
  const float maxRoughness = ssrcl::qualityPreset("medium").maxRoughness;
  const auto lum = [](const ssrcl::Image& im, int i) {
    return 0.2126 * im.data[4 * i] + 0.7152 * im.data[4 * i + 1] + 0.0722 * im.data[4 * i + 2];
  };
  std::vector<int> reflecting;
  double peak = 0;
  for (int i = 0; i < w * h; ++i) {
    const float d = g.depth.data[i];
    if (!(d >= camera.nearPlane && d <= camera.farPlane) || roughness > maxRoughness) continue;
    reflecting.push_back(i);
    for (int c = 0; c < 3; ++c) peak = std::max(peak, double(reference.data[4 * i + c]));
  }
  ASSERT_GT(reflecting.size(), size_t(w * h / 4));
  double se = 0, over = 0;
  for (int i : reflecting) {
    for (int c = 0; c < 3; ++c) se += std::pow(double(pass.data[4 * i + c]) - reference.data[4 * i + c], 2);
    over += std::abs(lum(pass, i) - lum(reference, i)) > 0.05 * std::max(lum(reference, i), 0.01 * peak);
  }
  const double rmse = std::sqrt(se / (3.0 * reflecting.size()));
  std::cout << "bench error columns: rmse " << error["rmse"] << " (here " << rmse << "), psnr " << error["psnr_db"]
            << ", >5% " << error["fraction_over_5_percent"] << " (here " << over / reflecting.size() << ")\n";
  ASSERT_GT(rmse, 0.0);  // a scene where the preset does differ from the reference
  EXPECT_NEAR(error["rmse"].get<double>(), rmse, 1e-6 * rmse + 1e-9);
  EXPECT_NEAR(error["psnr_db"].get<double>(), 20 * std::log10(peak / rmse), 1e-4);
  EXPECT_NEAR(error["fraction_over_5_percent"].get<double>(), over / reflecting.size(), 1e-12);
}

TEST(BenchCli, BadOptionsAreUsageErrors) {
  auto r = runCommand(cli("bench --scene nowhere --size 64x32 --no-reference"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("nowhere"), std::string::npos) << r.output;
  r = runCommand(cli("bench --scene half_sky --size 64by32 --no-reference"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--size"), std::string::npos) << r.output;
  r = runCommand(cli("bench --scene half_sky --size 64x32 --no-reference --plot /tmp/never.svg"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("never.svg"), std::string::npos) << r.output;
}

// The native roofline is a program of bench/, not of the installed CLI: `ssrcl bench --roofline`
// says where it is, and that program prints its table with the OpenCL and native hits agreeing
// (they trace the same rays: test_native_roofline).
TEST(BenchCli, RooflineIsTheBenchProgram) {
  auto r = runCommand(cli("bench --scene mirror_wall --size 64x36 --roofline"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("bench/ssrcl_roofline"), std::string::npos) << r.output;

  const char* device = std::getenv("SSRCL_TEST_DEVICE");
  r = runCommand(shellQuote(SSRCL_ROOFLINE) + " --scene spheres_on_mirror --scene-roughness 0 --size 96x54 " +
                 "--repetitions 1 --device " + (device ? device : "cpu"));
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* row : {"Native roofline", "setup ", "hzb ", "trace ", "OpenCL / native"})
    EXPECT_NE(r.output.find(row), std::string::npos) << row << "\n" << r.output;
  const size_t at = r.output.find("hits agree on ");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_GE(std::stod(r.output.substr(at + 14)), 99.9) << r.output;
}

}  // namespace
