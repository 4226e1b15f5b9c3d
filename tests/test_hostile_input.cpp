// Hostile and broken input, and device problems (issue 6), through the `ssrcl` command where a
// user meets them: one clear line naming the file and what is wrong, a non-zero exit code, and
// an existing output file left exactly as it was (no temporary left behind either).
//
// Complements test_io.cpp, test_camera.cpp and test_cli.cpp, which cover the loaders' errors as
// library calls (zero-byte, truncated and PNG files, missing channels, size mismatches, camera
// fields) and the CLI's basic exit codes; what is here is what they do not: those failures end
// to end with the output untouched, headers declaring absurd sizes, deep and subsampled data,
// corrupted pixel data, hostile camera JSON, no OpenCL platform, a kernel build failure with its
// log, and device memory limits.
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineOutputFile.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "pipeline/device_impl.hpp"
#include "scenes/analytic_scene.hpp"
#include "ssrcl/ssrcl.hpp"
#include "support/scoped_env.hpp"
#include "support/exr_fixtures.hpp"
#include "support/run_command.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

namespace {

using namespace ssrcl;
using namespace ssrcl::test;
namespace fs = std::filesystem;
using nlohmann::json;

constexpr int kW = 40, kH = 30;
const std::string kEarlier = "an earlier, good result";

std::string cli(const std::string& args) { return shellQuote(SSRCL_CLI) + " " + args; }

// A Blender-style G-buffer of spheres on a mirror, with its camera sidecar.
struct Shot {
  Camera camera;
  std::vector<ExrChannel> channels;
};

Shot makeShot() {
  const Scene scene = makeScene("spheres_on_mirror");
  Shot s;
  s.camera = makeCamera(scene.view, kW, kH);
  const AnalyticGBuffer g = renderGBuffer(scene, s.camera);
  const auto plane = [&](const Image& image, int c) {
    std::vector<float> v(size_t(kW) * kH);
    for (int y = 0; y < kH; ++y)
      for (int x = 0; x < kW; ++x) v[size_t(y) * kW + x] = image.at(x, y, c);
    return v;
  };
  s.channels = {{"ViewLayer.Combined.R", plane(g.color, 0), Imf::HALF},
                {"ViewLayer.Combined.G", plane(g.color, 1), Imf::HALF},
                {"ViewLayer.Combined.B", plane(g.color, 2), Imf::HALF},
                {"ViewLayer.Depth.Z", plane(g.depth, 0)},
                {"ViewLayer.Normal.X", plane(g.normal, 0)},
                {"ViewLayer.Normal.Y", plane(g.normal, 1)},
                {"ViewLayer.Normal.Z", plane(g.normal, 2)},
                {"ViewLayer.roughness.X", plane(g.roughness, 0)}};
  return s;
}

class Hostile : public ::testing::Test {
 protected:
  TempDir dir{"ssrcl-hostile"};
  std::string shot = dir.file("shot.exr");
  std::string camera = dir.file("shot.camera.json");
  std::string out = dir.file("shot.refl.exr");
  Shot good = makeShot();

  void SetUp() override {
    writeExr(shot, kW, kH, good.channels);
    saveCameraJson(camera, good.camera);
  }

  std::string trace(const std::string& extra = "") {
    return cli("trace " + shellQuote(shot) + " -o " + shellQuote(out) + (extra.empty() ? "" : " " + extra));
  }

