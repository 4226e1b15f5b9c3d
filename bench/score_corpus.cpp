// Scores configurations of ssrcl against Cycles' path-traced glossy passes over a corpus of
// scenes (samples/corpus) and prints one table: per scene PSNR, then the means over the tuning
// scenes, the held-out scenes and all, with time, the share of squared error on low-confidence
// pixels and the 99th percentile of per-pixel error; then speckle, over the pixels every scored pass
// answers (A >= 0.5, so the off-screen hole, which no filter can fix, is left out): the 99th
// percentile of error, the fireflies and the mean signed error there (the paired difference of two
// rows that trace the same rays is their bias against each other), and with --noise the pass's own
// noise, which needs no reference: the 99th percentile of |pass(seed) - pass(seed + 1)| / sqrt 2. See
// tests/support/cycles_reference.hpp for what is compared with what, and scripts/score-corpus.sh
// for the command.
//
//   ssrcl_score_corpus --corpus samples/corpus [--configs medium,high,...] [--scenes a,b] [--json out.json]
//   ssrcl_score_corpus render.exr ... [--configs ...]   (renders of one's own, split "file")
//   ssrcl_score_corpus --scenes interior_room --configs "medium;medium:views=all" [--views DIR]
//       (auxiliary views, default samples/corpus/views)
//   ssrcl_score_corpus --corpus samples/corpus/environment --environment samples/corpus/environment/sky.exr
//       --configs "medium;medium:fill=0;eevee"   (environment fill: filled, premultiplied, EEVEE)
//   ssrcl_score_corpus --corpus samples/real   (scenes with an "environment" in corpus.json get that fill)
//   ssrcl_score_corpus --corpus samples/real --configs "pass:out/before;pass:out/after"
//       (passes another build of `ssrcl trace --output-form glossy-pass` wrote: <dir>/<scene>.exr; with
//        --noise, those of the next seed in <dir>/seed2/<scene>.exr)
//
// A configuration is a preset name, optionally with settings after a colon:
//   medium   high:spp=32   medium:thickness=0.01   medium:model=constant,thickness=0.005
// Keys: thickness (constant), model (adaptive|constant), scale, tmin, tmax (adaptive), back (1: the
// scene's back-face depth pass <scene>.back.exr, samples/blender/render_back_faces.py),
// hits (bounce, the default: hits on glossy pixels continue, with the render's glossy passes;
// screen: they take the screen colour), materials (1, the default: those hits are shaded with
// each pixel's F0 from the render's base_color / metallic AOVs where it has them, as `ssrcl trace`
// does with them loaded; 0: without, specular colour alone),
// hitroughness, spp, fullrays (fullRaysRoughness: smoother pixels get proportionally fewer rays),
// reuse, denoise, separable (1: the filter in two passes), prefilter, edges (edge colours), tracer, step, seed,
// stride, iterations, fade (the edge fade, a fraction of the smaller side), form (incident, the
// default: our pass times E(F0 = 1) here; glossy-pass: the
// pass `ssrcl trace --output-form glossy-pass` writes, compared with Cycles as it is, F0 from the
// render's base_color / metallic AOVs where it has them, else 1 as the corpus's reflectors have),
// metal (1: where the render has no material AOVs, the glossy-pass form is given the corpus's
// reflectors as what they are, base colour 1 and metallic 1, rather than an F0 pass of 1: its pure
// metal pixels then take their render's colour; the trace is the same).
// views (auxiliary views: the first N of <views dir>/<scene>.*.exr in name order, "all" every one;
// samples/blender/make_views.py renders them; default 0),
// "eevee" scores Blender EEVEE's own SSR (<scene>.eevee.exr) where it exists; "eevee:form=glossy-pass"
// its Specular Light x Specular Color against Cycles as it is (needs GlossCol in the EEVEE file).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bench_report.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/cycles_reference.hpp"
#include "support/shot_metric.hpp"

