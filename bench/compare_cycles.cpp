// Error of each quality setting against Cycles' path-traced glossy passes on a Blender sample:
//   ssrcl_compare_cycles <sample.exr> [camera.json] [specular]
// Cycles' Glossy Direct + Indirect on a floor of F0 = `specular` (1 for the glossy sample) is
//   specular * E(o, alpha) * (lobe-weighted mean incident radiance),
// E being single-scatter GGX's directional albedo, while our pass is that mean times the found
// fraction A. So each setting's rgb * E * specular is compared with Cycles on the floor pixels
// whose reflection the reference setting finds entirely on screen (A >= 0.98 there), where both
// estimate the same thing; fast settings that miss part of it are charged for it.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <iomanip>
#include <iostream>
#include <map>

#include "ssrcl/ssrcl.hpp"

namespace {

constexpr double kPi = 3.14159265358979323846;

double lambda(const glm::dvec3& w, double alpha) {
  const double tan2 = (w.x * w.x + w.y * w.y) / (w.z * w.z);
  return 0.5 * (std::sqrt(1.0 + alpha * alpha * tan2) - 1.0);
}

// E(o) = integral of D G2 / (4 o.z) over l = E over visible-normal samples of G2 / G1(o), taken on
// a 128 x 128 grid of stratum midpoints (deterministic, converged to ~1e-4 for these lobes).
double directionalAlbedo(double cosO, double alpha) {
  const glm::dvec3 o(std::sqrt(std::max(0.0, 1.0 - cosO * cosO)), 0.0, cosO);
  const glm::dvec3 vh = glm::normalize(glm::dvec3(alpha * o.x, alpha * o.y, o.z));
  const glm::dvec3 t1 = vh.x * vh.x + vh.y * vh.y > 0 ? glm::normalize(glm::dvec3(-vh.y, vh.x, 0)) : glm::dvec3(1, 0, 0);
  const glm::dvec3 t2 = glm::cross(vh, t1);
  const int n = 128;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double u1 = (i + 0.5) / n, u2 = (j + 0.5) / n;
      const double r = std::sqrt(u1), phi = 2 * kPi * u2;
      const double s = 0.5 * (1 + vh.z);
      double p1 = r * std::cos(phi), p2 = r * std::sin(phi);
      p2 = (1 - s) * std::sqrt(std::max(0.0, 1 - p1 * p1)) + s * p2;
      const glm::dvec3 nh = p1 * t1 + p2 * t2 + std::sqrt(std::max(0.0, 1 - p1 * p1 - p2 * p2)) * vh;
      const glm::dvec3 h = glm::normalize(glm::dvec3(alpha * nh.x, alpha * nh.y, std::max(0.0, nh.z)));
      const glm::dvec3 l = 2 * glm::dot(o, h) * h - o;
      if (l.z > 0) sum += (1 + lambda(o, alpha)) / (1 + lambda(o, alpha) + lambda(l, alpha));
    }
  return sum / (n * n);
}

struct Setting {
  std::string name;
  ssrcl::TraceSettings settings;
};

