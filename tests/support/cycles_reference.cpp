#include "support/cycles_reference.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/glm.hpp>
#include <map>
#include <stdexcept>

#include "ssrcl/pipeline.hpp"
#include "ssrcl/specular_albedo.hpp"
#include "support/exr_fixtures.hpp"
#include "support/test_device.hpp"

namespace ssrcl::test {
CyclesReference loadCyclesReference(const std::string& exr, const std::string& cameraJson, double specular) {
  CyclesReference ref;
  GBufferSource source;
  source.file = exr;
  ref.gbuffer = loadGBuffer(source);
  const ExrContents passes = readExr(exr);
  auto channel = [&](const std::string& name) -> const std::vector<float>& {
    auto it = passes.channels.find("ViewLayer." + name);
    if (it == passes.channels.end()) throw std::runtime_error(exr + ": no channel ViewLayer." + name);
    return it->second.values;
  };
  std::filesystem::path p(exr);
  ref.camera = loadCameraJson(cameraJson.empty() ? (p.parent_path() / (p.stem().string() + ".camera.json")).string()
                                                 : cameraJson);
  const GBuffer& g = ref.gbuffer;
  const int w = g.depth.width, h = g.depth.height;
  const glm::dmat4 invViewProj = glm::inverse(ref.camera.projection * ref.camera.view);
  const glm::dvec3 eye = glm::dvec3(glm::inverse(ref.camera.view)[3]);
  const bool indexed = passes.channels.count("ViewLayer.IndexOB.X") > 0;
  const std::vector<float>& glossCol = channel("GlossCol.R");
  const std::vector<float>* index = indexed ? &channel("IndexOB.X") : nullptr;
  std::vector<const std::vector<float>*> gloss;
  for (const char* pass : {"GlossDir.", "GlossInd."})
    for (const char* c : {"R", "G", "B"}) gloss.push_back(&channel(std::string(pass) + c));

  std::map<float, std::vector<size_t>> byRoughness;
  std::vector<double> values;
  for (int i = 0; i < w * h; ++i) {
    const glm::dvec3 n(g.normal.data[3 * i], g.normal.data[3 * i + 1], g.normal.data[3 * i + 2]);
    const bool surface = g.depth.data[i] < 1e9f && glm::length(n) > 0.5;
    const bool reflector = indexed ? (*index)[i] == 1.0f
                                   : n.z > 0.999 && g.roughness.data[i] < 0.9f && glossCol[i] > 0.999f;
    if (!surface || !reflector) continue;
    const int x = i % w, y = i / w;
    const glm::dvec4 q = invViewProj * glm::dvec4(2.0 * (x + 0.5) / w - 1.0, 1.0 - 2.0 * (y + 0.5) / h, 0.0, 1.0);
    const glm::dvec3 toEye = glm::normalize(eye - glm::dvec3(q) / q.w);
    const float rough = std::clamp(g.roughness.data[i], 0.0f, 1.0f);
    if (!indexed) byRoughness[rough].push_back(ref.pixels.size());
    ref.pixels.push_back(i);
    ref.scale.push_back(specularAlbedo(rough, glm::dot(glm::normalize(n), toEye))(specular));
    for (int c = 0; c < 3; ++c) {
      ref.cycles.push_back((*gloss[c])[i] + (*gloss[3 + c])[i]);
      values.push_back(ref.cycles.back());
    }
  }
  if (values.empty()) throw std::runtime_error(exr + ": no reflector pixels");
  std::sort(values.begin(), values.end());
  ref.peak = values[std::min(values.size() - 1, size_t(0.999 * values.size()))];

  std::vector<size_t> all;
  for (size_t k = 0; k < ref.pixels.size(); ++k) all.push_back(k);
  if (!indexed) {
    // Stripes only: pixels on a boundary between two roughnesses hold blends.
    all.clear();
    for (auto& [rough, ks] : byRoughness)
      if (ks.size() > 1000) {
        ref.groups.push_back({"r=" + std::to_string(rough).substr(0, 6), ks});
        all.insert(all.end(), ks.begin(), ks.end());
      }
    std::sort(all.begin(), all.end());
  }
  ref.groups.insert(ref.groups.begin(), {"all", all});
  return ref;
}

Image traceRender(const GBuffer& g, const Camera& camera, const std::string& preset) {
  Device device = testDevice();
  Pipeline pipeline(device);
  pipeline.setGBuffer(g);
  pipeline.setCamera(camera);
  pipeline.settings() = qualityPreset(preset);
  pipeline.commit();
  pipeline.execute();
  return pipeline.output("reflection");
}

GBuffer withMaterialAovs(GBuffer gbuffer, const std::string& exr) {
  GBufferSource material;
  material.file = exr;
  material.baseColorChannels = "ViewLayer.base_color.R,ViewLayer.base_color.G,ViewLayer.base_color.B";
  material.metallicChannel = "ViewLayer.metallic.X";
  GBuffer m = loadGBuffer(material);
  gbuffer.baseColor = std::move(m.baseColor);
  gbuffer.metallic = std::move(m.metallic);
  return gbuffer;
}

ReferenceError referenceError(const CyclesReference& ref, const Image& reflection, const std::vector<size_t>& group) {
  double se = 0, seLow = 0, abs = 0, signedSum = 0;
  std::vector<double> perPixel;
  perPixel.reserve(group.size());
  // Cycles' per-pixel channel mean over the reflector (NaN elsewhere), for the local means.
  const int w = ref.gbuffer.depth.width, h = ref.gbuffer.depth.height;
  std::vector<double> cyclesMean(size_t(w) * h, NAN);
  for (size_t k = 0; k < ref.pixels.size(); ++k)
    cyclesMean[size_t(ref.pixels[k])] = (ref.cycles[3 * k] + ref.cycles[3 * k + 1] + ref.cycles[3 * k + 2]) / 3;
  auto localMean = [&](int i) {
    double sum = 0;
    int n = 0;
    for (int y = std::max(0, i / w - 3); y <= std::min(h - 1, i / w + 3); ++y)
      for (int x = std::max(0, i % w - 3); x <= std::min(w - 1, i % w + 3); ++x)
        if (const double v = cyclesMean[size_t(y) * w + x]; !std::isnan(v)) sum += v, ++n;
    return sum / n;  // n >= 1: the pixel itself is on the reflector
  };
  size_t fireflies = 0;
  for (size_t k : group) {
    const size_t i = size_t(ref.pixels[k]);
    double pixelSe = 0, pixelAbs = 0;
    for (int c = 0; c < 3; ++c) {
      const double ours = ref.scale[k] * reflection.data[reflection.channels * i + c];
      const double diff = ours - ref.cycles[3 * k + c];
      pixelSe += diff * diff;
      pixelAbs += std::abs(diff);
      signedSum += diff;
    }
    se += pixelSe;
    abs += pixelAbs;
    if (reflection.channels == 4 && reflection.data[4 * i + 3] < 0.5f) seLow += pixelSe;
    perPixel.push_back(pixelAbs / 3);
    if (pixelAbs / 3 > std::max(4 * localMean(ref.pixels[k]), 0.01 * ref.peak)) ++fireflies;
  }
  const double n = 3.0 * std::max<size_t>(group.size(), 1);
  ReferenceError e;
  e.rmse = std::sqrt(se / n);
  e.meanAbs = abs / n;
  e.bias = signedSum / n;
  e.psnr = 20 * std::log10(ref.peak / std::max(e.rmse, 1e-30));
  e.lowConfidence = se > 0 ? seLow / se : 0;
  e.fireflies = double(fireflies) / std::max<size_t>(group.size(), 1);
  if (!perPixel.empty()) {
    std::nth_element(perPixel.begin(), perPixel.begin() + perPixel.size() * 99 / 100, perPixel.end());
    e.p99 = perPixel[perPixel.size() * 99 / 100] / ref.peak;
  }
  return e;
}

Image eeveeSpecular(const std::string& path, bool withColor) {
  const ExrContents exr = readExr(path);
  Image img(exr.width, exr.height, 3);
  const auto channel = [&](const std::string& name) -> const std::vector<float>& {
    auto it = exr.channels.find(name);
    if (it == exr.channels.end()) throw std::runtime_error(path + ": no channel " + name);
    return it->second.values;
  };
  for (int c = 0; c < 3; ++c) {
    const std::string rgb(1, "RGB"[c]);
    const std::vector<float>& light = channel("ViewLayer.GlossDir." + rgb);
    const std::vector<float>* color = withColor ? &channel("ViewLayer.GlossCol." + rgb) : nullptr;
    for (size_t i = 0; i < light.size(); ++i) img.data[3 * i + c] = light[i] * (color ? (*color)[i] : 1.0f);
  }
  return img;
}

}  // namespace ssrcl::test