namespace {

struct Scene {
  std::string name, split, path;
  std::string environment;  // the HDRI the scene was lit by (corpus.json "environment"), or empty
};

struct Config {
  std::string label;
  bool eevee = false;
  bool glossyPasses = true;  // base and specular from the render's glossy passes, as `ssrcl trace` reads them
  bool materials = true;     // the render's material AOVs, where it has them, for those hits
  bool glossyPassForm = false;  // score the glossy-pass output form
  bool metal = false;           // the corpus rule as metallic 1, base colour 1 for that form (key "metal")
  bool fill = true;             // with --environment: misses take it (fill=0: the premultiplied pass)
  size_t views = 0;             // auxiliary views used (SIZE_MAX: all found)
  bool backDepth = false;       // the scene's back-face depth pass, <scene>.back.exr beside it
  std::string passDir;          // "pass:DIR": score <DIR>/<scene>.exr, a glossy-pass form pass written elsewhere
  ssrcl::TraceSettings settings;
};

std::vector<std::string> splitList(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, sep);)
    if (!item.empty()) out.push_back(item);
  return out;
}

Config parseConfig(const std::string& spec) {
  Config c{spec};
  const auto colon = spec.find(':');
  const std::string preset = spec.substr(0, colon);
  if (preset == "pass") {  // pass:DIR, e.g. another build's passes, scored by this build's measure
    if (colon == std::string::npos || colon + 1 == spec.size())
      throw std::runtime_error("configuration '" + spec + "': pass takes a directory, pass:DIR");
    c.passDir = spec.substr(colon + 1);
    c.glossyPassForm = true;
    return c;
  }
  if (preset == "eevee") {  // eevee, or eevee:form=glossy-pass (Specular Light x Specular Color)
    c.eevee = true;
    if (colon == std::string::npos) return c;
    if (spec.substr(colon + 1) != "form=glossy-pass")
      throw std::runtime_error("configuration '" + spec + "': eevee takes only form=glossy-pass");
    c.glossyPassForm = true;
    return c;
  }
  c.settings = ssrcl::qualityPreset(preset);
  if (colon == std::string::npos) return c;
  for (const std::string& kv : splitList(spec.substr(colon + 1), ',')) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos) throw std::runtime_error("configuration '" + spec + "': expected key=value");
    const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
    ssrcl::TraceSettings& s = c.settings;
    if (key == "thickness") {
      s.thicknessRelative = std::stof(value);
      s.thicknessModel = ssrcl::ThicknessModel::Constant;
    } else if (key == "model") {
      s.thicknessModel = value == "constant" ? ssrcl::ThicknessModel::Constant : ssrcl::ThicknessModel::Adaptive;
    } else if (key == "scale") {
      s.thicknessScale = std::stof(value);
    } else if (key == "tmin") {
      s.thicknessMinRelative = std::stof(value);
    } else if (key == "tmax") {
      s.thicknessMaxRelative = std::stof(value);
    } else if (key == "hits") {  // screen | bounce: how hits on glossy pixels are shaded
      c.glossyPasses = value == "bounce";
    } else if (key == "materials") {
      c.materials = value == "1";
    } else if (key == "hitroughness") {
      s.glossyHitRoughness = std::stof(value);
    } else if (key == "spp") {
      s.samplesPerPixel = std::stoi(value);
    } else if (key == "fullrays") {
      s.fullRaysRoughness = std::stof(value);
    } else if (key == "reuse") {
      s.reuseRadius = std::stoi(value);
    } else if (key == "denoise") {
      s.denoise = value == "1";
    } else if (key == "separable") {
      s.separableDenoise = value == "1";
    } else if (key == "prefilter") {
      s.prefilter = value == "1";
    } else if (key == "edges") {
      s.edgeColors = value == "1";
    } else if (key == "tracer") {
      s.tracer = value == "linear" ? ssrcl::Tracer::Linear : value == "dda" ? ssrcl::Tracer::DDA : ssrcl::Tracer::HiZ;
      if (s.tracer != ssrcl::Tracer::HiZ) s.maxIterations = ssrcl::qualityPreset("reference").maxIterations;
    } else if (key == "step") {
      s.linearStepPixels = std::stof(value);
    } else if (key == "seed") {
      s.seed = std::stoul(value);
    } else if (key == "stride") {
      s.traceStride = std::stoi(value);
    } else if (key == "form") {
      if (value != "incident" && value != "glossy-pass")
        throw std::runtime_error("configuration '" + spec + "': form is incident or glossy-pass");
      c.glossyPassForm = value == "glossy-pass";
    } else if (key == "metal") {
      c.metal = value == "1";
    } else if (key == "fill") {
      c.fill = value == "1";
    } else if (key == "views") {
      c.views = value == "all" ? SIZE_MAX : std::stoul(value);
    } else if (key == "back") {
      c.backDepth = value == "1";
    } else if (key == "iterations") {
      s.maxIterations = std::stoi(value);
    } else if (key == "fade") {
      s.edgeFade = std::stof(value);
    } else {
      throw std::runtime_error("configuration '" + spec + "': unknown key '" + key + "'");
    }
  }
  return c;
}

