// EXR input (G-buffer) and output (reflection pass) against files written by the fixtures.

#include <OpenEXR/ImfThreading.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"
#include "support/exr_fixtures.hpp"
#include "support/temp_dir.hpp"

namespace ssrcl {
namespace {

namespace fs = std::filesystem;
using test::ExrChannel;
using test::ExrOptions;
using test::ExrPart;

constexpr int kWidth = 13;  // odd sizes leave partial tiles and chunks
constexpr int kHeight = 9;

ExrChannel channel(const std::string& name, float seed, Imf::PixelType type = Imf::FLOAT) {
  return {name, test::pattern(kWidth, kHeight, seed), type};
}

// Blender's multilayer naming; colour in half as Blender writes it by default.
std::vector<ExrChannel> blenderChannels(const std::string& layer = "ViewLayer") {
  return {channel(layer + ".Combined.R", 1, Imf::HALF),
          channel(layer + ".Combined.G", 2, Imf::HALF),
          channel(layer + ".Combined.B", 3, Imf::HALF),
          channel(layer + ".Combined.A", 4, Imf::HALF),
          channel(layer + ".Depth.Z", 5),
          channel(layer + ".Normal.X", 6),
          channel(layer + ".Normal.Y", 7),
          channel(layer + ".Normal.Z", 8),
          channel(layer + ".roughness.X", 9, Imf::HALF)};
}

std::vector<ExrChannel> plainChannels() {
  return {
      channel("R", 11, Imf::HALF), channel("G", 12, Imf::HALF), channel("B", 13, Imf::HALF), channel("Z", 14),
      channel("N.X", 15),          channel("N.Y", 16),          channel("N.Z", 17),          channel("roughness", 18)};
}

const ExrChannel& named(const std::vector<ExrChannel>& channels, const std::string& name) {
  return *std::find_if(channels.begin(), channels.end(), [&](const ExrChannel& c) { return c.name == name; });
}

// Every pixel of image channel `c` holds what `expected` stored.
void expectChannel(const Image& image, int c, const ExrChannel& expected) {
  ASSERT_EQ(image.width, kWidth);
  ASSERT_EQ(image.height, kHeight);
  int mismatches = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x)
      if (image.at(x, y, c) != test::storedValue(expected.type, expected.values[y * kWidth + x])) ++mismatches;
  EXPECT_EQ(mismatches, 0) << "channel " << c << " vs " << expected.name;
}

void expectGBuffer(const GBuffer& g, const std::vector<ExrChannel>& color, const ExrChannel& depth,
                   const std::vector<ExrChannel>& normal, const ExrChannel* roughness) {
  ASSERT_EQ(g.color.channels, 3);
  ASSERT_EQ(g.depth.channels, 1);
  ASSERT_EQ(g.normal.channels, 3);
  for (int c = 0; c < 3; ++c) expectChannel(g.color, c, color[c]);
  expectChannel(g.depth, 0, depth);
  for (int c = 0; c < 3; ++c) expectChannel(g.normal, c, normal[c]);
  if (roughness) {
    ASSERT_EQ(g.roughness.channels, 1);
    expectChannel(g.roughness, 0, *roughness);
  } else {
    EXPECT_TRUE(g.roughness.empty());
  }
}

void expectBlender(const GBuffer& g, const std::vector<ExrChannel>& ch, const std::string& layer = "ViewLayer") {
  expectGBuffer(g,
                {named(ch, layer + ".Combined.R"), named(ch, layer + ".Combined.G"), named(ch, layer + ".Combined.B")},
                named(ch, layer + ".Depth.Z"),
                {named(ch, layer + ".Normal.X"), named(ch, layer + ".Normal.Y"), named(ch, layer + ".Normal.Z")},
                &named(ch, layer + ".roughness.X"));
}

// Runs `load` expecting Error with `code` whose message starts with `file` and contains `parts`.
template <class F>
void expectError(F&& load, ErrorCode code, const std::string& file, const std::vector<std::string>& parts) {
  try {
    load();
    ADD_FAILURE() << "no error thrown";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_EQ(e.code(), code) << message;
    EXPECT_EQ(message.rfind(file, 0), 0u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

GBufferSource fromFile(const std::string& file, const std::string& layer = "ViewLayer") {
  GBufferSource source;
  source.file = file;
  source.layer = layer;
  return source;
}

TEST(LoadGBuffer, BlenderMultilayerSinglePart) {
  test::TempDir dir;
  const auto ch = blenderChannels();
  test::writeExr(dir.file("render.exr"), kWidth, kHeight, ch);
  expectBlender(loadGBuffer(fromFile(dir.file("render.exr"))), ch);
}

TEST(LoadGBuffer, OtherLayerName) {
  test::TempDir dir;
  auto ch = blenderChannels("Shot");
  const auto decoys = blenderChannels();  // a second layer that must not be picked
  ch.insert(ch.end(), decoys.begin(), decoys.end());
  for (std::size_t i = 9; i < ch.size(); ++i) ch[i].values.assign(ch[i].values.size(), -7.0f);
  test::writeExr(dir.file("render.exr"), kWidth, kHeight, ch);
  expectBlender(loadGBuffer(fromFile(dir.file("render.exr"), "Shot")), ch, "Shot");
}

TEST(LoadGBuffer, ConstantRoughnessNeedsNoRoughnessChannel) {
  test::TempDir dir;
  auto ch = blenderChannels();
  ch.pop_back();
  test::writeExr(dir.file("render.exr"), kWidth, kHeight, ch);
  auto source = fromFile(dir.file("render.exr"));
  source.readRoughness = false;
  const GBuffer g = loadGBuffer(source);
  expectGBuffer(g, {ch[0], ch[1], ch[2]}, ch[4], {ch[5], ch[6], ch[7]}, nullptr);
}

TEST(LoadGBuffer, MultiPartWithLayerPassParts) {
  // Part "ViewLayer.Combined" with channel "R" and so on.
  test::TempDir dir;
  const std::vector<ExrPart> parts = {
      {"ViewLayer.Combined",
       {channel("R", 1, Imf::HALF), channel("G", 2, Imf::HALF), channel("B", 3, Imf::HALF),
        channel("A", 4, Imf::HALF)}},
      {"ViewLayer.Depth", {channel("Z", 5)}},
      {"ViewLayer.Normal", {channel("X", 6), channel("Y", 7), channel("Z", 8)}},
      {"ViewLayer.roughness", {channel("X", 9, Imf::HALF)}},
  };
  test::writeMultiPartExr(dir.file("parts.exr"), kWidth, kHeight, parts);
  const GBuffer g = loadGBuffer(fromFile(dir.file("parts.exr")));
  expectGBuffer(g, {parts[0].channels[0], parts[0].channels[1], parts[0].channels[2]}, parts[1].channels[0],
                {parts[2].channels[0], parts[2].channels[1], parts[2].channels[2]}, &parts[3].channels[0]);
}

TEST(LoadGBuffer, MultiPartWithLayerParts) {
  // Part "ViewLayer" with channel "Combined.R", next to another layer's part with the same names.
  test::TempDir dir;
  std::vector<ExrChannel> layer = blenderChannels("");
  for (ExrChannel& c : layer) c.name.erase(0, 1);  // ".Combined.R" -> "Combined.R"
  std::vector<ExrChannel> other = layer;
  for (ExrChannel& c : other) c.values.assign(c.values.size(), -3.0f);
  test::writeMultiPartExr(dir.file("parts.exr"), kWidth, kHeight, {{"Other", other}, {"ViewLayer", layer}});
  const GBuffer g = loadGBuffer(fromFile(dir.file("parts.exr")));
  expectGBuffer(g, {layer[0], layer[1], layer[2]}, layer[4], {layer[5], layer[6], layer[7]}, &layer[8]);
}

TEST(LoadGBuffer, SinglePartWithPartName) {
  // One named part is stored as a single-part file that keeps its name; the name still counts.
  test::TempDir dir;
  const auto ch = blenderChannels("");
  std::vector<ExrChannel> layer = ch;
  for (ExrChannel& c : layer) c.name.erase(0, 1);
  test::writeMultiPartExr(dir.file("named.exr"), kWidth, kHeight, {{"ViewLayer", layer}});
  const GBuffer g = loadGBuffer(fromFile(dir.file("named.exr")));
  expectGBuffer(g, {layer[0], layer[1], layer[2]}, layer[4], {layer[5], layer[6], layer[7]}, &layer[8]);
}

TEST(LoadGBuffer, MultiPartWithFullChannelNames) {
  // Parts whose channels carry the whole name are found by exact match, whatever the part is called.
  test::TempDir dir;
  const auto ch = blenderChannels();
  test::writeMultiPartExr(dir.file("parts.exr"), kWidth, kHeight,
                          {{"beauty", {ch[0], ch[1], ch[2], ch[3]}}, {"data", {ch[4], ch[5], ch[6], ch[7], ch[8]}}});
  expectBlender(loadGBuffer(fromFile(dir.file("parts.exr"))), ch);
}

TEST(LoadGBuffer, PlainSingleLayerWithUintRoughness) {
  test::TempDir dir;
  auto ch = plainChannels();
  ch.back() = {"roughness", std::vector<float>(kWidth * kHeight), Imf::UINT};
  for (std::size_t i = 0; i < ch.back().values.size(); ++i) ch.back().values[i] = float(i * 3 % 7);
  test::writeExr(dir.file("plain.exr"), kWidth, kHeight, ch);
  const GBuffer g = loadGBuffer(fromFile(dir.file("plain.exr"), ""));
  expectGBuffer(g, {ch[0], ch[1], ch[2]}, ch[3], {ch[4], ch[5], ch[6]}, &ch[7]);
}

TEST(LoadGBuffer, ExplicitChannelNames) {
  test::TempDir dir;
  const std::vector<ExrChannel> ch = {channel("Y", 1, Imf::HALF), channel("depth", 2), channel("nx", 3),
                                      channel("ny", 4),           channel("nz", 5),    channel("rough", 6)};
  test::writeExr(dir.file("custom.exr"), kWidth, kHeight, ch);
  GBufferSource source = fromFile(dir.file("custom.exr"));
  source.colorChannels = "Y,Y, Y";  // the same channel three times, spaces tolerated
  source.depthChannel = "depth";
  source.normalChannels = "nx,ny,nz";
  source.roughnessChannel = "rough";
  const GBuffer g = loadGBuffer(source);
  expectGBuffer(g, {ch[0], ch[0], ch[0]}, ch[1], {ch[2], ch[3], ch[4]}, &ch[5]);
}

TEST(LoadGBuffer, PerPassFilesOverrideTheMainFile) {
  test::TempDir dir;
  const auto ch = plainChannels();
  test::writeExr(dir.file("color.exr"), kWidth, kHeight, {ch[0], ch[1], ch[2]});
  test::writeExr(dir.file("depth.exr"), kWidth, kHeight, {ch[3]});
  test::writeExr(dir.file("normal.exr"), kWidth, kHeight, {ch[4], ch[5], ch[6]});
  test::writeExr(dir.file("rough.exr"), kWidth, kHeight, {ch[7]});
  // The main file has every pass, with values that must lose against the per-pass files.
  auto decoy = ch;
  for (ExrChannel& c : decoy) c.values.assign(c.values.size(), 42.0f);
  test::writeExr(dir.file("main.exr"), kWidth, kHeight, decoy);

  GBufferSource source = fromFile("", "");
  source.colorFile = dir.file("color.exr");
  source.depthFile = dir.file("depth.exr");
  source.normalFile = dir.file("normal.exr");
  source.roughnessFile = dir.file("rough.exr");
  expectGBuffer(loadGBuffer(source), {ch[0], ch[1], ch[2]}, ch[3], {ch[4], ch[5], ch[6]}, &ch[7]);

  source.file = dir.file("main.exr");
  source.colorFile.clear();
  expectGBuffer(loadGBuffer(source), {decoy[0], decoy[1], decoy[2]}, ch[3], {ch[4], ch[5], ch[6]}, &ch[7]);
}

TEST(LoadGBuffer, TiledSingleAndMultiPart) {
  test::TempDir dir;
  const auto ch = blenderChannels();
  ExrOptions options;
  options.tiled = true;
  test::writeExr(dir.file("tiled.exr"), kWidth, kHeight, ch, options);
  expectBlender(loadGBuffer(fromFile(dir.file("tiled.exr"))), ch);

  options.tileSize = 8;
  test::writeMultiPartExr(dir.file("tiled_parts.exr"), kWidth, kHeight,
                          {{"beauty", {ch[0], ch[1], ch[2], ch[3]}}, {"data", {ch[4], ch[5], ch[6], ch[7], ch[8]}}},
                          options);
  expectBlender(loadGBuffer(fromFile(dir.file("tiled_parts.exr"))), ch);
}

TEST(LoadGBuffer, DataWindowWithNonZeroOrigin) {
  test::TempDir dir;
  const auto ch = blenderChannels();
  ExrOptions options;
  options.originX = 5;
  options.originY = -3;
  test::writeExr(dir.file("window.exr"), kWidth, kHeight, ch, options);
  expectBlender(loadGBuffer(fromFile(dir.file("window.exr"))), ch);
  options.tiled = true;
  test::writeExr(dir.file("window_tiled.exr"), kWidth, kHeight, ch, options);
  expectBlender(loadGBuffer(fromFile(dir.file("window_tiled.exr"))), ch);
}

class LosslessCompression : public testing::TestWithParam<Imf::Compression> {};

TEST_P(LosslessCompression, ReadsBackExactly) {
  test::TempDir dir;
  const auto ch = blenderChannels();
  ExrOptions options;
  options.compression = GetParam();
  test::writeExr(dir.file("c.exr"), kWidth, kHeight, ch, options);
  expectBlender(loadGBuffer(fromFile(dir.file("c.exr"))), ch);
}

INSTANTIATE_TEST_SUITE_P(Compressions, LosslessCompression,
                         testing::Values(Imf::NO_COMPRESSION, Imf::RLE_COMPRESSION, Imf::ZIPS_COMPRESSION,
                                         Imf::ZIP_COMPRESSION, Imf::PIZ_COMPRESSION));

TEST(LoadGBuffer, DwaaCompressed) {
  // DWAA is lossy for channels whose last name component is R, G, B or Y, whatever their type:
  // that includes Normal.Y. Everything else passes through exactly.
  test::TempDir dir;
  const auto ch = blenderChannels();
  ExrOptions options;
  options.compression = Imf::DWAA_COMPRESSION;
  test::writeExr(dir.file("dwaa.exr"), kWidth, kHeight, ch, options);
  const GBuffer g = loadGBuffer(fromFile(dir.file("dwaa.exr")));
  const auto expectClose = [](const Image& image, int c, const ExrChannel& expected) {
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) {
        const float v = expected.values[y * kWidth + x];
        ASSERT_NEAR(image.at(x, y, c), v, 0.02f * std::abs(v) + 0.01f) << expected.name;
      }
  };
  for (int c = 0; c < 3; ++c) expectClose(g.color, c, ch[c]);
  expectChannel(g.depth, 0, ch[4]);
  expectChannel(g.normal, 0, ch[5]);
  expectClose(g.normal, 1, ch[6]);
  expectChannel(g.normal, 2, ch[7]);
  expectChannel(g.roughness, 0, ch[8]);
}

TEST(LoadGBufferErrors, MissingChannelIsNamedWithWhatTheFileHas) {
  test::TempDir dir;
  auto ch = blenderChannels();
  ch.erase(ch.begin() + 4);  // no depth
  const std::string file = dir.file("nodepth.exr");
  test::writeExr(file, kWidth, kHeight, ch);
  expectError([&] { loadGBuffer(fromFile(file)); }, ErrorCode::InvalidInput, file,
              {"missing channel 'ViewLayer.Depth.Z'", "depth", "has: ", "ViewLayer.Normal.X"});
}

TEST(LoadGBufferErrors, ChannelListIsShortened) {
  test::TempDir dir;
  std::vector<ExrChannel> many;
  for (int i = 0; i < 30; ++i) many.push_back(channel("extra" + std::to_string(100 + i), float(i)));
  const std::string file = dir.file("many.exr");
  test::writeExr(file, kWidth, kHeight, many);
  expectError([&] { loadGBuffer(fromFile(file, "")); }, ErrorCode::InvalidInput, file,
              {"missing channel 'R'", "extra100, extra101", "(18 more)"});
}

TEST(LoadGBufferErrors, MissingRoughnessUnlessConstant) {
  test::TempDir dir;
  auto ch = blenderChannels();
  ch.pop_back();
  const std::string file = dir.file("norough.exr");
  test::writeExr(file, kWidth, kHeight, ch);
  expectError([&] { loadGBuffer(fromFile(file)); }, ErrorCode::InvalidInput, file, {"'ViewLayer.roughness.X'"});
}

// Houdini writes each render var as a part of channels R, G, B (a file with parts N, albedo and C:
// github.com/AcademySoftwareFoundation/OpenImageIO/issues/3593). A bare "R" is then in every part:
// refused, naming the qualified names, instead of reading the first part's (the normals) as colour.
TEST(LoadGBufferErrors, BareNameInSeveralPartsIsRefused) {
  test::TempDir dir;
  const std::string file = dir.file("houdini.exr");
  const std::vector<ExrPart> parts = {{"N", {channel("R", 1), channel("G", 2), channel("B", 3)}},
                                      {"C", {channel("R", 4), channel("G", 5), channel("B", 6), channel("Z", 7)}},
                                      {"roughness", {channel("Y", 8)}}};
  test::writeMultiPartExr(file, kWidth, kHeight, parts);
  GBufferSource source = fromFile(file, "");
  source.depthChannel = "C.Z";
  source.normalChannels = "N.R,N.G,N.B";
  source.roughnessChannel = "roughness.Y";
  expectError([&] { loadGBuffer(source); }, ErrorCode::InvalidInput, file, {"'R' is in 2 parts", "'N.R', 'C.R'"});
  // Alternatives that the file holds only ambiguously say so, not that the channels are missing.
  source.colorChannels = "r,g,b|R,G,B";
  expectError([&] { loadGBuffer(source); }, ErrorCode::InvalidInput, file, {"'R' is in 2 parts", "'N.R', 'C.R'"});
  source.colorChannels = "C.R,C.G,C.B";
  expectGBuffer(loadGBuffer(source), {parts[1].channels[0], parts[1].channels[1], parts[1].channels[2]},
                parts[1].channels[3], {parts[0].channels[0], parts[0].channels[1], parts[0].channels[2]},
                &parts[2].channels[0]);
}

// "a|b" lists: the first alternative the file holds is read; when it holds none, every
// alternative is named.
TEST(LoadGBuffer, ChannelAlternatives) {
  test::TempDir dir;
  const std::string file = dir.file("alternatives.exr");
  const std::vector<ExrChannel> ch = {channel("R", 1),   channel("G", 2),   channel("B", 3),   channel("z", 4),
                                      channel("N.R", 5), channel("N.G", 6), channel("N.B", 7), channel("roughness", 8)};
  test::writeExr(file, kWidth, kHeight, ch);
  GBufferSource source = fromFile(file, "");
  source.depthChannel = "Z|z";
  source.normalChannels = "N.x,N.y,N.z|N.R,N.G,N.B";
  expectGBuffer(loadGBuffer(source), {ch[0], ch[1], ch[2]}, ch[3], {ch[4], ch[5], ch[6]}, &ch[7]);
  source.normalChannels = "N.x,N.y,N.z|N.X,N.Y,N.Z";
  expectError([&] { loadGBuffer(source); }, ErrorCode::InvalidInput, file,
              {"none of the channel sets 'N.x,N.y,N.z', 'N.X,N.Y,N.Z' for the normal pass", "has: B, G, N.B"});
}

TEST(LoadGBufferErrors, MultiPartListsQualifiedNames) {
  test::TempDir dir;
  const std::string file = dir.file("parts.exr");
  test::writeMultiPartExr(file, kWidth, kHeight,
                          {{"ViewLayer.Combined", {channel("R", 1)}}, {"ViewLayer.Depth", {channel("Z", 2)}}});
  expectError([&] { loadGBuffer(fromFile(file)); }, ErrorCode::InvalidInput, file,
              {"'ViewLayer.Combined.G'", "has: ViewLayer.Combined.R, ViewLayer.Depth.Z)"});
}

TEST(LoadGBufferErrors, SizeMismatchBetweenPassFiles) {
  test::TempDir dir;
  const auto ch = plainChannels();
  test::writeExr(dir.file("main.exr"), kWidth, kHeight, ch);
  test::writeExr(dir.file("depth.exr"), kWidth + 1, kHeight, {{"Z", test::pattern(kWidth + 1, kHeight, 0)}});
  GBufferSource source = fromFile(dir.file("main.exr"), "");
  source.depthFile = dir.file("depth.exr");
  expectError([&] { loadGBuffer(source); }, ErrorCode::InvalidInput, dir.file("depth.exr"),
              {"'Z' is 14x9", dir.file("main.exr") + " channel 'R' is 13x9"});
}

TEST(LoadGBufferErrors, BadChannelLists) {
  test::TempDir dir;
  test::writeExr(dir.file("render.exr"), kWidth, kHeight, blenderChannels());
  GBufferSource source = fromFile(dir.file("render.exr"));
  source.normalChannels = "X,Y";
  EXPECT_THROW(
      try { loadGBuffer(source); } catch (const Error& e) {
        EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
        EXPECT_NE(std::string(e.what()).find("normal"), std::string::npos) << e.what();
        throw;
      },
      Error);
  source.normalChannels = "X,,Z";
  EXPECT_THROW(loadGBuffer(source), Error);
}

TEST(LoadGBufferErrors, NoFileGiven) {
  try {
    loadGBuffer(GBufferSource{});
    FAIL() << "no error thrown";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidArgument);
  }
}

TEST(LoadGBufferErrors, NonExistentFile) {
  test::TempDir dir;
  const std::string file = dir.file("nothing.exr");
  expectError([&] { loadGBuffer(fromFile(file)); }, ErrorCode::IoError, file, {"not a readable OpenEXR file"});
}

TEST(LoadGBufferErrors, ZeroByteFile) {
  test::TempDir dir;
  const std::string file = dir.file("empty.exr");
  test::writeBytes(file, "");
  expectError([&] { loadGBuffer(fromFile(file)); }, ErrorCode::IoError, file, {"not a readable OpenEXR file"});
}

TEST(LoadGBufferErrors, PngRenamedToExr) {
  test::TempDir dir;
  const std::string file = dir.file("image.exr");
  const char png[] = "\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\0\x10\0\0\0\x10\x08\x02\0\0\0";  // signature + IHDR
  test::writeBytes(file, std::string(png, sizeof png - 1));
  expectError([&] { loadGBuffer(fromFile(file)); }, ErrorCode::IoError, file, {"not a readable OpenEXR file"});
}

TEST(LoadGBufferErrors, DirectoryInsteadOfFile) {
  test::TempDir dir;
  expectError([&] { loadGBuffer(fromFile(dir.path().string())); }, ErrorCode::IoError, dir.path().string(), {});
}

// Cutting a valid file anywhere must give a typed error, never a crash or silent garbage.
class TruncatedFile : public testing::TestWithParam<bool> {};

TEST_P(TruncatedFile, ThrowsIoErrorAtEveryCut) {
  test::TempDir dir;
  constexpr int kSize = 64;  // several chunks per channel
  std::vector<ExrChannel> ch;
  for (const char* name : {"R", "G", "B", "Z", "N.X", "N.Y", "N.Z", "roughness"})
    ch.push_back({name, test::pattern(kSize, kSize, float(ch.size()))});
  ExrOptions options;
  options.tiled = GetParam();
  options.tileSize = 16;
  const std::string good = dir.file("good.exr");
  test::writeExr(good, kSize, kSize, ch, options);
  const std::string bytes = test::readBytes(good);
  for (double fraction : {0.02, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99}) {
    const std::string file = dir.file("cut.exr");
    test::writeBytes(file, bytes.substr(0, std::size_t(bytes.size() * fraction)));
    SCOPED_TRACE(fraction);
    expectError([&] { loadGBuffer(fromFile(file, "")); }, ErrorCode::IoError, file, {});
  }
}

INSTANTIATE_TEST_SUITE_P(ScanlineAndTiled, TruncatedFile, testing::Bool());

Image filled(int width, int height, int channels, float seed) {
  Image image(width, height, channels);
  for (std::size_t i = 0; i < image.data.size(); ++i) image.data[i] = seed + 0.013f * float(i);
  return image;
}

std::vector<std::string> listDir(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(WriteReflectionExr, RoundTripsAsFloatRle) {
  test::TempDir dir;
  const Image rgba = filled(kWidth, kHeight, 4, 1.0f);
  Image distance = filled(kWidth, kHeight, 1, 100.0f);
  distance.at(3, 2, 0) = INFINITY;  // misses are written as they are
  const std::string file = dir.file("refl.exr");
  writeReflectionExr(file, rgba, distance);

  const test::ExrContents contents = test::readExr(file);
  EXPECT_EQ(contents.width, kWidth);
  EXPECT_EQ(contents.height, kHeight);
  EXPECT_EQ(contents.compression, Imf::RLE_COMPRESSION);
  ASSERT_EQ(contents.channels.size(), 5u);
  const char* names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    const ExrChannel& channel = contents.channels.at(names[c]);
    EXPECT_EQ(channel.type, Imf::FLOAT);
    for (int y = 0; y < kHeight; ++y)
      for (int x = 0; x < kWidth; ++x) ASSERT_EQ(channel.values[y * kWidth + x], rgba.at(x, y, c));
  }
  const ExrChannel& d = contents.channels.at("distance");
  EXPECT_EQ(d.type, Imf::FLOAT);
  EXPECT_EQ(d.values, distance.data);
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"refl.exr"});  // no temporary left behind
}

