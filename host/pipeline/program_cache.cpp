#include "program_cache.hpp"

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <vector>

namespace ssrcl::detail {
namespace {

namespace fs = std::filesystem;

const std::string kMagic = "ssrcl program binary 2\n";

std::uint64_t fnv1a(const unsigned char* bytes, std::size_t size) {
  std::uint64_t h = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
  return h;
}

fs::path cacheDirectory() {
  if (const char* d = std::getenv("SSRCL_CACHE_DIR")) return d;  // "": off
  if (const char* x = std::getenv("XDG_CACHE_HOME"); x && *x) return fs::path(x) / "ssrcl";
  if (const char* h = std::getenv("HOME"); h && *h) return fs::path(h) / ".cache" / "ssrcl";
  return {};
}

// Everything the binary depends on: a new driver, device, option or source is another entry.
std::string keyOf(const cl::Device& device, const std::string& source, const std::string& options) {
  const cl::Platform platform(device.getInfo<CL_DEVICE_PLATFORM>());
  return platform.getInfo<CL_PLATFORM_NAME>() + "\n" + platform.getInfo<CL_PLATFORM_VERSION>() + "\n" +
         device.getInfo<CL_DEVICE_NAME>() + "\n" + device.getInfo<CL_DEVICE_VERSION>() + "\n" +
         device.getInfo<CL_DRIVER_VERSION>() + "\n" + options + "\n" + source;
}

// The file of `key`: named by its FNV-1a hash, holding the key itself to rule out collisions.
fs::path fileOf(const fs::path& dir, const std::string& key) {
  char name[32];
  std::snprintf(name, sizeof name, "%016llx.bin",
                static_cast<unsigned long long>(fnv1a(reinterpret_cast<const unsigned char*>(key.data()), key.size())));
  return dir / name;
}

}  // namespace

cl::Program cachedProgram(const cl::Context& context, const cl::Device& device, const std::string& source,
                          const std::string& options) {
  const fs::path dir = cacheDirectory();
  if (dir.empty()) return {};
  try {
    const std::string key = keyOf(device, source, options);
    std::ifstream in(fileOf(dir, key), std::ios::binary);
    if (!in) return {};
    const std::string stored((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string header = kMagic + std::to_string(key.size()) + "\n" + key;
    if (stored.size() <= header.size() + 8 || stored.compare(0, header.size(), header) != 0) return {};
    const cl::Program::Binaries binaries{std::vector<unsigned char>(stored.begin() + header.size() + 8, stored.end())};
    // Checked before the driver sees it: PoCL crashes on a damaged binary rather than refuse it.
    std::uint64_t sum;
    std::memcpy(&sum, stored.data() + header.size(), 8);
    if (sum != fnv1a(binaries[0].data(), binaries[0].size())) return {};
    cl::Program program(context, {device}, binaries);
    program.build({device}, options.c_str());
    return program;
  } catch (const cl::Error&) {
    return {};  // rejected by the driver: built from source, and stored again
  }
}

void storeProgram(const cl::Program& program, const cl::Device& device, const std::string& source,
                  const std::string& options) {
  const fs::path dir = cacheDirectory();
  if (dir.empty()) return;
  try {
    const std::vector<std::vector<unsigned char>> binaries = program.getInfo<CL_PROGRAM_BINARIES>();
    if (binaries.size() != 1 || binaries[0].empty()) return;
    const std::string key = keyOf(device, source, options);
    std::error_code ec;
    fs::create_directories(dir, ec);
    // A sibling renamed over the entry: a process reading it never sees half a file.
    const fs::path target = fileOf(dir, key);
    const fs::path temp = target.string() + ".tmp." + std::to_string(getpid()) + "." +
                          std::to_string(std::random_device{}());
    {
      std::ofstream out(temp, std::ios::binary);
      const std::uint64_t sum = fnv1a(binaries[0].data(), binaries[0].size());
      out << kMagic << key.size() << "\n" << key;
      out.write(reinterpret_cast<const char*>(&sum), 8);
      out.write(reinterpret_cast<const char*>(binaries[0].data()), std::streamsize(binaries[0].size()));
      out.close();
      if (!out) {
        fs::remove(temp, ec);
        return;
      }
    }
    fs::rename(temp, target, ec);
    if (ec) fs::remove(temp, ec);
  } catch (const cl::Error&) {
  }
}

}  // namespace ssrcl::detail
