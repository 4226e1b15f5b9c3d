#include "support/exr_fixtures.hpp"

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfMultiPartOutputFile.h>
#include <OpenEXR/ImfOutputPart.h>
#include <OpenEXR/ImfPartType.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfTiledOutputPart.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace ssrcl::test {
namespace {

std::size_t bytesPerValue(Imf::PixelType type) { return type == Imf::HALF ? 2 : 4; }

// The channel's values in its stored representation.
std::vector<char> encode(const ExrChannel& channel) {
  const std::size_t size = bytesPerValue(channel.type);
  std::vector<char> bytes(channel.values.size() * size);
  for (std::size_t i = 0; i < channel.values.size(); ++i) {
    const float v = channel.values[i];
    const half h(v);
    const std::uint32_t u = std::uint32_t(v);
    std::memcpy(&bytes[i * size],
                channel.type == Imf::HALF   ? static_cast<const void*>(&h)
                : channel.type == Imf::UINT ? static_cast<const void*>(&u)
                                            : static_cast<const void*>(&v),
                size);
  }
  return bytes;
}

}  // namespace

void writeMultiPartExr(const std::string& path, int width, int height, const std::vector<ExrPart>& parts,
                       const ExrOptions& options) {
  const Imath::Box2i display = options.displayWindow.value_or(Imath::Box2i({0, 0}, {width - 1, height - 1}));
  const Imath::Box2i data({options.originX, options.originY},
                          {options.originX + width - 1, options.originY + height - 1});
  std::vector<Imf::Header> headers;
  for (const ExrPart& part : parts) {
    Imf::Header header(display, data);
    header.compression() = options.compression;
    if (!part.name.empty()) header.setName(part.name);
    if (options.editHeader) options.editHeader(header);
    header.setType(options.tiled ? Imf::TILEDIMAGE : Imf::SCANLINEIMAGE);
    if (options.tiled) header.setTileDescription(Imf::TileDescription(options.tileSize, options.tileSize));
    for (const ExrChannel& channel : part.channels) header.channels().insert(channel.name, Imf::Channel(channel.type));
    headers.push_back(header);
  }
  Imf::MultiPartOutputFile file(path.c_str(), headers.data(), int(headers.size()));
  for (std::size_t p = 0; p < parts.size(); ++p) {
    std::vector<std::vector<char>> storage;
    Imf::FrameBuffer buffer;
    for (const ExrChannel& channel : parts[p].channels) {
      if (channel.values.size() != std::size_t(width) * height)
        throw std::invalid_argument("channel " + channel.name + " has the wrong number of values");
      storage.push_back(encode(channel));
      const std::size_t size = bytesPerValue(channel.type);
      buffer.insert(channel.name, Imf::Slice::Make(channel.type, storage.back().data(), data, size, size * width));
    }
    if (options.tiled) {
      Imf::TiledOutputPart out(file, int(p));
      out.setFrameBuffer(buffer);
      out.writeTiles(0, out.numXTiles() - 1, 0, out.numYTiles() - 1);
    } else {
      Imf::OutputPart out(file, int(p));
      out.setFrameBuffer(buffer);
      out.writePixels(height);
    }
  }
}

void writeExr(const std::string& path, int width, int height, const std::vector<ExrChannel>& channels,
              const ExrOptions& options) {
  writeMultiPartExr(path, width, height, {{"", channels}}, options);
}

ExrContents readExr(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i& window = file.header().dataWindow();
  ExrContents contents;
  contents.width = window.max.x - window.min.x + 1;
  contents.height = window.max.y - window.min.y + 1;
  contents.compression = file.header().compression();
  contents.dataWindow = window;
  contents.displayWindow = file.header().displayWindow();
  Imf::FrameBuffer buffer;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it) {
    ExrChannel& channel = contents.channels[it.name()];
    channel = {it.name(), std::vector<float>(std::size_t(contents.width) * contents.height), it.channel().type};
    buffer.insert(it.name(), Imf::Slice::Make(Imf::FLOAT, channel.values.data(), window, sizeof(float),
                                              sizeof(float) * contents.width));
  }
  file.setFrameBuffer(buffer);
  file.readPixels(window.min.y, window.max.y);
  return contents;
}

float storedValue(Imf::PixelType type, float value) {
  return type == Imf::HALF ? float(half(value)) : type == Imf::UINT ? float(std::uint32_t(value)) : value;
}

std::vector<float> pattern(int width, int height, float seed) {
  std::vector<float> values(std::size_t(width) * height);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = seed + 0.0371f * float(i) - 0.5f;
  return values;
}

std::string stringAttribute(const std::string& path, const char* name) {
  return Imf::InputFile(path.c_str()).header().typedAttribute<Imf::StringAttribute>(name).value();
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeBytes(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << bytes;
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace ssrcl::test