TEST(WriteReflectionExr, ReplacesAnExistingFile) {
  test::TempDir dir;
  const std::string file = dir.file("refl.exr");
  writeReflectionExr(file, filled(4, 4, 4, 1.0f), filled(4, 4, 1, 2.0f));
  writeReflectionExr(file, filled(kWidth, kHeight, 4, 5.0f), filled(kWidth, kHeight, 1, 6.0f));
  const test::ExrContents contents = test::readExr(file);
  EXPECT_EQ(contents.width, kWidth);
  EXPECT_EQ(contents.channels.at("distance").values, filled(kWidth, kHeight, 1, 6.0f).data);
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"refl.exr"});
}

TEST(WriteReflectionExr, RelativePathInTheCurrentDirectory) {
  test::TempDir dir;
  const fs::path previous = fs::current_path();
  fs::current_path(dir.path());
  writeReflectionExr("refl.exr", filled(2, 3, 4, 0.0f), filled(2, 3, 1, 0.0f));
  fs::current_path(previous);
  EXPECT_EQ(test::readExr(dir.file("refl.exr")).height, 3);
}

TEST(WriteReflectionExr, MismatchedImagesLeaveTheTargetUntouched) {
  test::TempDir dir;
  const std::string file = dir.file("refl.exr");
  writeReflectionExr(file, filled(4, 4, 4, 1.0f), filled(4, 4, 1, 2.0f));
  const std::string before = test::readBytes(file);
  const std::vector<std::pair<Image, Image>> bad = {
      {filled(4, 4, 3, 0), filled(4, 4, 1, 0)},  // not RGBA
      {filled(4, 4, 4, 0), filled(4, 4, 2, 0)},  // distance with 2 channels
      {filled(4, 4, 4, 0), filled(5, 4, 1, 0)},  // size mismatch
      {Image(), Image()},                        // empty
  };
  for (const auto& [rgba, distance] : bad) {
    expectError([&] { writeReflectionExr(file, rgba, distance); }, ErrorCode::InvalidArgument, file, {});
  }
  EXPECT_EQ(test::readBytes(file), before);
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"refl.exr"});
}

