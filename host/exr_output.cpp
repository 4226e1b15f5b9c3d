#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>

#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl {
namespace {

namespace fs = std::filesystem;

bool wellFormed(const Image& image, int channels) {
  return image.channels == channels && image.width > 0 && image.height > 0 &&
         image.data.size() == std::size_t(image.width) * image.height * channels;
}

void writeExr(const std::string& path, const Image& rgba, const Image& distance, const ExrWindows& windows) {
  const auto box = [](const PixelBox& b) { return Imath::Box2i({b.minX, b.minY}, {b.maxX, b.maxY}); };
  Imf::Header header(box(windows.display), box(windows.data));
  header.compression() = Imf::ZIP_COMPRESSION;
  Imf::FrameBuffer buffer;
  const char* names[] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    header.channels().insert(names[c], Imf::Channel(Imf::FLOAT));
    buffer.insert(names[c], Imf::Slice::Make(Imf::FLOAT, &rgba.data[c], header.dataWindow(), sizeof(float) * 4,
                                             sizeof(float) * 4 * rgba.width));
  }
  header.channels().insert("distance", Imf::Channel(Imf::FLOAT));
  buffer.insert("distance", Imf::Slice::Make(Imf::FLOAT, distance.data.data(), header.dataWindow(), sizeof(float),
                                             sizeof(float) * distance.width));

  // Our own stream, because OutputFile's destructor writes the offset table and swallows
  // errors there (e.g. disk full); the stream state still records them.
  std::ofstream stream(path, std::ios::binary);
  if (!stream) throw std::runtime_error(std::string("cannot create a temporary file: ") + std::strerror(errno));
  {
    Imf::StdOFStream exrStream(stream, path.c_str());
    Imf::OutputFile file(exrStream, header);
    file.setFrameBuffer(buffer);
    file.writePixels(rgba.height);
  }
  stream.close();
  if (!stream) throw std::runtime_error("writing the temporary file failed");
}

}  // namespace

void writeReflectionExr(const std::string& path, const Image& rgba, const Image& distance,
                        const std::optional<ExrWindows>& windows) {
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
  const PixelBox whole{0, 0, rgba.width - 1, rgba.height - 1};
  ExrWindows written = windows.value_or(ExrWindows{whole, whole});
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

  // A hidden sibling, so the rename stays on one file system and is atomic.
  const fs::path temp =
      directory / ("." + target.filename().string() + ".tmp." + std::to_string(std::random_device{}()) + ".exr");
  try {
    writeExr(temp.string(), rgba, distance, written);
    fs::rename(temp, target, ec);
    if (ec) throw std::runtime_error("cannot replace it: " + ec.message());
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    fs::remove(temp, ec);
    throw Error(ErrorCode::IoError, path + ": cannot write (" + e.what() + ")");
  }
}

}  // namespace ssrcl