  // Fails with `code`, one line on stderr that names `file` and contains each of `needles`, and
  // leaves the earlier output byte for byte, with no temporary beside it.
  void expectFailure(const std::string& command, int code, const std::string& file,
                     const std::vector<std::string>& needles, const std::string& env = "") {
    writeBytes(out, kEarlier);
    const CommandResult r = runCommand(env + command);
    EXPECT_EQ(r.exitCode, code) << r.output;
    // Our one line (an OpenCL driver may print its own before it, e.g. PoCL's "1 error generated").
    const size_t at = r.output.rfind("ssrcl: ", 0) == 0 ? 0 : r.output.find("\nssrcl: ");
    ASSERT_NE(at, std::string::npos) << r.output;
    const std::string first = r.output.substr(at + (at ? 1 : 0), r.output.find('\n', at + 1) - at);
    if (!file.empty()) EXPECT_NE(first.find(file), std::string::npos) << "file not named: " << r.output;
    for (const std::string& n : needles)
      EXPECT_NE(r.output.find(n), std::string::npos) << "'" << n << "' in " << r.output;
    EXPECT_EQ(readBytes(out), kEarlier) << "the earlier output was touched";
    for (const auto& e : fs::directory_iterator(dir.path()))
      EXPECT_EQ(e.path().filename().string().find(".tmp"), std::string::npos) << "left behind: " << e.path();
  }
};

TEST_F(Hostile, TheGoodShotTraces) {
  const CommandResult r = runCommand(trace());
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const ExrContents exr = readExr(out);
  int lit = 0;
  for (float a : exr.channels.at("A").values) lit += a > 0;
  EXPECT_GT(lit, 50);  // the other tests' failures are not for want of a usable shot
}

// ------------------------------------------------------------------------------------------------
// Broken G-buffer files

TEST_F(Hostile, ZeroByteAndTruncatedExr) {
  const std::string bytes = readBytes(shot);
  writeBytes(shot, "");
  expectFailure(trace(), 2, shot, {"not a readable OpenEXR file"});
  // Cut in the magic number, the header, the offset table and the pixel data.
  for (size_t cut : {size_t(3), size_t(40), bytes.size() / 4, bytes.size() / 2, bytes.size() - 10}) {
    SCOPED_TRACE(cut);
    writeBytes(shot, bytes.substr(0, cut));
    expectFailure(trace(), 2, shot, {});
  }
}

TEST_F(Hostile, CorruptCompressedPixelData) {
  const std::string bytes = readBytes(shot);
  // Bytes overwritten in the compressed chunks (after the header and offset table): the
  // decompressor notices (zlib's checksum), and says so naming the file.
  for (double at : {0.5, 0.7, 0.9}) {
    std::string bad = bytes;
    for (size_t k = 0; k < 16; ++k) bad[size_t(bad.size() * at) + k] ^= char(0x5a);
    writeBytes(shot, bad);
    SCOPED_TRACE(at);
    expectFailure(trace(), 2, shot, {});
  }
}

// Uncompressed pixel data cannot tell flipped bits from values: the file loads, and whatever
// the values (NaN, infinities, huge), the pass is written and sane.
TEST_F(Hostile, CorruptUncompressedValuesStillGiveASanePass) {
  ExrOptions options;
  options.compression = Imf::NO_COMPRESSION;
  writeExr(shot, kW, kH, good.channels, options);
  const std::string bytes = readBytes(shot);
  std::mt19937 rng(7);
  int written = 0;
  // The file ends with one chunk per scanline: its y and byte count (8 bytes, structure a reader
  // rightly refuses when broken), then the pixels.
  size_t lineBytes = 0;
  for (const ExrChannel& c : good.channels) lineBytes += size_t(kW) * (c.type == Imf::HALF ? 2 : 4);
  const size_t chunk = 8 + lineBytes, pixelsStart = bytes.size() - size_t(kH) * chunk;
  for (int round = 0; round < 4; ++round) {
    std::string bad = bytes;
    // Scatter 0xff bytes (NaN/-Inf patterns in float and half) over the pixel bytes.
    for (int k = 0; k < 400; ++k) {
      const size_t at = pixelsStart + rng() % (bytes.size() - pixelsStart);
      if ((at - pixelsStart) % chunk >= 8) bad[at] = char(round % 2 ? 0xff : 0x7f);
    }
    writeBytes(shot, bad);
    const CommandResult r = runCommand(trace());
    ASSERT_TRUE(r.exitCode == 0 || r.exitCode == 2) << r.output;
    if (r.exitCode != 0) continue;
    ++written;
    const ExrContents exr = readExr(out);
    for (const char* c : {"R", "G", "B", "A", "distance"})
      for (float v : exr.channels.at(c).values) ASSERT_TRUE(std::isfinite(v)) << c;
    for (float a : exr.channels.at("A").values) ASSERT_TRUE(a >= 0.0f && a <= 1.0f) << a;
  }
  // Without a written pass the loop above asserted nothing about the values.
  EXPECT_GT(written, 0);
}

// Byte offset of a box2i attribute's value in an EXR header.
size_t boxAttribute(const std::string& bytes, const std::string& name) {
  const std::string key = name + std::string("\0box2i\0", 7);
  const size_t at = bytes.find(key);
  if (at == std::string::npos) throw std::runtime_error("no " + name + " in the header");
  return at + key.size() + 4;  // after the attribute's 4-byte size
}

void setBox(std::string& bytes, const std::string& name, int32_t x0, int32_t y0, int32_t x1, int32_t y1) {
  const size_t at = boxAttribute(bytes, name);
  const int32_t values[4] = {x0, y0, x1, y1};
  std::memcpy(&bytes[at], values, sizeof values);  // EXR is little-endian, as is every CI host
}

// A header is all it takes to declare any size. Refused before anything is allocated: beyond
// 2^30 pixels as unusable input, within it when the G-buffer would not fit in this machine's
// memory (the loader does not leave that to the kernel's out-of-memory killer).
TEST_F(Hostile, HeaderDeclaringAnAbsurdSize) {
  // The header patched, and room for the offset table of the declared height (else OpenEXR
  // already stops at the missing table).
  const std::string bytes = readBytes(shot) + std::string(size_t(1) << 16, '\0');
  struct Case {
    int32_t x0, y0, x1, y1;
    std::vector<std::string> needles;
  };
  const Case cases[] = {
      {0, 0, 99999, 99999, {"100000x100000", "2^30"}},
      {0, 0, 1999999999, 0, {"data window"}},  // OpenEXR's own sanity limit
      // 2^32 wide: the window's width overflows int.
      {-2147483647 - 1, 0, 2147483647, 0, {"data window"}},
      {5, 5, 0, 0, {}},  // empty (max < min): OpenEXR refuses the header
  };
  for (const Case& c : cases) {
    std::string bad = bytes;
    setBox(bad, "dataWindow", c.x0, c.y0, c.x1, c.y1);
    writeBytes(shot, bad);
    SCOPED_TRACE(std::to_string(c.x1) + "," + std::to_string(c.y1));
    expectFailure(trace(), 2, shot, c.needles);
  }
  // 32768 x 32767 fits the frame limit but needs 32 GiB; refused where the machine has less.
  const double memory = double(sysconf(_SC_PHYS_PAGES)) * double(sysconf(_SC_PAGE_SIZE));
  if (memory > 32.0 * 32768 * 32767) GTEST_SKIP() << "this machine could allocate that much: not tried";
  std::string big = bytes;
  setBox(big, "dataWindow", 0, 0, 32767, 32766);
  writeBytes(shot, big);
  expectFailure(trace(), 3, shot, {"32768x32767", "GiB of memory"});
}

TEST_F(Hostile, DeepDataIsRefusedByName) {
  Imf::Header header(kW, kH);
  header.setType(Imf::DEEPSCANLINE);
  header.compression() = Imf::ZIPS_COMPRESSION;
  for (const ExrChannel& c : good.channels) header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
  {
    Imf::DeepScanLineOutputFile file(shot.c_str(), header);
    std::vector<unsigned> counts(size_t(kW) * kH, 1);
    std::vector<std::vector<float*>> pointers(good.channels.size(), std::vector<float*>(size_t(kW) * kH));
    std::vector<std::vector<float>> values = {};
    for (const ExrChannel& c : good.channels) values.push_back(c.values);
    Imf::DeepFrameBuffer fb;
    fb.insertSampleCountSlice(
        Imf::Slice(Imf::UINT, reinterpret_cast<char*>(counts.data()), sizeof(unsigned), sizeof(unsigned) * kW));
    for (size_t k = 0; k < good.channels.size(); ++k) {
      for (size_t i = 0; i < counts.size(); ++i) pointers[k][i] = &values[k][i];
      fb.insert(good.channels[k].name, Imf::DeepSlice(Imf::FLOAT, reinterpret_cast<char*>(pointers[k].data()),
                                                      sizeof(float*), sizeof(float*) * kW, sizeof(float)));
    }
    file.setFrameBuffer(fb);
    file.writePixels(kH);
  }
  expectFailure(trace(), 2, shot, {"deep data", "not supported"});
}

TEST_F(Hostile, SubsampledChannelIsRefusedByName) {
  Imf::Header header(kW, kH);
  Imf::FrameBuffer fb;
  std::vector<float> half(size_t(kW / 2) * (kH / 2), 0.1f);
  for (const ExrChannel& c : good.channels) {
    const bool sub = c.name == "ViewLayer.roughness.X";
    header.channels().insert(c.name, Imf::Channel(Imf::FLOAT, sub ? 2 : 1, sub ? 2 : 1));
    float* data = const_cast<float*>(sub ? half.data() : c.values.data());
    fb.insert(c.name,
              sub ? Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data), sizeof(float), sizeof(float) * (kW / 2), 2, 2)
                  : Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data), sizeof(float), sizeof(float) * kW));
  }
  {
    Imf::OutputFile file(shot.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(kH);
  }
  expectFailure(trace(), 2, shot, {"'ViewLayer.roughness.X'", "subsampled"});
}

