#include <iomanip>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>

#include "bench_inputs.hpp"
#include "bench_report.hpp"
#include "bench_roofline.hpp"
#include "bench_runner.hpp"
#include "commands.hpp"
#include "exit_codes.hpp"
#include "settings_options.hpp"

namespace ssrcl::cli {
namespace {

struct BenchOptions {
  std::vector<std::string> files, samples, sizes{"1920x1080"};
  std::string scene, device, json, plot, sampleDir;
  float sceneRoughness = 0.3f;
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
  std::vector<BenchInput> inputs;
  for (const std::string& f : o.files) inputs.push_back(loadBenchFile(f));
  for (const std::string& s : o.samples) inputs.push_back(loadBundledSample(s, o.sampleDir));
  if (!o.scene.empty())
    for (const std::string& size : o.sizes) {
      const auto [w, h] = parseSize(size, "--size");
      inputs.push_back(generateScene(o.scene, w, h, o.sceneRoughness));
    }
  if (inputs.empty())
    for (const char* s : {"mirror", "glossy"}) inputs.push_back(loadBundledSample(s, o.sampleDir));

  Device device = openDevice(o.device);
  const std::vector<BenchConfig> configs = configurations(o);
  std::vector<BenchResult> results;
  std::vector<RooflineResult> rooflines;
  for (const BenchInput& input : inputs) {
    std::cerr << "bench: " << input.name << "..." << std::endl;
    Image reference;
    if (!o.noReference) reference = referencePass(device, input, o.referenceSpp);
    auto r = runBench(device, input, configs, o.repetitions, o.noReference ? nullptr : &reference);
    results.insert(results.end(), r.begin(), r.end());
    if (o.roofline) rooflines.push_back(runRoofline(device, input, o.repetitions));
  }
  const std::string deviceName = device.info().name;
  printBenchTable(std::cout, results, deviceName);
  if (!o.scene.empty() && o.sizes.size() > 1) printScaling(std::cout, results);
  if (o.roofline) printRoofline(std::cout, rooflines);
  if (!o.json.empty()) writeBenchJson(o.json, results, deviceName);
  if (!o.plot.empty()) writeBenchSvg(o.plot, results, deviceName);
  return kExitOk;
}

}  // namespace

Action addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Measure time and error of quality settings and tracers");
  cmd->add_option("inputs", o->files, "G-buffer EXRs (Blender naming, <stem>.camera.json beside each)");
  cmd->add_option("--sample", o->samples, "Bundled sample: mirror, glossy (default: both, when no input is given)")
      ->check(CLI::IsMember({"mirror", "glossy"}));
  cmd->add_option("--sample-dir", o->sampleDir,
                  "Directory holding the bundled samples (mirror/, glossy/); default: share/ssrcl/samples of the "
                  "installation")
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--scene", o->scene, "Generated analytic scene: spheres_on_mirror, mirror_wall, half_sky");
  cmd->add_option("--size", o->sizes, "Resolution(s) of the generated scene, e.g. 480x270 1920x1080")
      ->capture_default_str();
  cmd->add_option("--scene-roughness", o->sceneRoughness, "Roughness of every surface of the generated scene")
      ->capture_default_str()
      ->check(CLI::Range(0.0f, 1.0f));
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
                "Also time each input's mirror pass against a native C++ implementation of the same rays "
                "(OpenCL / native per stage, and whether their hits agree)");
  cmd->add_flag("--no-reference", o->noReference, "Skip the reference pass and the error columns");
  cmd->add_option("--device", o->device, "OpenCL device: index from `ssrcl devices`, cpu, gpu or default");
  cmd->add_option("--json", o->json, "Write every measurement as JSON");
  cmd->add_option("--plot", o->plot, "Write an SVG plot of error against time (the Pareto front)");
  return [o] { return runBenchCommand(*o); };
}

}  // namespace ssrcl::cli
