// The pass as a compositor reads it: named layer, half channels, compression, the input's windows
// and header attributes, the camera as OpenEXR's standard attributes, ssrcl's record, --append;
// and the checks around writing: batch resumes refuse outputs made otherwise, an unwritable
// location fails before any trace.
#include <OpenEXR/ImfChromaticitiesAttribute.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "io/exr_header_camera.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/simple_camera.hpp"
#include "support/temp_dir.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using ssrcl::test::ExrChannel;
using ssrcl::test::runCommand;
using ssrcl::test::shellQuote;

// A crop: the 40x30 data window sits inside a 48x36 display window, which the camera describes.
constexpr int kW = 40, kH = 30, kDisplayW = 48, kDisplayH = 36, kX0 = 4, kY0 = 3;
const ssrcl::PixelBox kDisplay{0, 0, kDisplayW - 1, kDisplayH - 1};
const ssrcl::PixelBox kData{kX0, kY0, kX0 + kW - 1, kY0 + kH - 1};

std::string testDevice() {
  const char* device = std::getenv("SSRCL_TEST_DEVICE");  // as testDevice() picks it
  return device ? device : "cpu";
}

std::string cli(const std::string& args, const std::string& device = testDevice()) {
  return shellQuote(SSRCL_CLI) + " " + args + " --device " + shellQuote(device);
}

ssrcl::Camera displayCamera() { return ssrcl::test::perspectiveCamera(kDisplayW, kDisplayH); }

// A mirror floor (y = 0) before a coloured wall (z = -2), ray cast through the crop's pixels, with
// channels of every type that --append must copy as they are.
void writeShot(const std::string& exr, Imf::Compression compression = Imf::ZIP_COMPRESSION) {
  const ssrcl::Camera cam = ssrcl::reframeCamera(displayCamera(), kDisplay, kData);
  const int n = kW * kH;
  std::vector<float> r(n), g(n), b(n), z(n), nx(n), ny(n), nz(n), rough(n, 0.0f), id(n), extra(n);
  const glm::dmat4 inv = glm::inverse(cam.projection * cam.view);
  const glm::dvec3 eye = glm::dvec3(glm::inverse(cam.view)[3]);
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x) {
      const int i = y * kW + x;
      const glm::dvec4 p = inv * glm::dvec4(2.0 * (x + 0.5) / kW - 1.0, 1.0 - 2.0 * (y + 0.5) / kH, 1.0, 1.0);
      const glm::dvec3 dir = glm::normalize(glm::dvec3(p) / p.w - eye);
      const double floor = dir.y < 0 ? -eye.y / dir.y : INFINITY, wall = dir.z < 0 ? (-2.0 - eye.z) / dir.z : INFINITY;
      const double t = std::min(floor, wall);
      const glm::dvec3 hit = eye + t * dir;
      z[i] = std::isfinite(t) ? float(-(cam.view * glm::dvec4(hit, 1.0)).z) : 1e10f;
      const bool onWall = wall < floor;
      nx[i] = 0.0f, ny[i] = onWall ? 0.0f : 1.0f, nz[i] = onWall ? 1.0f : 0.0f;
      r[i] = onWall ? 0.5f + 0.5f * float(std::sin(hit.x * 3.0)) : 0.1f;
      g[i] = onWall ? float(hit.y) * 0.3f : 0.1f;
      b[i] = 0.25f;
      id[i] = float(i * 7919 % 65536);  // integers, exact as floats
      extra[i] = 0.001f * float(i) - 0.3f;
    }
  ssrcl::test::ExrOptions options;
  options.compression = compression;
  options.originX = kX0, options.originY = kY0;
  options.displayWindow = Imath::Box2i({0, 0}, {kDisplayW - 1, kDisplayH - 1});
  options.editHeader = [](Imf::Header& h) {
    h.pixelAspectRatio() = 1.25f;
    h.screenWindowCenter() = Imath::V2f(0.1f, -0.2f);
    h.screenWindowWidth() = 1.5f;
    Imf::addChromaticities(h, Imf::Chromaticities({0.7f, 0.3f}, {0.2f, 0.7f}, {0.15f, 0.05f}, {0.31f, 0.33f}));
    h.insert("renderer/scene", Imf::StringAttribute("floor and wall"));
  };
  ssrcl::test::writeExr(exr, kW, kH,
                        {{"ViewLayer.Combined.R", r, Imf::HALF},
                         {"ViewLayer.Combined.G", g, Imf::HALF},
                         {"ViewLayer.Combined.B", b, Imf::HALF},
                         {"ViewLayer.Depth.Z", z, Imf::FLOAT},
                         {"ViewLayer.Normal.X", nx, Imf::FLOAT},
                         {"ViewLayer.Normal.Y", ny, Imf::FLOAT},
                         {"ViewLayer.Normal.Z", nz, Imf::FLOAT},
                         {"ViewLayer.roughness.X", rough, Imf::FLOAT},
                         {"ViewLayer.IndexOB.X", id, Imf::UINT},
                         {"ViewLayer.Extra.X", extra, Imf::HALF}},
                        options);
}