TEST_F(Hostile, PassFilesOfDisagreeingSizes) {
  const std::string depth = dir.file("depth.exr");
  writeExr(depth, kW + 2, kH, {{"Z", std::vector<float>(size_t(kW + 2) * kH, 5.0f)}});
  expectFailure(trace("--depth " + shellQuote(depth) + " --depth-channel Z"), 2, depth,
                {"42x30", "40x30", shot, "same size"});
}

// ------------------------------------------------------------------------------------------------
// Hostile camera JSON (the library's messages are checked in test_camera.cpp; here: end to end)

TEST_F(Hostile, CameraJsonThatCannotBeUsed) {
  const json valid = json::parse(readBytes(camera));
  const auto with = [&](const char* field, json value) {
    json j = valid;
    j[field] = std::move(value);
    return j.dump();
  };
  const auto without = [&](const char* field) {
    json j = valid;
    j.erase(field);
    return j.dump();
  };
  json textInNumber = valid;
  textInNumber["projection"][0][0] = "1.2";
  json oblique = valid;  // near and far must come from the file: an oblique matrix has none
  oblique.erase("near");
  oblique.erase("far");
  oblique["projection"] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0.2, 0, -1, -0.2}, {0, 0, -1, 0}};
  json nullInNumber = valid;
  nullInNumber["view"][2][1] = nullptr;
  struct Case {
    const char* why;
    std::string text;
    std::vector<std::string> needles;
  };
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  const Case cases[] = {
      {"missing view", without("view"), {"missing field 'view'"}},
      {"missing width", without("width"), {"missing field 'width'"}},
      {"projection 3x4", with("projection", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}}), {"'projection'", "4 rows"}},
      {"projection flat", with("projection", json::array({1, 0, 0, 0})), {"'projection'"}},
      {"text in a number", textInNumber.dump(), {"'projection'"}},
      {"null in a number", nullInNumber.dump(), {"'view'"}},
      {"width as text", with("width", "40"), {"'width'"}},
      {"width 2^31 - 1", with("width", 2147483647), {"2147483647x30", "2^30"}},
      {"height too large", with("height", 4e9), {"'height'"}},
      {"overflowing number",
       valid.dump().replace(valid.dump().find("\"height\""), 0, "\"x\":1e999,"),
       {"invalid JSON", "1e999"}},
      {"NaN literal", valid.dump().replace(valid.dump().find('}'), 0, ",\"near\":NaN"), {"invalid JSON"}},
      {"singular projection",
       with("projection", {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 0, 0}, {0, 0, -1, 0}}),
       {"projection"}},
      {"oblique projection without planes", oblique.dump(), {"'projection'", "oblique", "'near' and 'far'"}},
      {"near beyond far", with("near", 2000.0), {"near"}},
      {"deeply nested", deep, {}},
      {"binary garbage", std::string("\x00\xff\xfe{\"view\"", 10), {"invalid JSON"}},
      {"size other than the G-buffer's", with("width", 41), {"41x30", "40x30"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.why);
    writeBytes(camera, c.text);
    expectFailure(trace(), 2, camera, c.needles);
  }
}