std::vector<Scene> loadScenes(const std::string& corpus, const std::vector<std::string>& only) {
  std::ifstream in(corpus + "/corpus.json");
  if (!in) throw std::runtime_error(corpus + "/corpus.json: cannot read");
  const nlohmann::json manifest = nlohmann::json::parse(in);
  std::vector<Scene> scenes;
  for (const auto& s : manifest.at("scenes")) {
    const std::string name = s.at("name");
    if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
    const std::string environment = s.value("environment", std::string());
    scenes.push_back({name, s.at("split"), corpus + "/" + name + ".exr",
                      environment.empty() ? environment : corpus + "/" + environment});
  }
  return scenes;
}

// A scene's auxiliary views: <dir>/<scene>.*.exr in name order, each with its camera sidecar.
struct SceneViews {
  std::vector<std::string> files;
  std::vector<ssrcl::GBuffer> gbuffers;
  std::vector<ssrcl::Camera> cameras;
};

SceneViews loadSceneViews(const std::string& dir, const std::string& scene) {
  SceneViews v;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(scene + ".", 0) == 0 && entry.path().extension() == ".exr") v.files.push_back(entry.path().string());
  }
  std::sort(v.files.begin(), v.files.end());
  for (const std::string& f : v.files) {
    ssrcl::GBufferSource source;
    source.file = f;
    source.glossyPasses = false;
    v.gbuffers.push_back(ssrcl::loadGBuffer(source));
    const std::filesystem::path p(f);
    v.cameras.push_back(ssrcl::loadCameraJson((p.parent_path() / (p.stem().string() + ".camera.json")).string()));
  }
  return v;
}

// Ours (times E), Cycles, |difference| (each divided by the peak), our confidence A and the input
// colour side by side, sRGB-ish gamma: a binary PPM to see where a configuration's error is.
void writeComparison(const std::string& path, const ssrcl::test::CyclesReference& ref, const ssrcl::Image& pass) {
  const int w = ref.gbuffer.depth.width, h = ref.gbuffer.depth.height;
  constexpr int kPanels = 5;
  std::vector<unsigned char> rgb(size_t(kPanels * w) * h * 3, 0);
  auto put = [&](int panel, int i, int c, double v) {
    const double g = std::pow(std::clamp(v, 0.0, 1.0), 1 / 2.2);
    rgb[(size_t(i / w) * kPanels * w + panel * w + i % w) * 3 + c] = static_cast<unsigned char>(255 * g + 0.5);
  };
  for (int i = 0; i < w * h; ++i)
    for (int c = 0; c < 3; ++c) put(4, i, c, ref.gbuffer.color.data[3 * size_t(i) + c]);
  for (size_t k = 0; k < ref.pixels.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const double ours = ref.scale[k] * pass.data[pass.channels * size_t(ref.pixels[k]) + c];
      const double cycles = ref.cycles[3 * k + c];
      put(0, ref.pixels[k], c, ours / ref.peak);
      put(1, ref.pixels[k], c, cycles / ref.peak);
      put(2, ref.pixels[k], c, std::abs(ours - cycles) / ref.peak);
      if (pass.channels == 4) put(3, ref.pixels[k], c, pass.data[4 * size_t(ref.pixels[k]) + 3]);
    }
  std::ofstream f(path, std::ios::binary);
  f << "P6\n" << kPanels * w << " " << h << "\n255\n";
  f.write(reinterpret_cast<const char*>(rgb.data()), std::streamsize(rgb.size()));
  // The first two panels unclipped, for per-pixel error analysis: ours (times E) and Cycles side by
  // side as a little-endian PFM (rows bottom to top), 0 off the reflector.
  std::vector<float> pfm(size_t(2 * w) * h * 3, 0.0f);
  for (size_t k = 0; k < ref.pixels.size(); ++k)
    for (int c = 0; c < 3; ++c) {
      const int x = ref.pixels[k] % w, y = h - 1 - ref.pixels[k] / w;
      pfm[(size_t(y) * 2 * w + x) * 3 + c] = float(ref.scale[k] * pass.data[pass.channels * size_t(ref.pixels[k]) + c]);
      pfm[(size_t(y) * 2 * w + w + x) * 3 + c] = float(ref.cycles[3 * k + c]);
    }
  std::ofstream g(path.substr(0, path.size() - 4) + ".pfm", std::ios::binary);
  g << "PF\n" << 2 * w << " " << h << "\n-1.0\n";
  g.write(reinterpret_cast<const char*>(pfm.data()), std::streamsize(pfm.size() * sizeof(float)));
}

