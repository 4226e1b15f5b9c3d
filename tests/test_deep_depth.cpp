// Deep OpenEXR depth samples (host/io/exr_deep_depth.cpp): a deep file written here with known
// samples (scanline and tiled, unsorted, empty pixels) is read back exactly, and a real renderer's
// file (Arnold 5.4, tests/data/deep) is read as OpenEXR's own invariants require.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfDeepTiledOutputFile.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfTileDescriptionAttribute.h>

#include <algorithm>
#include <iostream>
#include <vector>

#include "io/exr_deep_depth.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/frame.hpp"
#include "support/temp_dir.hpp"

namespace {

using namespace ssrcl;

constexpr int kWidth = 5, kHeight = 3;

// Pixel i holds i % 4 samples (0 to 3), fronts in decreasing order for odd pixels (a writer need
// not sort), each a distinct interval [z, z + 0.25 (k + 1)].
struct KnownSamples {
  int width = kWidth, height = kHeight;
  std::vector<unsigned> counts;
  std::vector<std::vector<float>> z, zBack;
  explicit KnownSamples(bool pattern = true) {
    if (!pattern) return;
    for (int i = 0; i < kWidth * kHeight; ++i) {
      const unsigned n = unsigned(i % 4);
      counts.push_back(n);
      z.emplace_back();
      zBack.emplace_back();
      for (unsigned k = 0; k < n; ++k) {
        const float front = 1.0f + i + (i % 2 ? float(n - k) : float(k));
        z.back().push_back(front);
        zBack.back().push_back(front + 0.25f * float(k + 1));
      }
    }
  }
};

// Writes the samples with OpenEXR's deep API, data window origin at (originX, originY).
void writeDeep(const std::string& path, const KnownSamples& s, bool tiled, int originX = 2, int originY = 1) {
  const int w = s.width, h = s.height;
  const Imath::Box2i window({originX, originY}, {originX + w - 1, originY + h - 1});
  Imf::Header header(window, window);
  header.channels().insert("Z", Imf::Channel(Imf::FLOAT));
  header.channels().insert("ZBack", Imf::Channel(Imf::FLOAT));
  header.compression() = Imf::ZIPS_COMPRESSION;
  header.setType(tiled ? Imf::DEEPTILE : Imf::DEEPSCANLINE);
  if (tiled) header.setTileDescription(Imf::TileDescription(2, 2, Imf::ONE_LEVEL));
  std::vector<unsigned> counts = s.counts;
  std::vector<const float*> zAt, zBackAt;
  for (int i = 0; i < w * h; ++i) {
    zAt.push_back(s.z[i].data());
    zBackAt.push_back(s.zBack[i].data());
  }
  const long long offset = 1LL * originY * w + originX;  // pixel (0, 0) relative to the window's first
  Imf::DeepFrameBuffer fb;
  fb.insertSampleCountSlice(Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data() - offset), sizeof(unsigned),
                                       sizeof(unsigned) * w));
  fb.insert("Z", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(zAt.data() - offset), sizeof(float*),
                                sizeof(float*) * w, sizeof(float)));
  fb.insert("ZBack", Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(zBackAt.data() - offset), sizeof(float*),
                                    sizeof(float*) * w, sizeof(float)));
  if (tiled) {
    Imf::DeepTiledOutputFile out(path.c_str(), header);
    out.setFrameBuffer(fb);
    out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
  } else {
    Imf::DeepScanLineOutputFile out(path.c_str(), header);
    out.setFrameBuffer(fb);
    out.writePixels(h);
  }
}

// A deep back-face pass as `--back-depth-file`: one sample per pixel, [front, back] of the planar
// pass the corpus scene has, reads as that pass (its nearest sample's ZBack); hard-surface
// samples (ZBack = Z) as unknown.
TEST(DeepDepth, DeepFileGivesTheBackFaceDepth) {
  test::TempDir dir;
  const std::string scene = std::string(SSRCL_SOURCE_DIR) + "/samples/corpus/thin_objects";
  FrameSource planar;
  planar.file = scene + ".exr";
  planar.backDepthFile = scene + ".back.exr";
  const Frame expected = loadFrame(planar);
  const Image& front = expected.gbuffer.depth;
  KnownSamples s(false);
  s.width = front.width;
  s.height = front.height;
  for (size_t i = 0; i < front.data.size(); ++i) {
    const float b = expected.gbuffer.backDepth.data[i], d = front.data[i];
    const bool hard = i % 5 == 0;
    s.counts.push_back(d < 1e9f ? 1 : 0);
    s.z.push_back(d < 1e9f ? std::vector<float>{d} : std::vector<float>{});
    s.zBack.push_back(d < 1e9f ? std::vector<float>{b > 0.0f && !hard ? b : d} : std::vector<float>{});
  }
  writeDeep(dir.file("deep.exr"), s, false, 0, 0);
  FrameSource deep = planar;
  deep.backDepthFile = dir.file("deep.exr");
  const Frame f = loadFrame(deep);
  size_t known = 0;
  for (size_t i = 0; i < front.data.size(); ++i) {
    EXPECT_EQ(f.gbuffer.backDepth.data[i], i % 5 == 0 ? 0.0f : expected.gbuffer.backDepth.data[i]) << "pixel " << i;
    known += f.gbuffer.backDepth.data[i] > 0.0f;
  }
  EXPECT_GT(known, front.data.size() / 10);
}

