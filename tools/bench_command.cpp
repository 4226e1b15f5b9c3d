#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "bench_inputs.hpp"
#include "bench_report.hpp"
#include "bench_runner.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "settings_options.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::cli {
namespace {

struct BenchOptions {
  BenchInputOptions inputs;
  std::string device, json, plot;
  std::vector<std::string> qualities{"draft", "medium", "high"}, tracers{"hiz", "dda", "linear"};
  std::vector<int> sppList;
  std::vector<float> fullRaysRoughness, linearSteps;
  int repetitions = 3, referenceSpp = 64;
  bool noReference = false, unclassified = false, roofline = false;
};

std::vector<BenchConfig> configurations(const BenchOptions& o) {
  std::vector<BenchConfig> configs;
  for (const std::string& q : o.qualities) configs.push_back({q, qualityPreset(q)});
  // Every other row is the medium preset with one knob changed, named "medium, " + label.
  const auto medium = [&configs](const auto& change, const auto&... label) {
    TraceSettings s = qualityPreset("medium");
    change(s);
    std::ostringstream name;
    (name << "medium, " << ... << label);
    configs.push_back({name.str(), s});
  };
  // The tracers on equal terms: the medium preset's rays, each tracer.
  for (const std::string& t : o.tracers) {
    if (t == "hiz" && std::find(o.qualities.begin(), o.qualities.end(), "medium") != o.qualities.end()) continue;
    medium([&](TraceSettings& s) { selectTracer(s, t); }, t, " tracer");
  }
  for (int spp : o.sppList) medium([&](TraceSettings& s) { s.samplesPerPixel = spp; }, spp, " rays");
  // Coarser linear steps trade its accuracy for time: where its error meets Hi-Z's is the
  // equal-error comparison.
  for (float step : o.linearSteps)
    medium(
        [&](TraceSettings& s) {
          selectTracer(s, "linear");
          s.linearStepPixels = step;
        },
        "linear ", step, " px");
  for (float r : o.fullRaysRoughness) medium([&](TraceSettings& s) { s.fullRaysRoughness = r; }, "full rays at r", r);
  if (o.unclassified) medium([](TraceSettings& s) { s.classifyWork = false; }, "unclassified");
  return configs;
}

// How cost grows with pixels: median total time and time per megapixel, per configuration.
void printScaling(std::ostream& out, const std::vector<BenchResult>& results) {
  std::map<std::string, std::vector<const BenchResult*>> byConfig;
  std::vector<std::string> order;
  for (const BenchResult& r : results) {
    if (!byConfig.count(r.config)) order.push_back(r.config);
    byConfig[r.config].push_back(&r);
  }
  out << "\nScaling (median total ms, and ms per megapixel):\n";
  for (const std::string& c : order) {
    out << "  " << std::left << std::setw(26) << c << std::right;
    for (const BenchResult* r : byConfig[c]) {
      const double ms = r->stages.at("total").medianMs;
      out << "  " << r->width << "x" << r->height << ": " << std::fixed << std::setprecision(1) << ms << " ("
          << ms / (r->width * double(r->height) * 1e-6) << "/MP)";
    }
    out << "\n";
  }
}

int runBenchCommand(const BenchOptions& o) {
  // The native roofline is a benchmark of the source tree, not of the installed product.
  if (o.roofline)
    throw Error(ErrorCode::InvalidArgument,
                "--roofline: the native roofline is not part of the installed ssrcl; it is the program "
                "bench/ssrcl_roofline of a build with tests, taking the inputs `ssrcl bench` takes");
  const std::vector<BenchInput> inputs = loadBenchInputs(o.inputs);
  Device device = openDevice(o.device);
  const std::vector<BenchConfig> configs = configurations(o);
  std::vector<BenchResult> results;
  for (const BenchInput& input : inputs) {
    std::cerr << "bench: " << input.name << "..." << std::endl;
    Image reference;
    if (!o.noReference) reference = referencePass(device, input, o.referenceSpp);
    auto r = runBench(device, input, configs, o.repetitions, o.noReference ? nullptr : &reference);
    results.insert(results.end(), r.begin(), r.end());
  }
  const std::string deviceName = device.info().name;
  printBenchTable(std::cout, results, deviceName);
  if (!o.inputs.scene.empty() && o.inputs.sizes.size() > 1) printScaling(std::cout, results);
  if (!o.json.empty()) writeBenchJson(o.json, results, deviceName);
  if (!o.plot.empty()) writeBenchSvg(o.plot, results, deviceName);
  return kExitOk;
}

}  // namespace

Action addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Measure time and error of quality settings and tracers");
  addBenchInputOptions(*cmd, o->inputs);
  cmd->add_option("--quality", o->qualities, "Presets to measure")
      ->capture_default_str()
      ->check(CLI::IsMember({"draft", "medium", "high", "reference"}));
  cmd->add_option("--tracers", o->tracers,
                  "Tracers to compare at the medium preset's rays (dda and linear march to the screen edge)")
      ->capture_default_str()
      ->check(CLI::IsMember({"hiz", "dda", "linear"}));
  cmd->add_option("--spp", o->sppList, "Also the medium preset at these rays per pixel");
  cmd->add_option("--linear-steps", o->linearSteps, "Also the linear tracer at these step lengths (pixels)")
      ->check(CLI::Range(0.05f, 8.0f));
  cmd->add_option("--full-rays-roughness", o->fullRaysRoughness,
                  "Also the medium preset with ray counts following roughness, full from these roughnesses")
      ->check(CLI::Range(0.0f, 1.0f));
  cmd->add_flag("--unclassified", o->unclassified,
                "Also the medium preset dispatching every pixel and tile (no work classification)");
  cmd->add_option("--repetitions", o->repetitions, "Timed runs per configuration (after one warm-up)")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--reference-spp", o->referenceSpp,
                  "Rays per pixel of the reference pass errors are measured against")
      ->capture_default_str()
      ->check(CLI::Range(1, 65536));
  cmd->add_flag("--roofline", o->roofline,
                "Not in the installed CLI: says where the native roofline benchmark is (bench/ssrcl_roofline)");
  cmd->add_flag("--no-reference", o->noReference, "Skip the reference pass and the error columns");
  cmd->add_option("--device", o->device, "OpenCL device: index from `ssrcl devices`, cpu, gpu or default");
  cmd->add_option("--json", o->json, "Write every measurement as JSON");
  cmd->add_option("--plot", o->plot, "Write an SVG plot of error against time (the Pareto front)");
  return [o] { return runBenchCommand(*o); };
}

}  // namespace ssrcl::cli