std::string backDepthPath(const std::string& scene) {
  const std::filesystem::path p(scene);
  return (p.parent_path() / (p.stem().string() + ".back.exr")).string();
}

// The scene's back-face depth pass as `ssrcl trace --back-depth-file` reads it; empty without one.
ssrcl::Image sceneBackDepth(const std::string& scene, const ssrcl::Camera& camera) {
  if (!std::filesystem::exists(backDepthPath(scene))) return {};
  ssrcl::GBufferSource source;
  source.file = scene;
  source.backDepthFile = backDepthPath(scene);
  ssrcl::GBuffer g = ssrcl::loadGBuffer(source);
  ssrcl::applyInputConventions(g, source, camera);
  return g.backDepth;
}

struct Score {
  bool present = false;
  double ms = 0;
  ssrcl::test::ReferenceError error;
  ssrcl::test::ReferenceError answered;  // over the pixels every pass of the scene answers
  double noiseP99 = NAN;                 // --noise: p99 of |pass(seed) - pass(seed + 1)| / sqrt 2 there, / peak
};

// The 99th percentile over `group` of the channel mean of |a - b| / sqrt 2: one pass's own noise,
// from two of its seeds, relative to the peak.
double noiseP99(const ssrcl::test::CyclesReference& ref, const ssrcl::Image& a, const ssrcl::Image& b,
                const std::vector<size_t>& group) {
  std::vector<double> perPixel;
  for (size_t k : group) {
    const size_t i = size_t(ref.pixels[k]);
    double sum = 0;
    for (int c = 0; c < 3; ++c) sum += std::abs(a.data[a.channels * i + c] - b.data[b.channels * i + c]);
    perPixel.push_back(ref.scale[k] * sum / (3 * std::sqrt(2.0)));
  }
  if (perPixel.empty()) return NAN;
  std::nth_element(perPixel.begin(), perPixel.begin() + perPixel.size() * 99 / 100, perPixel.end());
  return perPixel[perPixel.size() * 99 / 100] / ref.peak;
}