void expectRead(const std::string& path, const KnownSamples& s) {
  ASSERT_TRUE(detail::isDeepExr(path));
  const detail::DeepDepth d = detail::readDeepDepth(path);
  ASSERT_EQ(d.width, kWidth);
  ASSERT_EQ(d.height, kHeight);
  for (int i = 0; i < kWidth * kHeight; ++i) {
    ASSERT_EQ(d.counts[i], s.counts[i]) << "pixel " << i;
    for (unsigned k = 0; k < s.counts[i]; ++k) {
      EXPECT_EQ(d.z[d.first[i] + k], s.z[i][k]) << "pixel " << i << " sample " << k;
      EXPECT_EQ(d.zBack[d.first[i] + k], s.zBack[i][k]) << "pixel " << i << " sample " << k;
    }
  }
  // The back of each pixel's nearest sample, wherever it is in the list; 0 with no sample.
  const Image back = detail::firstIntervalBack(d);
  for (int i = 0; i < kWidth * kHeight; ++i) {
    if (s.counts[i] == 0) {
      EXPECT_EQ(back.data[i], 0.0f) << "pixel " << i;
      continue;
    }
    const size_t nearest = size_t(std::min_element(s.z[i].begin(), s.z[i].end()) - s.z[i].begin());
    EXPECT_EQ(back.data[i], s.zBack[i][nearest]) << "pixel " << i;
  }
}

TEST(DeepDepth, ScanlineSamplesReadAsWritten) {
  test::TempDir dir;
  const KnownSamples s;
  writeDeep(dir.file("deep.exr"), s, false);
  expectRead(dir.file("deep.exr"), s);
}

TEST(DeepDepth, TiledSamplesReadAsWritten) {
  test::TempDir dir;
  const KnownSamples s;
  writeDeep(dir.file("deep.exr"), s, true);
  expectRead(dir.file("deep.exr"), s);
}

// Arnold's deep output: 150x100, Z and ZBack per sample. Its total (191482 samples, at most 227
// in one pixel) is what an independent decoder of the file's chunks counts (tests/data/deep).
TEST(DeepDepth, ArnoldFileReadAsTheRendererWroteIt) {
  const std::string path = std::string(SSRCL_SOURCE_DIR) + "/tests/data/deep/representativeDeepImage.exr";
  const detail::DeepDepth d = detail::readDeepDepth(path);
  ASSERT_EQ(d.width, 150);
  ASSERT_EQ(d.height, 100);
  uint64_t total = 0;
  uint32_t most = 0;
  for (uint32_t c : d.counts) total += c, most = std::max(most, c);
  EXPECT_EQ(total, d.z.size());
  EXPECT_EQ(total, 191482u);
  EXPECT_EQ(most, 227u);
  size_t unsorted = 0, inverted = 0, intervals = 0;
  for (size_t i = 0; i < d.counts.size(); ++i)
    for (uint64_t k = d.first[i]; k < d.first[i + 1]; ++k) {
      inverted += !(d.zBack[k] >= d.z[k]);
      intervals += d.zBack[k] > d.z[k];
      if (k > d.first[i]) unsorted += d.z[k] < d.z[k - 1];
    }
  EXPECT_EQ(inverted, 0u);  // every sample is an interval [Z, ZBack]
  EXPECT_EQ(unsorted, 0u);  // Arnold writes each pixel's samples front to back
  std::cout << intervals << " of " << total << " samples have ZBack > Z\n";
}

TEST(DeepDepth, FlatFileIsNotDeep) {
  test::TempDir dir;
  const std::string path = std::string(SSRCL_SOURCE_DIR) + "/tests/data/glazed_props.exr";
  EXPECT_FALSE(detail::isDeepExr(path));
  try {
    detail::readDeepDepth(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::InvalidInput);
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
