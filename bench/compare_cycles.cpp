// Error of each quality setting against Cycles' path-traced glossy passes on a Blender sample:
//   ssrcl_compare_cycles <sample.exr> [camera.json] [specular]
// Cycles' Glossy Direct + Indirect on a floor of F0 = `specular` (1 for the glossy sample) is
//   specular * E(o, alpha) * (lobe-weighted mean incident radiance),
// E being GGX's directional albedo with the separable Smith term Cycles 3.4 uses, while our pass
// is that mean times the found fraction A with nothing for the rest. The glossy sample's sky is
// invisible to glossy rays, so the rest is black there too and every floor pixel is compared:
// what stays is SSR's own error (off-screen and hidden content, tracing, noise).
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

// E(o) = integral of D G1(o) G1(l) / (4 o.z) over l = E over visible-normal samples of G1(l),
// taken on a 128 x 128 grid of stratum midpoints (deterministic, converged to ~1e-4 here).
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
      if (l.z > 0) sum += 1 / (1 + lambda(l, alpha));
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
  auto prefiltered = medium;
  prefiltered.prefilter = true;
  list.push_back({"medium + prefilter", prefiltered});
  auto denoised = medium;
  denoised.denoise = true;
  list.push_back({"medium + denoise", denoised});
  auto many = medium;
  many.samplesPerPixel = 16;
  list.push_back({"16 rays", many});
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
    // The floor: upward world normal (Blender is Z-up), a surface, glossy or mirror roughness, and
    // Cycles' glossy colour 1 (0 or fractional on object edges and stripe boundaries).
    const ssrcl::Image glossCol = pass("GlossCol");
    std::vector<int> floor;
    for (int i = 0; i < w * h; ++i)
      if (g.normal.data[3 * i + 2] > 0.999f && g.depth.data[i] < 1e9f && g.roughness.data[i] < 0.9f &&
          glossCol.data[3 * i] > 0.999f)
        floor.push_back(i);

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
    std::map<float, std::vector<size_t>> byRoughness;
    double peak = 0;
    for (size_t k = 0; k < floor.size(); ++k) {
      byRoughness[g.roughness.data[floor[k]]].push_back(k);
      for (int c = 0; c < 3; ++c)
        peak = std::max(peak, double(glossDir.data[3 * floor[k] + c] + glossInd.data[3 * floor[k] + c]));
    }
    // Stripes only: pixels on a boundary between two roughnesses hold blends.
    std::vector<std::pair<std::string, std::vector<size_t>>> groups;
    std::vector<size_t> all;
    for (auto& [rough, ks] : byRoughness)
      if (ks.size() > 1000) {
        groups.push_back({"r=" + std::to_string(rough).substr(0, 6), ks});
        all.insert(all.end(), ks.begin(), ks.end());
      }
    groups.insert(groups.begin(), {"floor", all});
    std::cout << "sample: " << exr << " (" << w << "x" << h << "), device: " << device.info().name << "\n"
              << "floor pixels compared: " << all.size() << ", peak " << peak
              << "; RMSE per group, PSNR (dB, peak / RMSE) and mean |error| over all\n"
              << std::left << std::setw(22) << "setting" << std::right << std::setw(11) << "device ms";
    for (auto& grp : groups) std::cout << std::setw(11) << grp.first;
    std::cout << std::setw(9) << "PSNR" << std::setw(11) << "mean|err|" << "\n";
    for (size_t s = 0; s < settings.size(); ++s) {
      std::cout << std::left << std::setw(22) << settings[s].name << std::right << std::fixed << std::setprecision(1)
                << std::setw(11) << deviceMs[s];
      double rmseAll = 0, absAll = 0;
      for (auto& [name, ks] : groups) {
        double se = 0, abs = 0;
        for (size_t k : ks) {
          const int i = floor[k];
          for (int c = 0; c < 3; ++c) {
            const double cycles = glossDir.data[3 * i + c] + glossInd.data[3 * i + c];
            const double ours = specular * albedo[k] * outputs[s].data[4 * i + c];
            se += (ours - cycles) * (ours - cycles);
            abs += std::abs(ours - cycles);
          }
        }
        const double n = 3.0 * std::max<size_t>(ks.size(), 1);
        const double rmse = std::sqrt(se / n);
        if (name == "floor") {
          rmseAll = rmse;
          absAll = abs / n;
        }
        std::cout << std::setprecision(4) << std::setw(11) << rmse;
      }
      std::cout << std::setprecision(2) << std::setw(9) << 20 * std::log10(peak / rmseAll) << std::setprecision(4)
                << std::setw(11) << absAll << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "ssrcl_compare_cycles: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