std::vector<Setting> settingsToCompare() {
  std::vector<Setting> list;
  auto medium = ssrcl::qualityPreset("medium");
  auto draft = medium;
  draft.samplesPerPixel = 1;
  draft.reuseRadius = 0;
  list.push_back({"1 ray, no reuse", draft});
  list.push_back({"medium", medium});
  auto denoised = medium;
  denoised.denoise = true;
  list.push_back({"medium + denoise", denoised});
  auto many = medium;
  many.samplesPerPixel = 32;
  list.push_back({"hiz 32 rays + reuse", many});
  auto reference = ssrcl::qualityPreset("reference");
  list.push_back({"reference (256)", reference});
  return list;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::cerr << "usage: ssrcl_compare_cycles <sample.exr> [camera.json] [specular]\n";
    return 2;
  }
  const std::string exr = argv[1];
  std::filesystem::path p(exr);
  const std::string cameraPath =
      argc > 2 && *argv[2] ? argv[2] : (p.parent_path() / (p.stem().string() + ".camera.json")).string();
  const double specular = argc > 3 ? std::atof(argv[3]) : 1.0;
  try {
    ssrcl::GBufferSource source;
    source.file = exr;
    ssrcl::GBuffer g = ssrcl::loadGBuffer(source);
    auto pass = [&](const std::string& name) {
      ssrcl::GBufferSource s = source;
      s.colorChannels = "ViewLayer." + name + ".R,ViewLayer." + name + ".G,ViewLayer." + name + ".B";
      s.constantRoughness = 0.0f;
      return ssrcl::loadGBuffer(s).color;
    };
    const ssrcl::Image glossDir = pass("GlossDir"), glossInd = pass("GlossInd");
    const ssrcl::Camera camera = ssrcl::loadCameraJson(cameraPath);
    const glm::dmat4 invViewProj = glm::inverse(camera.projection * camera.view);
    const glm::dvec3 eye = glm::dvec3(glm::inverse(camera.view)[3]);

    ssrcl::Device device(ssrcl::DeviceType::Default);
    ssrcl::Pipeline pipeline(device);
    pipeline.setImage("color", g.color);
    pipeline.setImage("depth", g.depth);
    pipeline.setImage("normal", g.normal);
    pipeline.setImage("roughness", g.roughness);
    pipeline.setCamera(camera);
    pipeline.commit();

    const int w = g.depth.width, h = g.depth.height;
    // The floor: upward world normal (Blender is Z-up), a surface, a glossy or mirror roughness.
    std::vector<int> floor;
    for (int i = 0; i < w * h; ++i)
      if (g.normal.data[3 * i + 2] > 0.999f && g.depth.data[i] < 1e9f && g.roughness.data[i] < 0.9f) floor.push_back(i);

    // E per floor pixel, cached on (roughness, n.o quantized to 1/512).
    std::map<std::pair<float, int>, double> albedoCache;
    std::vector<double> albedo(floor.size());
    for (size_t k = 0; k < floor.size(); ++k) {
      const int x = floor[k] % w, y = floor[k] / w;
      glm::dvec4 q = invViewProj * glm::dvec4(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h, 0.0, 1.0);
      const glm::dvec3 toEye = glm::normalize(eye - glm::dvec3(q) / q.w);
      const int bin = std::clamp(int(toEye.z * 512), 1, 512);  // n = +Z on the floor
      const float rough = g.roughness.data[floor[k]];
      auto key = std::make_pair(rough, bin);
      auto it = albedoCache.find(key);
      if (it == albedoCache.end())
        it = albedoCache.emplace(key, directionalAlbedo((bin - 0.5) / 512.0, double(rough) * rough)).first;
      albedo[k] = it->second;
    }

    std::vector<Setting> settings = settingsToCompare();
    std::vector<ssrcl::Image> outputs;
    std::vector<double> deviceMs, wallMs;
    for (const Setting& s : settings) {
      pipeline.settings() = s.settings;
      auto start = std::chrono::steady_clock::now();
      pipeline.execute();
      wallMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
      double ms = 0;
      for (const auto& [stage, t] : pipeline.stageTimes().ms) ms += t;
      deviceMs.push_back(ms);
      outputs.push_back(pipeline.output("reflection"));
    }
    const ssrcl::Image& reference = outputs.back();
    std::vector<size_t> mask;
    double peak = 0;
    for (size_t k = 0; k < floor.size(); ++k)
      if (reference.data[4 * floor[k] + 3] >= 0.98f) {
        mask.push_back(k);
        for (int c = 0; c < 3; ++c)
          peak = std::max(peak, double(glossDir.data[3 * floor[k] + c] + glossInd.data[3 * floor[k] + c]));
      }
    std::cout << "sample: " << exr << " (" << w << "x" << h << "), device: " << device.info().name << "\n"
              << "floor pixels: " << floor.size() << ", compared (reference finds >= 98% of the lobe): " << mask.size()
              << ", peak " << peak << "\n"
              << std::left << std::setw(22) << "setting" << std::right << std::setw(12) << "device ms" << std::setw(12)
              << "RMSE" << std::setw(12) << "PSNR dB" << std::setw(14) << "mean rel err" << "\n";
    for (size_t s = 0; s < settings.size(); ++s) {
      double se = 0, rel = 0;
      for (size_t k : mask) {
        const int i = floor[k];
        for (int c = 0; c < 3; ++c) {
          const double cycles = glossDir.data[3 * i + c] + glossInd.data[3 * i + c];
          const double ours = specular * albedo[k] * outputs[s].data[4 * i + c];
          se += (ours - cycles) * (ours - cycles);
          rel += std::abs(ours - cycles) / std::max(cycles, 0.02);
        }
      }
      const double n = 3.0 * std::max<size_t>(mask.size(), 1);
      const double rmse = std::sqrt(se / n);
      std::cout << std::left << std::setw(22) << settings[s].name << std::right << std::fixed << std::setprecision(1)
                << std::setw(12) << deviceMs[s] << std::setprecision(4) << std::setw(12) << rmse
                << std::setprecision(2) << std::setw(12) << 20 * std::log10(peak / rmse) << std::setprecision(4)
                << std::setw(14) << rel / n << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_compare_cycles: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
