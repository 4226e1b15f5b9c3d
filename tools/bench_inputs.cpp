#include "bench_inputs.hpp"

#include <filesystem>
#include <stdexcept>

#include "scenes/analytic_scene.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/frame.hpp"

namespace ssrcl::cli {

BenchInput loadBenchFile(const std::string& exr) {
  FrameSource source;
  source.file = exr;
  Frame frame = loadFrame(source);
  BenchInput in;
  in.name = std::filesystem::path(exr).stem().string();
  in.gbuffer = std::move(frame.gbuffer);
  in.camera = frame.camera;
  return in;
}

std::string findSampleDir(const std::string& sampleDir) {
  if (!sampleDir.empty()) return sampleDir;
  std::error_code ec;
  const std::filesystem::path exeDir = std::filesystem::read_symlink("/proc/self/exe", ec).parent_path();
  const std::filesystem::path installed = exeDir.parent_path() / "share" / "ssrcl" / "samples",
                              built = exeDir / "share" / "ssrcl" / "samples";
  for (const std::filesystem::path& dir : {installed, built})
    if (std::filesystem::is_directory(dir, ec)) return dir.string();
  throw Error(ErrorCode::IoError, "--sample: no bundled samples in " + installed.string() + " nor " + built.string() +
                                      "; give --sample-dir (a directory holding mirror/ and glossy/, e.g. the "
                                      "source tree's samples/blender)");
}

BenchInput loadBundledSample(const std::string& name, const std::string& sampleDir) {
  if (name != "mirror" && name != "glossy")
    throw Error(ErrorCode::InvalidArgument, "--sample: expected mirror or glossy, got '" + name + "'");
  BenchInput in = loadBenchFile(findSampleDir(sampleDir) + "/" + name + "/" + name + ".exr");
  in.name = "sample " + name;
  return in;
}

BenchInput generateScene(const std::string& scene, int width, int height, float roughness) {
  scenes::Scene s;
  try {
    s = scenes::makeScene(scene);
  } catch (const std::invalid_argument&) {
    std::string names;
    for (const auto& n : scenes::sceneNames()) names += (names.empty() ? "" : ", ") + n;
    throw Error(ErrorCode::InvalidArgument, "--scene: unknown scene '" + scene + "' (known: " + names + ")");
  }
  BenchInput in;
  in.camera = scenes::makeCamera(s.view, width, height);
  scenes::AnalyticGBuffer g = scenes::renderGBuffer(s, in.camera);
  in.gbuffer = static_cast<GBuffer&>(g);
  if (roughness >= 0.0f)
    for (float& r : in.gbuffer.roughness.data) r = roughness;
  in.name = scene + " " + std::to_string(width) + "x" + std::to_string(height) +
            (roughness >= 0.0f ? " r" + std::to_string(roughness).substr(0, 4) : "");
  return in;
}

std::pair<int, int> parseSize(const std::string& text, const std::string& option) {
  const auto x = text.find('x');
  try {
    if (x != std::string::npos) {
      size_t a = 0, b = 0;
      const int w = std::stoi(text.substr(0, x), &a), h = std::stoi(text.substr(x + 1), &b);
      if (a == x && b == text.size() - x - 1 && w > 0 && h > 0 && w <= 16384 && h <= 16384) return {w, h};
    }
  } catch (const std::exception&) {
  }
  throw Error(ErrorCode::InvalidArgument, option + ": expected WIDTHxHEIGHT (up to 16384x16384), got '" + text + "'");
}

void addBenchInputOptions(CLI::App& cmd, BenchInputOptions& o) {
  cmd.add_option("inputs", o.files, "G-buffer EXRs, read as `ssrcl trace` reads them (Blender preset: <stem>.camera.json beside each, else "
                 "the header camera)");
  cmd.add_option("--sample", o.samples, "Bundled sample: mirror, glossy (default: both, when no input is given)")
      ->check(CLI::IsMember({"mirror", "glossy"}));
  cmd.add_option("--sample-dir", o.sampleDir,
                 "Directory holding the bundled samples (mirror/, glossy/); default: share/ssrcl/samples of the "
                 "installation")
      ->check(CLI::ExistingDirectory);
  cmd.add_option("--scene", o.scene, "Generated analytic scene: spheres_on_mirror, mirror_wall, half_sky");
  cmd.add_option("--size", o.sizes, "Resolution(s) of the generated scene, e.g. 480x270 1920x1080")
      ->capture_default_str();
  cmd.add_option("--scene-roughness", o.sceneRoughness, "Roughness of every surface of the generated scene")
      ->capture_default_str()
      ->check(CLI::Range(0.0f, 1.0f));
}

std::vector<BenchInput> loadBenchInputs(const BenchInputOptions& o) {
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
  return inputs;
}

}  // namespace ssrcl::cli
