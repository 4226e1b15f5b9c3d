// Program binaries kept between processes: a new device loads them instead of building from
// source, traces the same pass, and anything wrong with an entry is a rebuild, not an error.

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "ssrcl/pipeline.hpp"
#include "support/analytic_frame.hpp"
#include "support/temp_dir.hpp"
#include "support/test_device.hpp"

namespace ssrcl {
namespace {

namespace fs = std::filesystem;

struct ScopedCacheDir {
  explicit ScopedCacheDir(const std::string& dir) { setenv("SSRCL_CACHE_DIR", dir.c_str(), 1); }
  ~ScopedCacheDir() { unsetenv("SSRCL_CACHE_DIR"); }
};

// A glossy frame traced on a new device (no programs in memory), its pass's values.
std::vector<float> traceOnNewDevice() {
  test::AnalyticFrame f = test::renderAnalyticFrame("spheres_on_mirror", 48, 32);
  for (float& r : f.g.roughness.data) r = 0.3f;  // glossy: every stage's program is built
  Device device = test::testDevice();
  Pipeline p(device);
  TraceSettings s;
  s.samplesPerPixel = 2;
  test::runFrame(p, f, s);
  std::vector<float> values = p.output("reflection").data;
  const std::vector<float>& d = p.output("distance").data;
  values.insert(values.end(), d.begin(), d.end());
  return values;
}

// Each entry's file, with what identifies that very file (rewritten: a new inode).
std::map<std::string, fs::file_time_type> entries(const fs::path& dir) {
  std::map<std::string, fs::file_time_type> found;
  for (const auto& e : fs::directory_iterator(dir)) found[e.path().filename().string()] = e.last_write_time();
  return found;
}

TEST(ProgramCache, ASecondDeviceLoadsTheBinariesAndTracesTheSamePass) {
  test::TempDir dir;
  const ScopedCacheDir cache(dir.file("programs"));
  const std::vector<float> built = traceOnNewDevice();
  const auto stored = entries(dir.file("programs"));
  EXPECT_GE(stored.size(), 5u);  // setup, thickness, hzb, trace, resolve, filter...
  for (const auto& [name, time] : stored) EXPECT_EQ(fs::path(name).extension(), ".bin") << name;  // no temporaries

  const std::vector<float> loaded = traceOnNewDevice();
  EXPECT_EQ(loaded, built);
  EXPECT_EQ(entries(dir.file("programs")), stored);  // every program was a hit: none stored again
}

TEST(ProgramCache, ADamagedEntryIsRebuilt) {
  test::TempDir dir;
  const ScopedCacheDir cache(dir.file("programs"));
  const std::vector<float> built = traceOnNewDevice();
  for (const auto& e : fs::directory_iterator(dir.file("programs"))) {
    // The key intact, the binary cut short and its end overwritten (PoCL crashes on such a binary).
    const auto size = fs::file_size(e.path());
    fs::resize_file(e.path(), size - size / 3);
    std::fstream f(e.path(), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(-64, std::ios::end);
    f << std::string(64, '\x5a');
  }
  EXPECT_EQ(traceOnNewDevice(), built);
  EXPECT_EQ(traceOnNewDevice(), built);  // from the entries stored again
}

TEST(ProgramCache, AnEmptyDirectoryNameTurnsItOff) {
  test::sharedTestDevice();  // PoCL settles its own cache under the real HOME, not the one below
  test::TempDir dir;
  const ScopedCacheDir cache("");
  const std::string home = std::getenv("HOME") ? std::getenv("HOME") : "";
  setenv("HOME", dir.path().c_str(), 1);
  unsetenv("XDG_CACHE_HOME");
  traceOnNewDevice();
  setenv("HOME", home.c_str(), 1);
  EXPECT_FALSE(fs::exists(dir.path() / ".cache" / "ssrcl"));
}

}  // namespace
}  // namespace ssrcl
