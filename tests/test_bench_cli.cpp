// `ssrcl bench` as a user runs it: a table, JSON with every measurement, an SVG plot, and the
// work counters agreeing with what the configurations ask for.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"

namespace {

using ssrcl::test::runCommand;
using ssrcl::test::shellQuote;

std::string cli(const std::string& args) { return shellQuote(SSRCL_CLI) + " " + args; }

TEST(BenchCli, GeneratedSceneTableJsonAndPlot) {
  ssrcl::test::TempDir dir("ssrcl-bench");
  const std::string json = dir.file("bench.json"), svg = dir.file("bench.svg");
  auto r = runCommand(cli("bench --scene half_sky --size 96x54 --repetitions 2 --reference-spp 8 --quality draft medium "
                          "--tracers hiz linear --spp 8 --json " + shellQuote(json) + " --plot " + shellQuote(svg)));
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

}  // namespace