// ------------------------------------------------------------------------------------------------
// Device problems

TEST_F(Hostile, NoOpenClPlatform) {
  // The ICD loader reads the vendor list from OCL_ICD_VENDORS: an empty directory, or one naming
  // a driver library that does not exist, leaves no platform.
  fs::create_directories(dir.file("vendors-empty"));
  fs::create_directories(dir.file("vendors-broken"));
  writeBytes(dir.file("vendors-broken/broken.icd"), "libssrcl-no-such-driver.so\n");
  for (const char* vendors : {"vendors-empty", "vendors-broken"}) {
    SCOPED_TRACE(vendors);
    const std::string env = "OCL_ICD_VENDORS=" + shellQuote(dir.file(vendors)) + " ";
    const CommandResult devices = runCommand(env + cli("devices"));
    EXPECT_EQ(devices.exitCode, 3) << devices.output;
    EXPECT_NE(devices.output.find("no OpenCL device found"), std::string::npos) << devices.output;
    expectFailure(trace(), 3, "", {"no OpenCL device found", "pocl-opencl-icd"}, env);
  }
}

// A farm node whose HOME cannot be written: PoCL cannot create its cache and lists no device.
// The error must say so and name the remedy, not send the user to install a driver. (/proc
// refuses new directories even to root.)
TEST_F(Hostile, UnwritablePoclCacheIsReportedWithTheRemedy) {
  const std::string env = "env -u POCL_CACHE_DIR -u XDG_CACHE_HOME HOME=/proc/ssrcl-no-home ";
  const CommandResult probe = runCommand(env + cli("devices"));
  if (probe.exitCode == 0) GTEST_SKIP() << "this OpenCL driver lists devices without a writable cache";
  EXPECT_EQ(probe.exitCode, 3) << probe.output;
  for (const char* needle : {"/proc/ssrcl-no-home/.cache/pocl", "not writable", "POCL_CACHE_DIR"})
    EXPECT_NE(probe.output.find(needle), std::string::npos) << needle << " in: " << probe.output;
  expectFailure(trace(), 3, "", {"PoCL cannot create its kernel cache", "POCL_CACHE_DIR"}, env);
  // The remedy works.
  const CommandResult fixed =
      runCommand(env + "POCL_CACHE_DIR=" + shellQuote(dir.file("pocl-cache")) + " " + cli("devices"));
  EXPECT_EQ(fixed.exitCode, 0) << fixed.output;
}

