#include "support/analytic_sequence.hpp"

#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>

#include "scenes/analytic_scene.hpp"
#include "ssrcl/io.hpp"
#include "support/exr_fixtures.hpp"

namespace ssrcl::test {
namespace {

// Channel `c` of an interleaved image, as one plane.
std::vector<float> plane(const Image& image, int c) {
  std::vector<float> values(std::size_t(image.width) * image.height);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = image.data[i * image.channels + c];
  return values;
}

}  // namespace

Scene sequenceScene(const AnalyticSequence& s) {
  Scene scene = makeScene(s.scene);
  if (s.roughness >= 0)
    for (Primitive& p : scene.primitives) p.material.roughness = s.roughness;
  return scene;
}

Camera sequenceCamera(const AnalyticSequence& s, int index) {
  ViewParams view = makeScene(s.scene).view;
  const glm::dmat4 orbit = glm::rotate(glm::dmat4(1.0), glm::radians(index * s.degreesPerFrame), glm::dvec3(0, 1, 0));
  const glm::dvec3 away = view.eye - view.target;
  view.eye = view.target + glm::dvec3(orbit * glm::dvec4(away + glm::normalize(away) * (index * s.dollyPerFrame), 0.0));
  if (s.fovYDegrees > 0) view.fovYDegrees = s.fovYDegrees;
  return makeCamera(view, s.width, s.height);
}

std::string writeAnalyticSequence(const AnalyticSequence& s) {
  const Scene scene = sequenceScene(s);
  std::filesystem::create_directories(s.directory);
  const std::string base = s.directory + "/" + s.prefix + ".";
  for (int i = 0; i < s.frameCount; ++i) {
    const Camera camera = sequenceCamera(s, i);
    const AnalyticGBuffer g = renderGBuffer(scene, camera);

    char number[16];
    std::snprintf(number, sizeof number, "%04d", s.firstFrame + i);
    writeExr(base + number + ".exr", s.width, s.height,
             {{"ViewLayer.Combined.R", plane(g.color, 0), Imf::HALF},
              {"ViewLayer.Combined.G", plane(g.color, 1), Imf::HALF},
              {"ViewLayer.Combined.B", plane(g.color, 2), Imf::HALF},
              {"ViewLayer.Depth.Z", plane(g.depth, 0), Imf::FLOAT},
              {"ViewLayer.Normal.X", plane(g.normal, 0), Imf::FLOAT},
              {"ViewLayer.Normal.Y", plane(g.normal, 1), Imf::FLOAT},
              {"ViewLayer.Normal.Z", plane(g.normal, 2), Imf::FLOAT},
              {"ViewLayer.roughness.X", plane(g.roughness, 0), Imf::HALF}});
    saveCameraJson(base + number + ".camera.json", camera);
  }
  return base + "####.exr";
}

}  // namespace ssrcl::test