TEST(WriteReflectionExr, MissingDirectory) {
  test::TempDir dir;
  const std::string file = dir.file("no/such/dir/refl.exr");
  expectError([&] { writeReflectionExr(file, filled(2, 2, 4, 0), filled(2, 2, 1, 0)); }, ErrorCode::IoError, file,
              {"cannot write", "is not an existing directory"});
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(WriteReflectionExr, FailedRenameRemovesTheTemporary) {
  // The target is a non-empty directory: the temporary file is written, renaming over it fails.
  test::TempDir dir;
  const std::string target = dir.file("refl.exr");
  fs::create_directory(target);
  test::writeBytes(target + "/keep", "content");
  expectError([&] { writeReflectionExr(target, filled(2, 2, 4, 0), filled(2, 2, 1, 0)); }, ErrorCode::IoError, target,
              {"cannot write (cannot replace it"});
  EXPECT_EQ(listDir(dir.path()), std::vector<std::string>{"refl.exr"});
  EXPECT_EQ(test::readBytes(target + "/keep"), "content");
}

// OpenEXR's pool compresses chunks out of order; the file must not show it. Tall enough for many
// ZIP chunks of 16 lines, and read back through the pool too.
TEST(WriteReflectionExr, ThreadedIsTheSameBytesAndPixels) {
  test::TempDir dir;
  constexpr int width = 37, height = 203;
  Image rgba(width, height, 4), distance(width, height, 1);
  const std::vector<float> values = test::pattern(width, height * 5, 21);
  std::copy(values.begin(), values.begin() + rgba.data.size(), rgba.data.begin());
  std::copy(values.begin() + rgba.data.size(), values.end(), distance.data.begin());
  const std::string serial = dir.file("serial.exr"), threaded = dir.file("threaded.exr");
  setExrThreads(0);
  writeReflectionExr(serial, rgba, distance);
  setExrThreads(3);
  ASSERT_EQ(Imf::globalThreadCount(), 3);
  writeReflectionExr(threaded, rgba, distance);
  const test::ExrContents contents = test::readExr(threaded);
  setExrThreads(0);
  EXPECT_EQ(test::readBytes(threaded), test::readBytes(serial));
  EXPECT_EQ(contents.channels.at("distance").values, distance.data);
  const std::vector<float>& b = contents.channels.at("B").values;
  for (int i = 0; i < width * height; ++i) ASSERT_EQ(b[i], rgba.data[i * 4 + 2]) << "pixel " << i;
}

TEST(LoadGBuffer, ThreadedReadsTheSamePixels) {
  test::TempDir dir;
  const auto ch = blenderChannels();
  test::writeExr(dir.file("render.exr"), kWidth, kHeight, ch, {Imf::ZIPS_COMPRESSION});  // a chunk per line
  setExrThreads(3);
  const GBuffer g = loadGBuffer(fromFile(dir.file("render.exr")));
  setExrThreads(0);
  expectBlender(g, ch);
}

}  // namespace
}  // namespace ssrcl
