// libFuzzer target: the EXR G-buffer loader (loadGBuffer) on arbitrary bytes.
// Property: it returns a G-buffer whose images have the shapes it promises, or throws
// ssrcl::Error; any other exception, crash, leak of control (abort) or sanitizer report is a bug.
//
// The loader allocates what a header declares (bounded by 2^30 pixels and the machine's memory,
// by design: a tiny ZIP file can hold a huge constant image), so inputs declaring more than
// kMaxPixels are skipped here to keep the fuzzer's own memory limit (-rss_limit_mb) from
// reporting that designed behaviour; tests/test_hostile_input.cpp covers huge declared sizes.
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "fuzz_input_file.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

namespace {

constexpr long long kMaxPixels = 1 << 20;

// The largest data window among the header's "dataWindow" box2i attributes (found by their bytes,
// so that OpenEXR's own parsing is left to the loader under test).
bool declaresHugeImage(const uint8_t* data, size_t size) {
  static const char key[] = "dataWindow\0box2i\0";
  const std::string bytes(reinterpret_cast<const char*>(data), size), k(key, sizeof key - 1);
  for (size_t at = bytes.find(k); at != std::string::npos; at = bytes.find(k, at + 1)) {
    if (at + k.size() + 20 > size) break;
    int32_t v[4];
    std::memcpy(v, data + at + k.size() + 4, sizeof v);
    const double pixels = (double(v[2]) - v[0] + 1) * (double(v[3]) - v[1] + 1);
    if (pixels > double(kMaxPixels)) return true;
  }
  return false;
}

void checkShape(const ssrcl::Image& image, int channels, int width, int height) {
  if (image.channels != channels || image.width != width || image.height != height ||
      image.data.size() != size_t(width) * height * channels)
    std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const std::string path = ssrcl::fuzz::inputPath("gbuffer.exr");
  if (declaresHugeImage(data, size)) return 0;
  ssrcl::fuzz::writeInput(path, data, size);
  // Blender multilayer names with a roughness channel, and plain names with a constant roughness.
  for (int naming = 0; naming < 2; ++naming) {
    ssrcl::GBufferSource source;
    source.file = path;
    if (naming == 1) {
      source.layer = "";
      source.readRoughness = false;
    }
    try {
      const ssrcl::GBuffer g = ssrcl::loadGBuffer(source);
      const int w = g.depth.width, h = g.depth.height;
      checkShape(g.color, 3, w, h);
      checkShape(g.depth, 1, w, h);
      checkShape(g.normal, 3, w, h);
      if (naming == 0) checkShape(g.roughness, 1, w, h);
      if (w <= 0 || h <= 0) std::abort();
    } catch (const ssrcl::Error& e) {
      if (std::string(e.what()).rfind(path, 0) != 0 && e.code() != ssrcl::ErrorCode::InvalidArgument)
        std::abort();  // every file error names the file first
    }
  }
  return 0;
}