// The reflector pixels (indices into ref.pixels) that every pass answers, A >= 0.5; a pass without
// A (EEVEE's) answers all.
std::vector<size_t> answeredByAll(const std::vector<size_t>& all, const std::vector<const ssrcl::Image*>& passes,
                                  const ssrcl::test::CyclesReference& ref) {
  std::vector<size_t> answered;
  for (size_t k : all) {
    const size_t i = size_t(ref.pixels[k]);
    if (std::all_of(passes.begin(), passes.end(),
                    [&](const ssrcl::Image* p) { return p->channels != 4 || p->data[4 * i + 3] >= 0.5f; }))
      answered.push_back(k);
  }
  return answered;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Scores ssrcl configurations against Cycles over a corpus of scenes"};
  std::string corpus = std::string(SSRCL_SOURCE_DIR) + "/samples/corpus", jsonPath, plotPath;
  std::string configList = "draft,medium,high,reference,eevee", sceneList;
  std::string dumpDir, environmentPath, viewsDir;
  std::vector<std::string> files;
  int repetitions = 1;
  bool noise = false;
  app.add_option("files", files, "Renders to score instead of the corpus (Blender passes, IndexOB 1 = reflector)");
  app.add_option("--corpus", corpus, "Directory with corpus.json and the scenes")->capture_default_str();
  app.add_option("--configs", configList, "Comma-separated configurations (';' also separates)")->capture_default_str();
  app.add_option("--scenes", sceneList, "Only these scenes (comma-separated)");
  app.add_option("--repetitions", repetitions, "Timed runs per configuration (the minimum is reported)");
  app.add_option("--json", jsonPath, "Write every figure as JSON");
  app.add_option("--plot", plotPath, "Write the corpus mean error against time as SVG");
  app.add_option("--environment", environmentPath,
                 "Environment fill from this equirect EXR for every scene (default: each scene's corpus.json "
                 "\"environment\", none where it has none; configs with fill=0 go without)");
  app.add_option("--views", viewsDir, "Auxiliary views of each scene: <dir>/<scene>.*.exr (default <corpus>/views)");
  app.add_flag("--noise", noise,
               "Also each pass's own noise: traced configurations again with the next seed; pass:DIR reads "
               "DIR/seed2/<scene>.exr");
  app.add_option("--dump", dumpDir,
                 "Write <scene>.<config index>.ppm: ours, Cycles and |difference| side by side (and .pfm: ours and "
                 "Cycles, unclipped)");
  CLI11_PARSE(app, argc, argv);

  try {
    // Configurations with settings hold commas: ';' separates them when any has settings (':').
    std::vector<Config> configs;
    const bool settings = configList.find_first_of(";:") != std::string::npos;
    for (const std::string& spec : splitList(configList, settings ? ';' : ','))
      configs.push_back(parseConfig(spec));
    std::vector<Scene> scenes;
    for (const std::string& f : files) scenes.push_back({std::filesystem::path(f).stem().string(), "file", f});
    if (files.empty()) scenes = loadScenes(corpus, splitList(sceneList, ','));
    if (scenes.empty()) throw std::runtime_error("no scenes selected");

    ssrcl::Device device(ssrcl::DeviceType::Default);
    const ssrcl::EnvironmentMap givenEnvironment =
        environmentPath.empty() ? ssrcl::EnvironmentMap{} : ssrcl::loadEnvironmentMap(environmentPath);
    std::vector<std::vector<Score>> scores(configs.size(), std::vector<Score>(scenes.size()));
    std::vector<double> answeredShare(scenes.size(), 0), peak(scenes.size(), 1);
    for (size_t s = 0; s < scenes.size(); ++s) {
      const ssrcl::test::CyclesReference ref = ssrcl::test::loadCyclesReference(scenes[s].path);
      const ssrcl::EnvironmentMap environment =
          !environmentPath.empty()          ? givenEnvironment
          : scenes[s].environment.empty() ? ssrcl::EnvironmentMap{}
                                          : ssrcl::loadEnvironmentMap(scenes[s].environment);
      const auto& all = ref.groups.front().second;
      // For the glossy-pass form: the render's material AOVs (samples/blender/
      // make_tinted_glossy_scene.py), or the corpus's white metal, F0 = 1; and Cycles unscaled.
      ssrcl::GBuffer withF0 = ref.gbuffer, asMetal;
      try {
        withF0 = ssrcl::test::withMaterialAovs(ref.gbuffer, scenes[s].path);
        asMetal = withF0;
      } catch (const ssrcl::Error&) {  // no material AOVs: the corpus's rule
        withF0.f0 = ssrcl::Image(withF0.color.width, withF0.color.height, 3);
        std::fill(withF0.f0.data.begin(), withF0.f0.data.end(), 1.0f);
        asMetal = ref.gbuffer;  // the same F0 (principledF0 of white at metallic 1)
        asMetal.baseColor = withF0.f0;
        asMetal.metallic = ssrcl::Image(withF0.color.width, withF0.color.height, 1);
        std::fill(asMetal.metallic.data.begin(), asMetal.metallic.data.end(), 1.0f);
      }
      ssrcl::test::CyclesReference unscaled = ref;
      std::fill(unscaled.scale.begin(), unscaled.scale.end(), 1.0);
      const SceneViews views = loadSceneViews(viewsDir.empty() ? corpus + "/views" : viewsDir, scenes[s].name);
      const ssrcl::Image backDepth = sceneBackDepth(scenes[s].path, ref.camera);
      ssrcl::Pipeline pipeline(device);
      pipeline.setGBuffer(ref.gbuffer);
      pipeline.setCamera(ref.camera);
      std::vector<ssrcl::Image> passes(configs.size()), seed2(configs.size());
      for (size_t c = 0; c < configs.size(); ++c) {
        Score& score = scores[c][s];
        if (configs[c].eevee || !configs[c].passDir.empty()) {
          const std::filesystem::path dir = configs[c].eevee ? std::filesystem::path(scenes[s].path).parent_path()
                                                             : std::filesystem::path(configs[c].passDir);
          const std::string path = (dir / (scenes[s].name + (configs[c].eevee ? ".eevee.exr" : ".exr"))).string();
          if (!std::filesystem::exists(path)) continue;
          passes[c] = configs[c].eevee ? ssrcl::test::eeveeSpecular(path, configs[c].glossyPassForm)
                                       : ssrcl::test::readReflectionPass(path);
          if (noise && !configs[c].eevee)
            seed2[c] = ssrcl::test::readReflectionPass((dir / "seed2" / (scenes[s].name + ".exr")).string());
          score.present = true;
          continue;
        }
        const ssrcl::Image none;
        pipeline.setImage("base", configs[c].glossyPasses ? ref.gbuffer.base : none);
        pipeline.setImage("specular", configs[c].glossyPasses ? ref.gbuffer.specular : none);
        const bool materials = configs[c].materials && withF0.f0.empty();  // the render's own AOVs
        pipeline.setImage("base_color", materials ? withF0.baseColor : none);
        pipeline.setImage("metallic", materials ? withF0.metallic : none);
        if (configs[c].backDepth && backDepth.empty())
          throw std::runtime_error(scenes[s].name + ": " + configs[c].label + " needs its back-face depth pass " +
                                   backDepthPath(scenes[s].path) + " (samples/blender/render_back_faces.py)");
        pipeline.setImage("back_depth", configs[c].backDepth ? backDepth : none);
        pipeline.settings() = configs[c].settings;
        const ssrcl::EnvironmentMap noEnvironment;
        pipeline.setEnvironment(configs[c].fill ? environment : noEnvironment);
        pipeline.clearViews();
        if (configs[c].views != SIZE_MAX && configs[c].views > views.files.size())
          throw std::runtime_error(scenes[s].name + ": " + configs[c].label + " asks for more views than the " +
                                   std::to_string(views.files.size()) + " found");
        for (size_t k = 0; k < std::min(configs[c].views, views.files.size()); ++k)
          pipeline.setView(int(k), views.gbuffers[k], views.cameras[k], views.files[k]);
        pipeline.commit();
        score.ms = INFINITY;
        for (int r = 0; r < std::max(1, repetitions); ++r) {
          pipeline.execute();
          double ms = 0;
          for (const auto& [stage, t] : pipeline.stageTimes().ms) ms += t;
          score.ms = std::min(score.ms, ms);
        }
        passes[c] = pipeline.output("reflection");
        if (noise) {
          pipeline.settings().seed += 1;
          pipeline.commit();
          pipeline.execute();
          seed2[c] = pipeline.output("reflection");
        }
        for (ssrcl::Image* p : {&passes[c], &seed2[c]})
          if (configs[c].glossyPassForm && !p->empty())
            ssrcl::applyGlossyPassForm(*p, configs[c].metal ? asMetal : withF0, ref.camera,
                                       configs[c].settings.constantRoughness);
        score.present = true;
      }
      std::vector<const ssrcl::Image*> present;
      for (size_t c = 0; c < configs.size(); ++c)
        if (scores[c][s].present) present.push_back(&passes[c]);
      const std::vector<size_t> answered = answeredByAll(all, present, ref);
      peak[s] = ref.peak;
      answeredShare[s] = double(answered.size()) / double(std::max<size_t>(all.size(), 1));
      for (size_t c = 0; c < configs.size(); ++c) {
        if (!scores[c][s].present) continue;
        const ssrcl::test::CyclesReference& against = configs[c].glossyPassForm ? unscaled : ref;
        scores[c][s].error = ssrcl::test::referenceError(against, passes[c], all);
        scores[c][s].answered = ssrcl::test::referenceError(against, passes[c], answered);
        if (!seed2[c].empty()) scores[c][s].noiseP99 = noiseP99(against, passes[c], seed2[c], answered);
        if (!dumpDir.empty() && !configs[c].eevee)
          writeComparison(dumpDir + "/" + scenes[s].name + "." + std::to_string(c) + ".ppm", against, passes[c]);
      }
      std::cerr << "scored " << scenes[s].name << " (" << all.size() << " reflector pixels; glossy-pass F0 from "
                << (withF0.f0.empty() ? "base_color + metallic AOVs" : "the corpus rule, 1") << ")\n";
    }

    // Table 1: PSNR per scene. Table 2: means per split, time, low-confidence share, p99.
    size_t labelWidth = 10;
    for (const Config& c : configs) labelWidth = std::max(labelWidth, c.label.size() + 2);
    std::cout << "device: " << device.info().name << "\nPSNR (dB) against Cycles, peak = 99.9th percentile\n"
              << std::left << std::setw(labelWidth) << "config" << std::right;
    for (const Scene& s : scenes) std::cout << std::setw(std::max<size_t>(8, s.name.size() + 1)) << s.name;
    std::cout << "\n" << std::fixed << std::setprecision(2);
    for (size_t c = 0; c < configs.size(); ++c) {
      std::cout << std::left << std::setw(labelWidth) << configs[c].label << std::right;
      for (size_t s = 0; s < scenes.size(); ++s) {
        std::cout << std::setw(std::max<size_t>(8, scenes[s].name.size() + 1));
        if (scores[c][s].present)
          std::cout << scores[c][s].error.psnr;
        else
          std::cout << "-";
      }
      std::cout << "\n";
    }
    std::cout << "\nmeans over scenes (tune / holdout / all); ms = device time per frame; low-A = share of squared "
                 "error on pixels with A < 0.5; p99 = 99th percentile per-pixel error, % of peak; flies = per mille of pixels over 4x\n"
                 "Cycles' local mean\n"
              << std::left << std::setw(labelWidth) << "config" << std::right << std::setw(9) << "ms" << std::setw(9)
              << "tune" << std::setw(9) << "holdout" << std::setw(9) << "all" << std::setw(9) << "low-A"
              << std::setw(9) << "p99" << std::setw(9) << "flies" << "\n";
    nlohmann::json json;
    std::vector<ssrcl::cli::BenchResult> points;
    for (size_t c = 0; c < configs.size(); ++c) {
      std::map<std::string, std::pair<double, int>> psnr;
      double ms = 0, low = 0, p99 = 0, flies = 0, rmseRel = 0;
      int n = 0;
      for (size_t s = 0; s < scenes.size(); ++s) {
        const Score& sc = scores[c][s];
        if (!sc.present) continue;
        for (const std::string& split : {scenes[s].split, std::string("all")}) {
          psnr[split].first += sc.error.psnr;
          psnr[split].second += 1;
        }
        ms += sc.ms, low += sc.error.lowConfidence, p99 += sc.error.p99, flies += sc.error.fireflies;
        rmseRel += std::pow(10.0, -sc.error.psnr / 20);
        ++n;
        json["scores"].push_back({{"config", configs[c].label},
                                  {"scene", scenes[s].name},
                                  {"split", scenes[s].split},
                                  {"ms", sc.ms},
                                  {"psnr_db", sc.error.psnr},
                                  {"rmse", sc.error.rmse},
                                  {"bias", sc.error.bias},
                                  {"low_confidence_share", sc.error.lowConfidence},
                                  {"p99_relative", sc.error.p99},
                                  {"firefly_share", sc.error.fireflies},
                                  {"answered_share", answeredShare[s]},
                                  {"answered_psnr_db", sc.answered.psnr},
                                  {"answered_p99_relative", sc.answered.p99},
                                  {"answered_fireflies", sc.answered.fireflies},
                                  {"answered_bias", sc.answered.bias},
                                  {"answered_noise_p99_relative", std::isnan(sc.noiseP99) ? nlohmann::json() : nlohmann::json(sc.noiseP99)}});
      }
      if (!n) continue;
      auto mean = [&](const std::string& split) {
        auto it = psnr.find(split);
        std::ostringstream o;
        o << std::fixed << std::setprecision(2);
        if (it == psnr.end()) return std::string("-");
        o << it->second.first / it->second.second;
        return o.str();
      };
      std::cout << std::left << std::setw(labelWidth) << configs[c].label << std::right << std::setprecision(0)
                << std::setw(9) << ms / n << std::setw(9) << mean("tune") << std::setw(9) << mean("holdout")
                << std::setw(9) << mean("all") << std::setprecision(3) << std::setw(9) << low / n << std::setprecision(2)
                << std::setw(9) << 100 * p99 / n << std::setw(9) << 1000 * flies / n << "\n";
      if (!configs[c].eevee && configs[c].passDir.empty()) {
        ssrcl::cli::BenchResult point;
        point.input = "corpus mean (" + std::to_string(n) + " scenes)";
        point.config = configs[c].label;
        point.stages["total"].medianMs = ms / n;
        point.hasError = true;
        point.error.rmse = rmseRel / n;
        points.push_back(point);
      }
    }
    // Table 3: speckle where every pass answers.
    std::cout << "\nspeckle over the pixels every pass answers (A >= 0.5 in each): p99 % of peak / fireflies per "
                 "mille / mean signed error, % of peak"
              << (noise ? " / own noise p99 (two seeds), % of peak" : "") << "\n"
              << std::left << std::setw(labelWidth) << "answered" << std::right;
    const auto cellWidth = [&](size_t s) { return std::max<size_t>(noise ? 28 : 21, scenes[s].name.size() + 1); };
    for (size_t s = 0; s < scenes.size(); ++s)
      std::cout << std::setw(cellWidth(s)) << std::to_string(int(std::lround(100 * answeredShare[s]))) + " %";
    std::cout << "\n";
    for (size_t c = 0; c < configs.size(); ++c) {
      std::cout << std::left << std::setw(labelWidth) << configs[c].label << std::right;
      for (size_t s = 0; s < scenes.size(); ++s) {
        const Score& sc = scores[c][s];
        std::ostringstream cell;
        cell << std::fixed << std::setprecision(1);
        if (!sc.present) {
          cell << "-";
        } else {
          cell << 100 * sc.answered.p99 << " / " << 1000 * sc.answered.fireflies << " / " << std::showpos
               << std::setprecision(2) << 100 * sc.answered.bias / peak[s] << std::noshowpos << std::setprecision(1);
          if (!std::isnan(sc.noiseP99)) cell << " / " << 100 * sc.noiseP99;
        }
        std::cout << std::setw(cellWidth(s)) << cell.str();
      }
      std::cout << "\n";
    }
    if (!jsonPath.empty()) {
      std::ofstream(jsonPath) << json.dump(2) << "\n";
    }
    if (!plotPath.empty())
      ssrcl::cli::writeBenchSvg(plotPath, points, device.info().name, "RMSE / peak against Cycles, corpus mean (log)");
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_score_corpus: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