TEST_F(Hostile, KernelBuildFailureShowsTheBuildLog) {
  expectFailure(trace(), 3, "",
                {"OpenCL kernels failed to build", "-Dsanitize_radiance=)", "--- OpenCL build log ---",
                 "expected identifier"},
                "SSRCL_KERNEL_BUILD_OPTIONS='-Dsanitize_radiance=)' ");
}

TEST(DeviceErrors, KernelBuildFailureIsTypedAndCarriesTheLog) {
  // A function of common.cl, which every program includes, turned into a stray ')': none builds.
  const ssrcl::test::ScopedEnv env("SSRCL_KERNEL_BUILD_OPTIONS", "-Dsanitize_radiance=)");
  Device device = testDevice();  // a new device builds its own program
  const Shot shot = makeShot();
  Image color(kW, kH, 3), depth(kW, kH, 1), normal(kW, kH, 3);
  Pipeline p(device);
  p.setImage("color", color);
  p.setImage("depth", depth);
  p.setImage("normal", normal);
  p.setCamera(shot.camera);
  p.settings().constantRoughness = 0.0f;
  try {
    p.commit();
    FAIL() << "no error thrown";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::KernelBuild) << e.what();
    EXPECT_NE(std::string(e.what()).find(device.info().name), std::string::npos) << e.what();
    EXPECT_NE(e.buildLog().find("expected identifier"), std::string::npos) << e.buildLog();
  }
}

TEST(DeviceErrors, BufferBeyondTheDeviceLimitIsOutOfMemory) {
  Device device = testDevice();
  const auto maxAlloc = detail::DeviceAccess::impl(device).device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  // The driver refuses the size itself (CL_INVALID_BUFFER_SIZE): nothing is allocated.
  try {
    try {
      cl::Buffer huge(detail::DeviceAccess::impl(device).context, CL_MEM_READ_WRITE, size_t(maxAlloc) + 4096);
      FAIL() << "the driver accepted a buffer beyond CL_DEVICE_MAX_MEM_ALLOC_SIZE";
    } catch (const cl::Error& e) {
      detail::rethrowClError(e, "allocating device buffers for 99999x99999");
    }
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), ErrorCode::OutOfMemory) << e.what();
    EXPECT_NE(std::string(e.what()).find("99999x99999"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("CL_INVALID_BUFFER_SIZE"), std::string::npos) << e.what();
  }
}

TEST(DeviceErrors, DeviceMemoryCheckNamesTheSizes) {
  Device device = testDevice();
  const auto& impl = detail::DeviceAccess::impl(device);
  const unsigned long long maxAlloc = impl.device.getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
  unsigned long long global = impl.device.getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
  if (!device.info().isGpu)  // a CPU device may use the machine's memory (see checkDeviceMemory)
    global = std::max(global, static_cast<unsigned long long>(sysconf(_SC_PHYS_PAGES)) * sysconf(_SC_PAGE_SIZE));
  EXPECT_NO_THROW(detail::checkDeviceMemory(impl, maxAlloc, global, "a fitting frame"));
  const auto expectOom = [&](unsigned long long largest, unsigned long long total, const std::string& needle) {
    try {
      detail::checkDeviceMemory(impl, largest, total, "a 65536x65536 frame");
      ADD_FAILURE() << "no error thrown";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), ErrorCode::OutOfMemory);
      const std::string m = e.what();
      EXPECT_NE(m.find("a 65536x65536 frame"), std::string::npos) << m;
      EXPECT_NE(m.find(device.info().name), std::string::npos) << m;
      EXPECT_NE(m.find(needle), std::string::npos) << m;
    }
  };
  expectOom(maxAlloc + 1, maxAlloc + 1, "per buffer");
  expectOom(maxAlloc, global + 1, "of device memory");
}

}  // namespace
