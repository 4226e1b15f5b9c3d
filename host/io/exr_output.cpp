#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStdIO.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include "exr_header_camera.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/exr_output.hpp"

namespace ssrcl {
namespace {

namespace fs = std::filesystem;

bool wellFormed(const Image& image, int channels) {
  return image.channels == channels && image.width > 0 && image.height > 0 &&
         image.data.size() == std::size_t(image.width) * image.height * channels;
}

Imath::Box2i box(const PixelBox& b) { return Imath::Box2i({b.minX, b.minY}, {b.maxX, b.maxY}); }

std::size_t pixelSize(Imf::PixelType type) { return type == Imf::HALF ? 2 : 4; }

// The header, pixels and storage of one output file.
struct OutputImage {
  Imf::Header header;
  Imf::FrameBuffer buffer;
  std::vector<std::vector<char>> storage;  // copied input channels, half pass channels
};

// Every channel of a single-part file at its stored type and sampling, and every attribute but
// the ones that describe the stored layout (the output is written as scan lines).
void copyInput(const std::string& file, const PixelBox& dataWindow, OutputImage& out) {
  if (Imf::MultiPartInputFile(file.c_str()).parts() != 1)
    throw Error(ErrorCode::InvalidInput, file + ": --append needs a single-part EXR; this one has several parts");
  Imf::InputFile in(file.c_str());
  const Imf::Header& source = in.header();
  if (source.hasType() && Imf::isDeepData(source.type()))
    throw Error(ErrorCode::InvalidInput, file + ": --append cannot copy deep data");
  if (source.dataWindow() != box(dataWindow))
    throw Error(ErrorCode::InvalidInput, file + ": its data window is not the traced G-buffer's; cannot append to it");
  for (auto a = source.begin(); a != source.end(); ++a) {
    const std::string name = a.name();
    if (name != "channels" && name != "tiles" && name != "type" && name != "chunkCount" && name != "lineOrder")
      out.header.insert(name, a.attribute());
  }
  const Imath::Box2i& w = source.dataWindow();
  const long width = long(w.max.x) - w.min.x + 1, height = long(w.max.y) - w.min.y + 1;
  Imf::FrameBuffer inBuffer;
  for (auto c = source.channels().begin(); c != source.channels().end(); ++c) {
    const Imf::Channel& ch = c.channel();
    const std::size_t size = pixelSize(ch.type);
    std::vector<char>& data =
        out.storage.emplace_back(size * std::size_t(width / ch.xSampling) * std::size_t(height / ch.ySampling));
    const Imf::Slice slice = Imf::Slice::Make(ch.type, data.data(), w, size, 0, ch.xSampling, ch.ySampling);
    inBuffer.insert(c.name(), slice);
    out.buffer.insert(c.name(), slice);
    out.header.channels().insert(c.name(), ch);
  }
  in.setFrameBuffer(inBuffer);
  in.readPixels(w.min.y, w.max.y);
}

// What the pass keeps of the G-buffer's header, so compositing reads both alike.
void carryHeader(const std::string& file, Imf::Header& header) {
  const Imf::Header source = Imf::MultiPartInputFile(file.c_str()).header(0);
  header.pixelAspectRatio() = source.pixelAspectRatio();
  header.screenWindowCenter() = source.screenWindowCenter();
  header.screenWindowWidth() = source.screenWindowWidth();
  if (Imf::hasChromaticities(source)) Imf::addChromaticities(header, Imf::chromaticities(source));
}

// Adds channel `name` from every `stride`-th float of `values`, converted to half when asked.
void addPassChannel(OutputImage& out, const std::string& name, const float* values, std::size_t stride,
                    std::size_t count, bool half) {
  if (out.header.channels().findChannel(name))
    throw Error(ErrorCode::InvalidInput, "the file already has a channel '" + name + "': give another --output-layer");
  const Imf::PixelType type = half ? Imf::HALF : Imf::FLOAT;
  out.header.channels().insert(name, Imf::Channel(type));
  const Imath::Box2i& w = out.header.dataWindow();
  const std::size_t rowPixels = std::size_t(w.max.x - w.min.x + 1);
  if (!half) {
    out.buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, values, w, sizeof(float) * stride,
                                             sizeof(float) * stride * rowPixels));
    return;
  }
  std::vector<char>& data = out.storage.emplace_back(count * sizeof(::half));
  ::half* h = reinterpret_cast<::half*>(data.data());
  for (std::size_t i = 0; i < count; ++i) h[i] = ::half(values[i * stride]);
  out.buffer.insert(name, Imf::Slice::Make(Imf::HALF, h, w, sizeof(::half), sizeof(::half) * rowPixels));
}

Imf::Compression compressionNamed(const std::string& name) {
  const std::vector<std::string>& names = exrCompressionNames();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw Error(ErrorCode::InvalidArgument, "unknown EXR compression '" + name + "'");
  return Imf::Compression(it - names.begin());  // names are in the enum's order
}