Imf::Header readHeader(const std::string& path) { return Imf::InputFile(path.c_str()).header(); }

std::string stringAttribute(const Imf::Header& h, const char* name) {
  const auto* a = h.findTypedAttribute<Imf::StringAttribute>(name);
  return a ? a->value() : "<missing " + std::string(name) + ">";
}

// Same map, up to float storage: view, and the projection's x, y and w rows (the standard
// attributes carry no clip planes: z is discarded).
void expectSameCamera(const ssrcl::Camera& got, const ssrcl::Camera& want) {
  EXPECT_EQ(got.width, want.width);
  EXPECT_EQ(got.height, want.height);
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {
      EXPECT_NEAR(got.view[c][r], want.view[c][r], 1e-5) << "view[" << c << "][" << r << "]";
      if (r != 2) EXPECT_NEAR(got.projection[c][r], want.projection[c][r], 1e-5) << "projection[" << c << "][" << r << "]";
    }
}

class OutputConventions : public ::testing::Test {
 protected:
  ssrcl::test::TempDir dir{"ssrcl-output"};
  std::string shot = dir.file("shot.exr");
  std::string out = dir.file("shot.refl.exr");
  void SetUp() override {
    writeShot(shot);
    ssrcl::saveCameraJson(dir.file("shot.camera.json"), displayCamera());
  }
  void trace(const std::string& args, const std::string& output) {
    auto r = runCommand(cli("trace " + shellQuote(shot) + " -o " + shellQuote(output) + " " + args));
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
};

TEST(HeaderCamera, WrittenAsStandardAttributesReadsBackTheSameCamera) {
  ssrcl::Camera shifted = displayCamera();
  shifted.projection[2][0] = 0.2, shifted.projection[2][1] = -0.1;  // off-centre (lens shift)
  ssrcl::Camera ortho = ssrcl::test::perspectiveCamera(kDisplayW, kDisplayH, {3, 4, -6}, {0.5, 0, 0});
  ortho.projection = glm::ortho(-4.0, 4.0, -3.0, 3.0, 0.5, 50.0);
  for (const ssrcl::Camera& camera : {ssrcl::test::perspectiveCamera(kDisplayW, kDisplayH, {1, 2, 7}, {0, 1, -1}), shifted, ortho}) {
    Imf::Header header(kDisplayW, kDisplayH);
    ssrcl::detail::cameraToHeader(camera, header);
    const std::optional<ssrcl::HeaderCamera> back = ssrcl::detail::cameraFromHeader(header, "header");
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(back->problem, "");
    EXPECT_EQ(back->attributes, "worldToCamera + worldToNDC");
    expectSameCamera(back->camera, camera);
  }
}

TEST_F(OutputConventions, DefaultsKeepPlainFloatRleChannelsAndCarryTheInputHeader) {
  trace("", out);
  const ssrcl::test::ExrContents exr = ssrcl::test::readExr(out);
  std::set<std::string> names;
  for (const auto& [name, channel] : exr.channels) {
    names.insert(name);
    EXPECT_EQ(channel.type, Imf::FLOAT) << name;
  }
  EXPECT_EQ(names, (std::set<std::string>{"R", "G", "B", "A", "distance"}));
  EXPECT_EQ(exr.compression, Imf::RLE_COMPRESSION);

  const Imf::Header h = readHeader(out);
  EXPECT_EQ(h.dataWindow(), Imath::Box2i({kData.minX, kData.minY}, {kData.maxX, kData.maxY}));
  EXPECT_EQ(h.displayWindow(), Imath::Box2i({0, 0}, {kDisplayW - 1, kDisplayH - 1}));
  EXPECT_EQ(h.pixelAspectRatio(), 1.25f);
  EXPECT_EQ(h.screenWindowCenter(), Imath::V2f(0.1f, -0.2f));
  EXPECT_EQ(h.screenWindowWidth(), 1.5f);
  ASSERT_TRUE(Imf::hasChromaticities(h));
  EXPECT_EQ(Imf::chromaticities(h).red, Imath::V2f(0.7f, 0.3f));
  EXPECT_EQ(Imf::chromaticities(h).white, Imath::V2f(0.31f, 0.33f));
  const std::optional<ssrcl::HeaderCamera> camera = ssrcl::detail::cameraFromHeader(h, out);
  ASSERT_TRUE(camera.has_value());
  expectSameCamera(camera->camera, displayCamera());
}

TEST_F(OutputConventions, LayerHalfCompressionAndTheRecord) {
  const std::string floatOut = dir.file("float.exr");
  trace("--output-layer refl --quality high --spp 3 --seed 7", floatOut);
  trace("--output-layer refl --quality high --spp 3 --seed 7 --half --compression piz", out);

  const ssrcl::test::ExrContents full = ssrcl::test::readExr(floatOut), half = ssrcl::test::readExr(out);
  EXPECT_EQ(half.compression, Imf::PIZ_COMPRESSION);
  ASSERT_EQ(half.channels.size(), 5u);
  int found = 0;
  for (const char* c : {"refl.R", "refl.G", "refl.B", "refl.A", "refl.distance"}) {
    ASSERT_TRUE(half.channels.count(c)) << c;
    EXPECT_EQ(half.channels.at(c).type, Imf::HALF) << c;
    EXPECT_EQ(full.channels.at(c).type, Imf::FLOAT) << c;
    const std::vector<float>& h = half.channels.at(c).values;
    const std::vector<float>& f = full.channels.at(c).values;
    ASSERT_EQ(h.size(), f.size());
    for (size_t i = 0; i < h.size(); ++i) ASSERT_EQ(h[i], float(::half(f[i]))) << c << " pixel " << i;
  }
  for (float a : full.channels.at("refl.A").values) found += a > 0.0f;
  EXPECT_GT(found, 50);  // the floor reflects the wall: the values compared are not all zero

  const Imf::Header h = readHeader(out);
  EXPECT_EQ(stringAttribute(h, "ssrcl/version"), SSRCL_VERSION);
  EXPECT_EQ(stringAttribute(h, "ssrcl/preset"), "high");
  EXPECT_EQ(stringAttribute(h, "ssrcl/seed"), "7");
  EXPECT_FALSE(stringAttribute(h, "ssrcl/device").empty());
  const json settings = json::parse(stringAttribute(h, "ssrcl/settings"));
  EXPECT_EQ(settings["samplesPerPixel"], 3);
  EXPECT_EQ(settings["seed"], 7);
  EXPECT_EQ(settings["denoise"], ssrcl::qualityPreset("high").denoise);
  EXPECT_EQ(settings["tracer"], "hiz");
  for (const char* field : {"thicknessModel", "thicknessScale", "thicknessMinRelative", "thicknessMaxRelative",
                            "glossyHitRoughness", "maxIterations", "reuseRadius", "prefilter", "traceStride"})
    EXPECT_TRUE(settings.contains(field)) << field;
  const json inputs = json::parse(stringAttribute(h, "ssrcl/inputs"));
  EXPECT_EQ(inputs["gbuffer"], shot);
  EXPECT_EQ(inputs["camera"], dir.file("shot.camera.json"));
}

TEST_F(OutputConventions, AppendKeepsEveryInputChannelBitExact) {
  writeShot(shot, Imf::PIZ_COMPRESSION);
  trace("--append", out);
  const ssrcl::test::ExrContents input = ssrcl::test::readExr(shot), output = ssrcl::test::readExr(out);
  EXPECT_EQ(output.compression, Imf::PIZ_COMPRESSION);  // the input's
  EXPECT_EQ(output.dataWindow, input.dataWindow);
  ASSERT_EQ(output.channels.size(), input.channels.size() + 5);
  for (const auto& [name, channel] : input.channels) {
    ASSERT_TRUE(output.channels.count(name)) << name;
    EXPECT_EQ(output.channels.at(name).type, channel.type) << name;
    const std::vector<float>& a = channel.values;
    const std::vector<float>& b = output.channels.at(name).values;
    ASSERT_EQ(a.size(), b.size()) << name;
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << name;
  }
  for (const char* c : {"reflection.R", "reflection.G", "reflection.B", "reflection.A", "reflection.distance"})
    EXPECT_TRUE(output.channels.count(c)) << c;
  const Imf::Header h = readHeader(out);
  EXPECT_EQ(stringAttribute(h, "renderer/scene"), "floor and wall");  // input attributes kept
  EXPECT_EQ(stringAttribute(h, "ssrcl/preset"), "medium");

  // A layer whose names the input already has is refused, naming the channel, before anything is written.
  const std::string clash = dir.file("clash.exr");
  auto r = runCommand(cli("trace " + shellQuote(shot) + " -o " + shellQuote(clash) +
                          " --append --output-layer ViewLayer.Combined --half --compression dwaa"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("ViewLayer.Combined.R"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(clash));
}

class BatchResume : public OutputConventions {
 protected:
  std::string outDir = dir.file("refl");
  void SetUp() override {
    for (const char* frame : {"shot.0001", "shot.0002"}) {
      writeShot(dir.file(std::string(frame) + ".exr"));
      ssrcl::saveCameraJson(dir.file(std::string(frame) + ".camera.json"), displayCamera());
    }
  }
  ssrcl::test::CommandResult batch(const std::string& args) {
    return runCommand(cli("batch " + shellQuote(dir.file("shot.####.exr")) + " --frames 1-2 -q -o " +
                          shellQuote(outDir + "/") + " " + args));
  }
  std::string output(int frame) { return outDir + "/shot.000" + std::to_string(frame) + ".refl.exr"; }
  void expectRefused(const std::string& args, const std::string& needle) {
    const std::string before = ssrcl::test::readBytes(output(1));
    auto r = batch(args);
    EXPECT_EQ(r.exitCode, 2) << args << ": " << r.output;
    EXPECT_NE(r.output.find(output(1)), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.output;
    EXPECT_EQ(ssrcl::test::readBytes(output(1)), before);
  }
};

TEST_F(BatchResume, RefusesOutputsMadeOtherwiseUnlessOverwrite) {
  ASSERT_EQ(batch("--quality draft --output-layer refl").exitCode, 0);
  EXPECT_EQ(batch("--quality draft --output-layer refl").exitCode, 0);  // same request: resumes
  expectRefused("--quality medium --output-layer refl", "preset draft");
  expectRefused("--quality draft --output-layer refl --spp 3", "samplesPerPixel");
  expectRefused("--quality draft --output-layer refl --half", "channel type float");
  expectRefused("--quality draft --output-layer refl --compression piz", "compression rle");
  expectRefused("--quality draft", "output layer");

  const std::string sky = std::string(SSRCL_SOURCE_DIR) + "/samples/corpus/environment/sky.exr";
  const std::string otherSky = dir.file("other_sky.exr");
  fs::copy_file(sky, otherSky);
  expectRefused("--quality draft --output-layer refl --environment " + shellQuote(sky), "environment none");
  ASSERT_EQ(batch("--quality draft --output-layer refl --overwrite --environment " + shellQuote(sky)).exitCode, 0);
  EXPECT_EQ(batch("--quality draft --output-layer refl --environment " + shellQuote(sky)).exitCode, 0);
  expectRefused("--quality draft --output-layer refl --environment " + shellQuote(otherSky), "'" + otherSky + "'");
  expectRefused("--quality draft --output-layer refl", "but none");

  auto r = batch("--quality draft --output-layer refl --spp 3 --overwrite");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(json::parse(stringAttribute(readHeader(output(1)), "ssrcl/settings"))["samplesPerPixel"], 3);

  // An output without ssrcl's record (an older version's) is reported as such.
  std::vector<float> zero(kW * kH, 0.0f);
  ssrcl::test::writeExr(output(1), kW, kH,
                        {{"refl.R", zero}, {"refl.G", zero}, {"refl.B", zero}, {"refl.A", zero}, {"refl.distance", zero}});
  expectRefused("--quality draft --output-layer refl --spp 3", "without ssrcl's record");
  EXPECT_EQ(batch("--quality draft --output-layer refl --spp 3 --overwrite").exitCode, 0);
}

// A directory nobody can create files in: as root, permissions do not stop writes, but /proc does.
std::string unwritableDirectory(const ssrcl::test::TempDir& dir) {
  if (geteuid() == 0) return "/proc/self";
  const fs::path locked = dir.path() / "locked";
  fs::create_directory(locked);
  fs::permissions(locked, fs::perms::owner_read | fs::perms::owner_exec);
  return locked.string();
}

TEST_F(OutputConventions, UnwritableLocationFailsBeforeAnyTrace) {
  const std::string target = unwritableDirectory(dir) + "/shot.refl.exr";
  // --device 99 does not exist: exit 4 rather than 3 shows the check came before the device was
  // opened, so before any trace.
  auto r = runCommand(cli("trace " + shellQuote(shot) + " -o " + shellQuote(target), "99"));
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find(target), std::string::npos) << r.output;

  writeShot(dir.file("shot.0001.exr"));
  ssrcl::saveCameraJson(dir.file("shot.0001.camera.json"), displayCamera());
  r = runCommand(cli("batch " + shellQuote(dir.file("shot.####.exr")) + " --frames 1 -q -o " +
                     shellQuote(unwritableDirectory(dir) + "/"),
                     "99"));
  EXPECT_EQ(r.exitCode, 4) << r.output;
  EXPECT_NE(r.output.find(unwritableDirectory(dir)), std::string::npos) << r.output;
}

}  // namespace
