#pragma once
#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::cli {

// One frame to benchmark: a G-buffer and its camera.
struct BenchInput {
  std::string name;
  GBuffer gbuffer;
  Camera camera;
};

// A G-buffer EXR read as `ssrcl trace` reads it with the Blender preset (loadFrame: its
// <stem>.camera.json sidecar or header camera, the input check, the conventions).
BenchInput loadBenchFile(const std::string& exr);
// Where the bundled samples are (a directory holding mirror/ and glossy/): `sampleDir` when given
// (--sample-dir), else share/ssrcl/samples installed beside the executable's bin/, else the copy
// the build puts beside the executable. No source path is compiled in.
std::string findSampleDir(const std::string& sampleDir);
// A bundled sample: "mirror" or "glossy" (<sample dir>/<name>/<name>.exr with its camera sidecar).
BenchInput loadBundledSample(const std::string& name, const std::string& sampleDir);
// A generated analytic scene at a resolution; roughness >= 0 makes every surface that rough.
BenchInput generateScene(const std::string& scene, int width, int height, float roughness);

// "1920x1080" -> {1920, 1080}; throws Error(InvalidArgument) naming `option`.
std::pair<int, int> parseSize(const std::string& text, const std::string& option);

// The frames a benchmark runs on (`ssrcl bench`, bench/ssrcl_roofline): files, bundled samples, a
// generated scene at sizes; none given: both samples.
struct BenchInputOptions {
  std::vector<std::string> files, samples, sizes{"1920x1080"};
  std::string scene, sampleDir;
  float sceneRoughness = 0.3f;
};
// inputs, --sample, --sample-dir, --scene, --size, --scene-roughness
void addBenchInputOptions(CLI::App& cmd, BenchInputOptions& o);
std::vector<BenchInput> loadBenchInputs(const BenchInputOptions& o);

}  // namespace ssrcl::cli