void buildOutput(const Image& rgba, const Image& distance, const ReflectionExrOptions& options,
                 const ExrWindows& windows, OutputImage& out) {
  out.header = Imf::Header(box(windows.display), box(windows.data));
  const std::string& source = options.appendTo.empty() ? options.headerFrom : options.appendTo;
  try {
    if (!options.appendTo.empty()) {
      copyInput(options.appendTo, windows.data, out);
    } else {
      out.header.compression() = compressionNamed(defaultExrCompression());
      if (!options.headerFrom.empty()) carryHeader(options.headerFrom, out.header);
    }
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    throw Error(ErrorCode::InvalidInput, source + ": cannot read its header and channels (" + e.what() + ")");
  }
  if (!options.compression.empty()) out.header.compression() = compressionNamed(options.compression);
  if (options.camera) detail::cameraToHeader(*options.camera, out.header);
  for (const auto& [name, value] : options.attributes) out.header.insert(name, Imf::StringAttribute(value));

  const std::string prefix = options.layer.empty() ? "" : options.layer + ".";
  const std::size_t count = rgba.data.size() / 4;
  const char* names[] = {"R", "G", "B", "A"};
  try {
    for (int c = 0; c < 4; ++c) addPassChannel(out, prefix + names[c], &rgba.data[c], 4, count, options.half);
    addPassChannel(out, prefix + "distance", distance.data.data(), 1, count, options.half);
    if (options.view) {
      addPassChannel(out, prefix + "view", &options.view->data[0], 2, count, options.half);
      addPassChannel(out, prefix + "view_share", &options.view->data[1], 2, count, options.half);
    }
  } catch (const Error& e) {
    throw Error(e.code(), (options.appendTo.empty() ? "" : options.appendTo + ": ") + e.what());
  }
}

void writeExr(const std::string& path, const OutputImage& image, int rows) {
  // Our own stream, because OutputFile's destructor writes the offset table and swallows
  // errors there (e.g. disk full); the stream state still records them.
  std::ofstream stream(path, std::ios::binary);
  if (!stream) throw std::runtime_error(std::string("cannot create a temporary file: ") + std::strerror(errno));
  {
    Imf::StdOFStream exrStream(stream, path.c_str());
    Imf::OutputFile file(exrStream, image.header);
    file.setFrameBuffer(image.buffer);
    file.writePixels(rows);
  }
  stream.close();
  if (!stream) throw std::runtime_error("writing the temporary file failed");
}

}  // namespace

const std::vector<std::string>& exrCompressionNames() {
  static const std::vector<std::string> names = {"none", "rle", "zips", "zip", "piz",
                                                 "pxr24", "b44", "b44a", "dwaa", "dwab"};
  return names;
}

const std::string& defaultExrCompression() {
  static const std::string name = "rle";
  return name;
}

void writeReflectionExr(const std::string& path, const Image& rgba, const Image& distance,
                        const ReflectionExrOptions& options) {
  if (!wellFormed(rgba, 4) || !wellFormed(distance, 1) || rgba.width != distance.width ||
      rgba.height != distance.height) {
    throw Error(ErrorCode::InvalidArgument,
                path +
                    ": reflection output needs a 4-channel colour and a 1-channel distance image of the same "
                    "non-zero size (got " +
                    std::to_string(rgba.width) + "x" + std::to_string(rgba.height) + "x" +
                    std::to_string(rgba.channels) + " and " + std::to_string(distance.width) + "x" +
                    std::to_string(distance.height) + "x" + std::to_string(distance.channels) + ")");
  }
  if (options.view && (!wellFormed(*options.view, 2) || options.view->width != rgba.width ||
                       options.view->height != rgba.height))
    throw Error(ErrorCode::InvalidArgument, path + ": the view image must have 2 channels and the pass's size");
  const PixelBox whole{0, 0, rgba.width - 1, rgba.height - 1};
  const ExrWindows written = options.windows.value_or(ExrWindows{whole, whole});
  if (written.data.width() != rgba.width || written.data.height() != rgba.height || written.display.width() <= 0 ||
      written.display.height() <= 0)
    throw Error(ErrorCode::InvalidArgument, path + ": the data window is " + std::to_string(written.data.width()) +
                                                "x" + std::to_string(written.data.height()) + " but the images are " +
                                                std::to_string(rgba.width) + "x" + std::to_string(rgba.height));
  const fs::path target(path);
  const fs::path directory = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(directory, ec))
    throw Error(ErrorCode::IoError,
                path + ": cannot write ('" + directory.string() + "' is not an existing directory)");

  OutputImage image;
  buildOutput(rgba, distance, options, written, image);
  // A hidden sibling, so the rename stays on one file system and is atomic.
  const fs::path temp =
      directory / ("." + target.filename().string() + ".tmp." + std::to_string(std::random_device{}()) + ".exr");
  try {
    writeExr(temp.string(), image, rgba.height);
    fs::rename(temp, target, ec);
    if (ec) throw std::runtime_error("cannot replace it: " + ec.message());
  } catch (const std::exception& e) {
    fs::remove(temp, ec);
    throw Error(ErrorCode::IoError, path + ": cannot write (" + e.what() + ")");
  }
}

void writeReflectionExr(const std::string& path, const Image& rgba, const Image& distance,
                        const std::optional<ExrWindows>& windows) {
  ReflectionExrOptions options;
  options.windows = windows;
  writeReflectionExr(path, rgba, distance, options);
}

}  // namespace ssrcl
