// Deep OpenEXR depth samples. A deep pixel lists every surface or volume segment the renderer's
// ray met, each with its front Z and back ZBack (Arnold, RenderMan, Karma): the first one's
// interval is how deep the visible surface goes.
#include "exr_deep_depth.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDeepFrameBuffer.h>
#include <OpenEXR/ImfDeepScanLineInputPart.h>
#include <OpenEXR/ImfDeepTiledInputPart.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfPartType.h>

#include <climits>
#include <cmath>
#include <new>

#include "exr_header_check.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::detail {
namespace {

// Opens `path` (checking its header first), turning OpenEXR's exceptions into Error naming it.
template <class F>
auto openedAs(const std::string& path, F&& use) {
  try {
    checkHeaderSizes(path);
    Imf::MultiPartInputFile file(path.c_str());
    return use(file);
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::OutOfMemory, path + ": out of memory");
  } catch (const std::exception& e) {
    throw Error(ErrorCode::IoError, path + ": cannot read deep samples (" + e.what() + ")");
  }
}

bool deep(const Imf::Header& header) { return header.hasType() && Imf::isDeepData(header.type()); }

// A slice of per-pixel values (counts, or sample pointers) over the data window: OpenEXR
// addresses it from pixel (0, 0), so the base is offset back to there.
template <class T>
char* windowBase(std::vector<T>& values, const Imath::Box2i& window, int width) {
  const long long offset = static_cast<long long>(window.min.y) * width + window.min.x;
  return reinterpret_cast<char*>(values.data()) - offset * static_cast<long long>(sizeof(T));
}

}  // namespace

bool isDeepExr(const std::string& path) {
  return openedAs(path, [](Imf::MultiPartInputFile& file) { return deep(file.header(0)); });
}

DeepDepth readDeepDepth(const std::string& path) {
  return openedAs(path, [&](Imf::MultiPartInputFile& file) {
    const Imf::Header& header = file.header(0);
    if (!deep(header)) throw Error(ErrorCode::InvalidInput, path + ": not a deep OpenEXR file");
    if (!header.channels().findChannel("Z"))
      throw Error(ErrorCode::InvalidInput, path + ": deep file without a Z channel, so no sample depths");
    const bool hasBack = header.channels().findChannel("ZBack") != nullptr;
    const Imath::Box2i window = header.dataWindow();
    const long long w = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long h = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (w <= 0 || h <= 0 || w * h > (1LL << 30))
      throw Error(ErrorCode::InvalidInput, path + ": deep data window is empty or beyond 2^30 pixels");
    DeepDepth d;
    d.width = int(w);
    d.height = int(h);
    const size_t pixels = size_t(w * h);
    d.counts.assign(pixels, 0);
    std::vector<float*> zAt(pixels), zBackAt(pixels);
    Imf::DeepFrameBuffer buffer;
    buffer.insertSampleCountSlice(Imf::Slice(Imf::UINT, windowBase(d.counts, window, d.width), sizeof(uint32_t),
                                             sizeof(uint32_t) * d.width));
    buffer.insert("Z", Imf::DeepSlice(Imf::FLOAT, windowBase(zAt, window, d.width), sizeof(float*),
                                      sizeof(float*) * d.width, sizeof(float)));
    if (hasBack)
      buffer.insert("ZBack", Imf::DeepSlice(Imf::FLOAT, windowBase(zBackAt, window, d.width), sizeof(float*),
                                            sizeof(float*) * d.width, sizeof(float)));
    // Counts first, then storage for every sample, then the samples.
    const auto place = [&] {
      d.first.resize(pixels + 1);
      d.first[0] = 0;
      for (size_t i = 0; i < pixels; ++i) d.first[i + 1] = d.first[i] + d.counts[i];
      d.z.resize(d.first[pixels]);
      d.zBack.resize(d.first[pixels]);
      for (size_t i = 0; i < pixels; ++i) {
        zAt[i] = d.z.data() + d.first[i];
        zBackAt[i] = d.zBack.data() + d.first[i];
      }
    };
    if (header.type() == Imf::DEEPTILE) {
      Imf::DeepTiledInputPart part(file, 0);
      part.setFrameBuffer(buffer);
      const int tx = part.numXTiles(0), ty = part.numYTiles(0);
      part.readPixelSampleCounts(0, tx - 1, 0, ty - 1);
      place();
      part.readTiles(0, tx - 1, 0, ty - 1);
    } else {
      Imf::DeepScanLineInputPart part(file, 0);
      part.setFrameBuffer(buffer);
      part.readPixelSampleCounts(window.min.y, window.max.y);
      place();
      part.readPixels(window.min.y, window.max.y);
    }
    if (!hasBack) d.zBack = d.z;
    return d;
  });
}

Image firstIntervalBack(const DeepDepth& deep) {
  Image back(deep.width, deep.height, 1);
  for (size_t i = 0; i < deep.counts.size(); ++i) {
    // Writers need not sort samples (OpenEXR's "tidy" images are): the nearest front is the first.
    float front = INFINITY, end = 0.0f;
    for (uint64_t k = deep.first[i]; k < deep.first[i + 1]; ++k)
      if (deep.z[k] < front) front = deep.z[k], end = deep.zBack[k];
    back.data[i] = end > front ? end : 0.0f;
  }
  return back;
}

}  // namespace ssrcl::detail
