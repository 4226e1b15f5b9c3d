// Writes the fuzzers' seed corpus: tiny valid G-buffers in the layouts the loader accepts and
// camera sidecars of each projection kind. Usage: ssrcl_fuzz_corpus <fuzz/corpus directory>
#include <cmath>
#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <string>
#include <vector>

#include "ssrcl/io.hpp"
#include "support/exr_fixtures.hpp"

using namespace ssrcl::test;

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  const std::string dir = argv[1];
  const int w = 4, h = 3;
  const auto ch = [&](const std::string& name, float seed, Imf::PixelType type = Imf::FLOAT) {
    return ExrChannel{name, pattern(w, h, seed), type};
  };
  const std::vector<ExrChannel> blender = {ch("ViewLayer.Combined.R", 0, Imf::HALF),
                                           ch("ViewLayer.Combined.G", 1, Imf::HALF),
                                           ch("ViewLayer.Combined.B", 2, Imf::HALF),
                                           ch("ViewLayer.Depth.Z", 3),
                                           ch("ViewLayer.Normal.X", 4),
                                           ch("ViewLayer.Normal.Y", 5),
                                           ch("ViewLayer.Normal.Z", 6),
                                           ch("ViewLayer.roughness.X", 7)};
  const std::vector<ExrChannel> plain = {ch("R", 0),   ch("G", 1),   ch("B", 2),   ch("Z", 3),
                                         ch("N.X", 4), ch("N.Y", 5), ch("N.Z", 6), ch("roughness", 7, Imf::UINT)};
  ExrOptions o;
  writeExr(dir + "/gbuffer/blender-zip.exr", w, h, blender, o);
  o.compression = Imf::NO_COMPRESSION;
  writeExr(dir + "/gbuffer/plain-none.exr", w, h, plain, o);
  o.compression = Imf::RLE_COMPRESSION;
  o.originX = -2;
  o.originY = 5;
  writeExr(dir + "/gbuffer/plain-rle-window.exr", w, h, plain, o);
  o = ExrOptions{};
  o.compression = Imf::PIZ_COMPRESSION;
  o.tiled = true;
  o.tileSize = 2;
  writeExr(dir + "/gbuffer/blender-piz-tiled.exr", w, h, blender, o);
  o = ExrOptions{};
  o.compression = Imf::ZIPS_COMPRESSION;
  writeMultiPartExr(dir + "/gbuffer/blender-multipart.exr", w, h,
                    {{"ViewLayer.Combined", {ch("R", 0), ch("G", 1), ch("B", 2)}},
                     {"ViewLayer.Depth", {ch("Z", 3)}},
                     {"ViewLayer.Normal", {ch("X", 4), ch("Y", 5), ch("Z", 6)}},
                     {"ViewLayer.roughness", {ch("X", 7)}}},
                    o);

  ssrcl::Camera c;
  c.width = w;
  c.height = h;
  c.view = glm::lookAt(glm::dvec3(1, 2, 3), glm::dvec3(0.0), glm::dvec3(0, 1, 0));
  c.nearPlane = 0.1;
  c.farPlane = 100.0;
  c.projection = glm::perspective(0.8, double(w) / h, c.nearPlane, c.farPlane);
  ssrcl::saveCameraJson(dir + "/camera/perspective.json", c);
  c.projection = glm::ortho(-2.0, 2.0, -1.5, 1.5, c.nearPlane, c.farPlane);
  ssrcl::saveCameraJson(dir + "/camera/orthographic.json", c);
  c.projection = glm::infinitePerspective(0.8, double(w) / h, c.nearPlane);
  c.farPlane = INFINITY;
  ssrcl::saveCameraJson(dir + "/camera/infinite.json", c);
  c.projection[2][2] = 0.0;  // reversed Z, [0, 1], infinite far: row 3 = (0, 0, 0, near)
  c.projection[3][2] = c.nearPlane;
  ssrcl::saveCameraJson(dir + "/camera/reversed-infinite.json", c);
  // Without near/far: derived from the projection.
  writeBytes(dir + "/camera/derived-planes.json",
             R"({"view": [[1,0,0,0],[0,1,0,0],[0,0,1,-5],[0,0,0,1]],
  "projection": [[1.2,0,0.1,0],[0,1.6,0,0],[0,0,-1.002,-0.2002],[0,0,-1,0]], "width": 4, "height": 3})");
  return 0;
}
