// G-buffer input. Every pass may come from its own file; channels are found by full name in any
// part, or as part name + "." + channel (how multi-part writers such as Nuke name layers; a file
// with a single named part is stored as single-part but keeps its name, so that counts too).
// Images cover the data window (row 0 = its top row); passes line up by data-window-relative
// position and only their sizes have to agree. The geometry pass's data and display windows are
// kept: the camera describes the display window.

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfPartType.h>

#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

#include "exr_deep_depth.hpp"
#include "exr_files.hpp"
#include "exr_header_camera.hpp"
#include "exr_header_check.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl {
namespace {

// Runs an OpenEXR operation, turning its untyped exceptions into Error naming the file.
template <class F>
void guarded(const std::string& path, const char* doing, F&& operation) {
  try {
    operation();
  } catch (const Error&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw Error(ErrorCode::OutOfMemory, path + ": out of memory");
  } catch (const std::exception& e) {  // Iex::BaseExc derives from std::exception
    throw Error(ErrorCode::IoError, path + ": " + doing + " (" + e.what() + ")");
  }
}

// Refuses a G-buffer before allocating it: beyond 2^30 pixels (the kernels index pixels with
// 32-bit ints; validateCamera has the same bound), or needing more memory than the machine has.
// A tiny file may declare any size (its header is all it takes), and allocating first would
// leave the kernel's out-of-memory killer to answer instead of a message.
void checkFrameSize(const std::string& path, int width, int height, std::size_t channels) {
  const long long pixels = static_cast<long long>(width) * height;
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  if (pixels > (1LL << 30))
    throw Error(ErrorCode::InvalidInput, path + ": the G-buffer is " + size + " = " + std::to_string(pixels) +
                                             " pixels, more than the 1073741824 (2^30) a frame may have");
  const double bytes = double(pixels) * double(channels) * sizeof(float);
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  const double memory = pages > 0 && pageSize > 0 ? double(pages) * double(pageSize) : 0.0;
  if (memory > 0 && bytes > memory) {
    char text[160];
    std::snprintf(text, sizeof text, ": the %s G-buffer needs %.1f GiB of memory, more than this machine's %.1f GiB",
                  size.c_str(), bytes / 1073741824.0, memory / 1073741824.0);
    throw Error(ErrorCode::OutOfMemory, path + text);
  }
}

}  // namespace

// Checks an EXR header before OpenEXR reads it. OpenEXR (3.1) allocates what a header declares
// before finding the file too short: a 2 KB file whose 'type' string attribute claims 1.8 GB
// makes it allocate 1.8 GB (found by fuzz/fuzz_gbuffer), a scanline image 2^31 lines high an
// offset table of 16 GB, a wide one line buffers of the width. So the header is walked here the
// way OpenEXR reads it (fixed-size attribute types read their size whatever the size field says,
// the channel list reads up to its empty name, strings, vectors, previews and unknown types
// allocate what they declare), and refused when any of that would not fit in the file, when a
// part's offset table (8 bytes a chunk) would not, when its data window exceeds the 2^30 pixels a
// frame may have, or when one decoded chunk would exceed 2 GB. Files without the EXR magic
// number are left to OpenEXR to refuse. Throws Error(IoError) naming the file.
void checkHeaderSizes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return;  // OpenEXR reports why
  in.seekg(0, std::ios::end);
  const long long fileSize = static_cast<long long>(in.tellg());
  in.seekg(0);
  unsigned char start[8];
  if (!in.read(reinterpret_cast<char*>(start), 8) || start[0] != 0x76 || start[1] != 0x2f || start[2] != 0x31 ||
      start[3] != 0x01)
    return;
  const bool multiPart = (start[5] & 0x10) != 0, singleTiled = (start[5] & 0x02) != 0;
  const auto bad = [&](const std::string& problem) {
    throw Error(ErrorCode::IoError, path + ": not a readable OpenEXR file (" + problem + ")");
  };
  const auto left = [&] { return fileSize - static_cast<long long>(in.tellg()); };
  const auto need = [&](long long bytes, const std::string& what) {
    if (bytes < 0 || bytes > left())
      bad(what + " declares " + std::to_string(bytes) + " bytes; the file has " + std::to_string(left()) + " left");
  };
  const auto readName = [&](std::string& name) {
    name.clear();
    for (char c; in.get(c);) {
      if (c == '\0') return;
      if (name.size() >= 255) bad("a header name is longer than 255 characters");
      name += c;
    }
    bad("the header ends early");
  };
  const auto readBytes = [&](long long n) {
    need(n, "the header");
    std::string v(size_t(n), '\0');
    in.read(v.data(), n);
    return v;
  };
  const auto int32At = [](const std::string& v, size_t at) {
    return v.size() >= at + 4
               ? static_cast<int32_t>(uint32_t(uint8_t(v[at])) | uint32_t(uint8_t(v[at + 1])) << 8 |
                                      uint32_t(uint8_t(v[at + 2])) << 16 | uint32_t(uint8_t(v[at + 3])) << 24)
               : 0;
  };
  // Bytes OpenEXR 3.1 reads for each fixed-size attribute type, whatever the size field says.
  static const std::map<std::string, int> kFixed = {{"box2i", 16},
                                                    {"box2f", 16},
                                                    {"chromaticities", 32},
                                                    {"compression", 1},
                                                    {"deepImageState", 1},
                                                    {"double", 8},
                                                    {"envmap", 1},
                                                    {"float", 4},
                                                    {"int", 4},
                                                    {"keycode", 28},
                                                    {"lineOrder", 1},
                                                    {"m33f", 36},
                                                    {"m33d", 72},
                                                    {"m44f", 64},
                                                    {"m44d", 128},
                                                    {"rational", 8},
                                                    {"tiledesc", 9},
                                                    {"timecode", 8},
                                                    {"v2i", 8},
                                                    {"v2f", 8},
                                                    {"v2d", 16},
                                                    {"v3i", 12},
                                                    {"v3f", 12},
                                                    {"v3d", 24}};

  long long tableBytes = 0;
  for (int part = 0;; ++part) {
    std::string dataWindow, tiles, compression, chunkCount, partType;
    long long pixelBytes = 0;  // one pixel of every channel, at full resolution
    int attributes = 0;
    for (;; ++attributes) {
      std::string name, type;
      readName(name);
      if (name.empty()) break;
      readName(type);
      const int32_t size = int32At(readBytes(4), 0);
      const std::string what = "header attribute '" + name + "' (" + type + ")";
      if (size < 0) bad(what + " has a negative size");
      const auto fixed = kFixed.find(type);
      std::string value;
      if (fixed != kFixed.end()) {
        value = readBytes(fixed->second);
      } else if (type == "chlist") {
        for (std::string channel;;) {  // name, then type, pLinear, 3 reserved, xSampling, ySampling
          readName(channel);
          if (channel.empty()) break;
          const std::string c = readBytes(16);
          const int32_t pixelType = int32At(c, 0), xs = int32At(c, 8), ys = int32At(c, 12);
          pixelBytes += pixelType == 1 ? 2 : 4;
          if (xs < 1 || ys < 1) bad("channel '" + channel + "' has a sampling rate below 1");
        }
      } else if (type == "preview") {
        const std::string wh = readBytes(8);  // width, height, then 4 bytes a pixel
        const double bytes = 4.0 * uint32_t(int32At(wh, 0)) * uint32_t(int32At(wh, 4));
        if (bytes > double(left())) need(static_cast<long long>(std::min(bytes, 9e18)), what);
        in.seekg(static_cast<long long>(bytes), std::ios::cur);
      } else if (type == "stringvector") {
        need(size, what);
        for (long long read = 0; read < size;) {
          const int32_t length = int32At(readBytes(4), 0);
          need(length, what + ", one of its strings,");
          in.seekg(length, std::ios::cur);
          read += 4 + length;
        }
      } else {  // string, floatvector, idmanifest and unknown (opaque) types: `size` bytes
        need(size, what);
        if (name == "type" || name == "chunkCount")
          value = readBytes(size);
        else
          in.seekg(size, std::ios::cur);
      }
      if (name == "dataWindow") dataWindow = value;
      if (name == "tiles") tiles = value;
      if (name == "compression") compression = value;
      if (name == "chunkCount") chunkCount = value;
      if (name == "type") partType = value;
    }
    if (attributes == 0) {
      if (part == 0) bad("empty header");
      break;  // the empty header that ends a multi-part file's list
    }
    const bool tiled = (!multiPart && singleTiled) || partType.find("tile") != std::string::npos;
    long long chunks = 0, width = 0, height = 0, chunkLines = 1, chunkWidth = 0;
    if (dataWindow.size() == 16) {
      width = static_cast<long long>(int32At(dataWindow, 8)) - int32At(dataWindow, 0) + 1;
      height = static_cast<long long>(int32At(dataWindow, 12)) - int32At(dataWindow, 4) + 1;
    }
    if (width > 0 && height > 0) {
      if (width > (1LL << 30) || height > (1LL << 30) || width * height > (1LL << 30))
        bad("its data window is " + std::to_string(width) + "x" + std::to_string(height) +
            ", more than the 1073741824 (2^30) pixels a frame may have");
      if (tiled && tiles.size() >= 8) {
        const long long tx = std::max<long long>(1, uint32_t(int32At(tiles, 0)));
        const long long ty = std::max<long long>(1, uint32_t(int32At(tiles, 4)));
        chunks = ((width + tx - 1) / tx) * ((height + ty - 1) / ty);  // level 0 alone: a lower bound
        chunkWidth = std::min(tx, width);
        chunkLines = std::min(ty, height);
      } else if (!tiled) {
        // Scanlines per chunk of each compression (NO, RLE, ZIPS, ZIP, PIZ, PXR24, B44, B44A, DWAA, DWAB).
        static const int kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};
        const int c = compression.empty() ? 0 : uint8_t(compression[0]);
        const long long lines = c < 10 ? kLines[c] : 256;
        chunks = (height + lines - 1) / lines;
        chunkWidth = width;
        chunkLines = std::min(lines, height);
      }
    }
    if (!chunkCount.empty()) chunks = std::max<long long>(chunks, int32At(chunkCount, 0));
    if (chunks < 0) bad("a negative chunk count");
    if (double(chunkWidth) * double(chunkLines) * double(pixelBytes) > 2147483647.0)
      bad("one chunk of its " + std::to_string(width) + "x" + std::to_string(height) +
          " pixels would decode to more than 2 GB");
    tableBytes += 8 * chunks;
    if (tableBytes > fileSize)
      bad("its header declares " + std::to_string(chunks) +
          " chunks, whose offset table alone is longer than the file (" + std::to_string(fileSize) + " bytes)");
    if (!multiPart) break;
  }
}

namespace {

struct ChannelRef {
  int part = -1;
  std::string name;  // the name inside that part
  int width = 0, height = 0;
};

class ExrFile {
 public:
  explicit ExrFile(std::string path) : path_(std::move(path)) {
    guarded(path_, "not a readable OpenEXR file", [&] {
      checkHeaderSizes(path_);
      file_ = std::make_unique<Imf::MultiPartInputFile>(path_.c_str());
    });
  }

  const std::string& path() const { return path_; }
  Imf::MultiPartInputFile& file() { return *file_; }

  // A bare name that several parts hold is refused rather than read from the first: Houdini
  // writes each render var as a part of channels R, G, B (parts "N", "albedo", "C": see docs/renderers.md,
  // Karma), so "R" alone could be a normal's x.
  ChannelRef find(const std::string& fullName) const {
    std::vector<int> holders;
    for (int p = 0; p < file_->parts(); ++p)
      if (file_->header(p).channels().findChannel(fullName)) holders.push_back(p);
    if (holders.size() > 1) {
      std::string qualified;
      for (int p : holders)
        if (file_->header(p).hasName())
          qualified += (qualified.empty() ? "'" : ", '") + file_->header(p).name() + "." + fullName + "'";
      throw Error(ErrorCode::InvalidInput, path_ + ": channel '" + fullName + "' is in " +
                                               std::to_string(holders.size()) + " parts; name it with its part (" +
                                               qualified + ")");
    }
    if (holders.size() == 1) return ref(holders[0], fullName);
    for (int p = 0; p < file_->parts(); ++p) {
      if (!file_->header(p).hasName()) continue;
      const std::string prefix = file_->header(p).name() + ".";
      if (fullName.compare(0, prefix.size(), prefix) == 0 &&
          file_->header(p).channels().findChannel(fullName.substr(prefix.size())))
        return ref(p, fullName.substr(prefix.size()));
    }
    return {};
  }

  // "a, b, c" as find() accepts them, shortened for one-line messages. Part names are shown only
  // where they are needed to tell parts apart.
  std::string listChannels() const {
    constexpr int kShown = 12;
    std::string list;
    int count = 0;
    for (int p = 0; p < file_->parts(); ++p) {
      const bool qualify = file_->parts() > 1 && file_->header(p).hasName();
      const std::string prefix = qualify ? file_->header(p).name() + "." : "";
      const Imf::ChannelList& channels = file_->header(p).channels();
      for (auto it = channels.begin(); it != channels.end(); ++it, ++count)
        if (count < kShown) list += (count ? ", " : "") + prefix + it.name();
    }
    if (count > kShown) list += ", ... (" + std::to_string(count - kShown) + " more)";
    return count ? list : "no channels";
  }

 private:
  ChannelRef ref(int part, const std::string& name) const {
    const Imf::Header& header = file_->header(part);
    if (header.hasType() && Imf::isDeepData(header.type()))
      throw Error(ErrorCode::InvalidInput,
                  path_ + ": channel '" + name + "' is deep data (" + header.type() + "), which is not supported");
    const Imf::Channel& channel = *header.channels().findChannel(name);
    if (channel.xSampling != 1 || channel.ySampling != 1)
      throw Error(ErrorCode::InvalidInput, path_ + ": channel '" + name + "' is subsampled, which is not supported");
    const Imath::Box2i& window = header.dataWindow();
    // In 64 bits: a hostile window (min -2^31, max 2^31 - 1) overflows int.
    const long long width = static_cast<long long>(window.max.x) - window.min.x + 1;
    const long long height = static_cast<long long>(window.max.y) - window.min.y + 1;
    if (width <= 0 || height <= 0 || width > INT_MAX || height > INT_MAX)
      throw Error(ErrorCode::InvalidInput, path_ + ": data window (" + std::to_string(window.min.x) + ", " +
                                               std::to_string(window.min.y) + ") - (" + std::to_string(window.max.x) +
                                               ", " + std::to_string(window.max.y) + ") is empty or too large");
    return {part, name, int(width), int(height)};
  }

  std::string path_;
  std::unique_ptr<Imf::MultiPartInputFile> file_;
};

// The items of a `separator`-separated list, spaces around each trimmed.
std::vector<std::string> split(const std::string& list, char separator) {
  std::vector<std::string> items;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = list.find(separator, start);
    std::string item = list.substr(start, end == std::string::npos ? std::string::npos : end - start);
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    items.push_back(item);
    if (end == std::string::npos) return items;
    start = end + 1;
  }
}

std::vector<std::string> splitNames(const std::string& list) { return split(list, ','); }
std::vector<std::string> splitAlternatives(const std::string& list) { return split(list, '|'); }

enum class Holds { Missing, Ambiguous, All };

// Whether `file` holds every channel of a comma-separated list, and unambiguously.
Holds holdsAll(const ExrFile& file, const std::string& names) {
  Holds holds = Holds::All;
  for (const std::string& name : splitNames(names)) {
    try {
      if (file.find(name).part < 0) return Holds::Missing;
    } catch (const Error&) {  // in several parts: another alternative may name it exactly
      holds = Holds::Ambiguous;
    }
  }
  return holds;
}

// Whether `file` holds one of the alternatives of `names` (held ambiguously counts: reading it
// names the parts that hold it).
bool holdsAny(const ExrFile& file, const std::string& names) {
  const std::vector<std::string> alternatives = splitAlternatives(names);
  return std::any_of(alternatives.begin(), alternatives.end(),
                     [&](const std::string& alternative) { return holdsAll(file, alternative) != Holds::Missing; });
}

// "a,b,c|d,e,f" lists alternatives in order of preference (renderer presets name each layout a
// renderer is known to write): the first the file holds is read. A list without '|' is returned
// as is, so a missing channel is reported by name; so is the first alternative held only
// ambiguously when none is held exactly, so that its read names the parts that hold it.
std::string chooseAlternative(const ExrFile& file, const std::string& names, const char* label) {
  if (names.find('|') == std::string::npos) return names;
  const std::vector<std::string> alternatives = splitAlternatives(names);
  const std::string* ambiguous = nullptr;
  for (const std::string& alternative : alternatives) {
    const Holds holds = holdsAll(file, alternative);
    if (holds == Holds::All) return alternative;
    if (holds == Holds::Ambiguous && !ambiguous) ambiguous = &alternative;
  }
  if (ambiguous) return *ambiguous;
  std::string tried;
  for (const std::string& alternative : alternatives) tried += (tried.empty() ? "'" : ", '") + alternative + "'";
  throw Error(ErrorCode::InvalidInput, file.path() + ": none of the channel sets " + tried + " for the " + label +
                                           " pass is there (has: " + file.listChannels() + ")");
}

struct Pass {
  const char* label;
  Image* image;
  int channels;
  const std::string& file;
  const std::string& names;  // user's comma-separated names, empty for the default
  const char* layered;       // default suffixes after "{layer}."
  const char* plain;         // default names when the layer is ""
};

struct Request {
  Image* image;
  int channel;
  ExrFile* file;
  std::string name;  // as requested, for messages
  ChannelRef ref;
};

}  // namespace

namespace detail {

struct ExrFiles::Opened {
  std::map<std::string, ExrFile> byPath;

  ExrFile& at(const std::string& path) { return byPath.try_emplace(path, path).first->second; }
};

ExrFiles::ExrFiles() : opened_(std::make_unique<Opened>()) {}
ExrFiles::~ExrFiles() = default;

bool ExrFiles::holds(const std::string& file, const std::string& names) { return holdsAny(opened_->at(file), names); }

}  // namespace detail

bool holdsChannels(const std::string& path, const std::string& names) { return holdsAny(ExrFile(path), names); }

GBuffer loadGBuffer(const GBufferSource& source) {
  detail::ExrFiles files;
  return detail::loadGBuffer(source, files);
}

GBuffer detail::loadGBuffer(const GBufferSource& source, ExrFiles& exrFiles) {
  GBuffer gbuffer;
  std::vector<Pass> passes = {
      {"color", &gbuffer.color, 3, source.colorFile, source.colorChannels, "Combined.R,Combined.G,Combined.B", "R,G,B"},
      source.positionChannels.empty()
          ? Pass{"depth", &gbuffer.depth, 1, source.depthFile, source.depthChannel, "Depth.Z", "Z"}
          : Pass{"position", &gbuffer.position, 3, source.positionFile, source.positionChannels, "", ""},
      {"normal", &gbuffer.normal, 3, source.normalFile, source.normalChannels, "Normal.X,Normal.Y,Normal.Z",
       "N.X,N.Y,N.Z"},
  };
  if (source.readRoughness)
    passes.push_back({"roughness", &gbuffer.roughness, 1, source.roughnessFile, source.roughnessChannel, "roughness.X",
                      "roughness"});

  // Material passes for the glossy-pass output form: full names given, no defaults.
  const std::pair<const char*, std::pair<Image*, const std::string*>> material[] = {
      {"F0", {&gbuffer.f0, &source.f0Channels}},
      {"base colour", {&gbuffer.baseColor, &source.baseColorChannels}},
      {"metallic", {&gbuffer.metallic, &source.metallicChannel}}};
  for (const auto& [label, pass] : material)
    if (!pass.second->empty())
      passes.push_back({label, pass.first, pass.first == &gbuffer.metallic ? 1 : 3, source.materialFile, *pass.second,
                        "", ""});

  ExrFiles::Opened& files = exrFiles.opened();  // each file is opened once

  // Optional glossy passes, read where all nine channels are there (Blender multilayer naming).
  Image glossDir, glossInd, glossCol;
  const std::string noNames;
  const std::string& colorPath = source.colorFile.empty() ? source.file : source.colorFile;
  if (source.glossyPasses && !source.layer.empty() && !colorPath.empty()) {
    ExrFile& file = files.at(colorPath);
    bool present = true;
    for (const char* pass : {"GlossDir", "GlossInd", "GlossCol"})
      for (const char* c : {"R", "G", "B"}) present = present && file.find(source.layer + "." + pass + "." + c).part >= 0;
    if (present) {
      passes.push_back({"glossy direct", &glossDir, 3, source.colorFile, noNames, "GlossDir.R,GlossDir.G,GlossDir.B", ""});
      passes.push_back(
          {"glossy indirect", &glossInd, 3, source.colorFile, noNames, "GlossInd.R,GlossInd.G,GlossInd.B", ""});
      passes.push_back({"glossy colour", &glossCol, 3, source.colorFile, noNames, "GlossCol.R,GlossCol.G,GlossCol.B", ""});
    }
  }

  // With positions, a depth pass in the same file is read too: the input check compares the two.
  if (!source.positionChannels.empty()) {
    const std::string& path = source.positionFile.empty() ? source.file : source.positionFile;
    const std::string name = !source.depthChannel.empty() ? source.depthChannel
                             : source.layer.empty()       ? std::string("Z")
                                                          : source.layer + ".Depth.Z";
    if (!path.empty() && holdsAny(files.at(path), name))
      passes.push_back({"depth", &gbuffer.depth, 1, source.positionFile, source.depthChannel, "Depth.Z", "Z"});
  }

  // The back-face depth: the channel named (by default Blender's ViewLayer.Depth.Z) of its own
  // file, or of the depth's file; else the add-on's BackFaces layer where that file holds it. A
  // deep file is read sample by sample below.
  const std::string depthPath = source.depthFile.empty() ? source.file : source.depthFile;
  const std::string backPath = source.backDepthFile.empty() ? depthPath : source.backDepthFile;
  const bool deepBack = !source.backDepthFile.empty() && detail::isDeepExr(backPath);
  std::string backChannel = source.backDepthChannel;
  if (backChannel.empty() && !source.backDepthFile.empty()) backChannel = "ViewLayer.Depth.Z";
  if (backChannel.empty() && !backPath.empty() && holdsAny(files.at(backPath), "BackFaces.Depth.Z"))
    backChannel = "BackFaces.Depth.Z";
  if (!deepBack && !backChannel.empty())
    passes.push_back({"back-face depth", &gbuffer.backDepth, 1, backPath, backChannel, "", ""});

  std::vector<Request> requests;
  for (const Pass& pass : passes) {
    const std::string& path = pass.file.empty() ? source.file : pass.file;
    if (path.empty())
      throw Error(ErrorCode::InvalidArgument, std::string("no input file given for the ") + pass.label + " pass");
    ExrFile& file = files.at(path);
    std::vector<std::string> names;
    if (!pass.names.empty()) {
      names = splitNames(chooseAlternative(file, pass.names, pass.label));
    } else if (source.layer.empty()) {
      names = splitNames(pass.plain);
    } else {
      for (const std::string& suffix : splitNames(pass.layered)) names.push_back(source.layer + "." + suffix);
    }
    if (int(names.size()) != pass.channels ||
        std::any_of(names.begin(), names.end(), [](const std::string& n) { return n.empty(); })) {
      throw Error(ErrorCode::InvalidArgument, std::string(pass.label) + " needs " + std::to_string(pass.channels) +
                                                  " comma-separated channel name(s), got '" + pass.names + "'");
    }
    for (int c = 0; c < pass.channels; ++c) {
      const ChannelRef ref = file.find(names[c]);
      if (ref.part < 0)
        throw Error(ErrorCode::InvalidInput, path + ": missing channel '" + names[c] + "' for the " + pass.label +
                                                 " pass (has: " + file.listChannels() + ")");
      if (!requests.empty() && (ref.width != requests[0].ref.width || ref.height != requests[0].ref.height)) {
        const Request& other = requests[0];
        throw Error(ErrorCode::InvalidInput, path + ": channel '" + names[c] + "' is " + std::to_string(ref.width) +
                                                 "x" + std::to_string(ref.height) + " but " + other.file->path() +
                                                 " channel '" + other.name + "' is " + std::to_string(other.ref.width) +
                                                 "x" + std::to_string(other.ref.height) +
                                                 "; all passes must have the same size");
      }
      requests.push_back({pass.image, c, &file, names[c], ref});
    }
  }

  // The windows and header camera of the geometry pass: the camera is matched against them.
  for (const Request& request : requests) {
    if (request.image != &gbuffer.depth && request.image != &gbuffer.position) continue;
    const Imf::Header& header = request.file->file().header(request.ref.part);
    const auto box = [](const Imath::Box2i& b) { return PixelBox{b.min.x, b.min.y, b.max.x, b.max.y}; };
    gbuffer.dataWindow = box(header.dataWindow());
    gbuffer.displayWindow = box(header.displayWindow());
    gbuffer.headerCamera = detail::cameraFromHeader(header, request.file->path());
    break;
  }

  const Request& first = requests.front();
  checkFrameSize(first.file->path(), first.ref.width, first.ref.height, requests.size());
  guarded(first.file->path(), "cannot allocate the G-buffer", [&] {
    for (const Pass& pass : passes) *pass.image = Image(first.ref.width, first.ref.height, pass.channels);
  });

  // One read per part decodes each chunk once for all passes it holds. A channel requested twice
  // (e.g. "Y,Y,Y") goes into a second frame buffer, as a frame buffer holds one slice per name.
  std::map<std::pair<ExrFile*, int>, std::vector<Imf::FrameBuffer>> reads;
  for (const Request& request : requests) {
    auto& buffers = reads[{request.file, request.ref.part}];
    auto buffer = std::find_if(buffers.begin(), buffers.end(),
                               [&](const Imf::FrameBuffer& b) { return b.findSlice(request.ref.name) == nullptr; });
    if (buffer == buffers.end()) buffer = buffers.emplace(buffers.end());
    Image& image = *request.image;
    const std::size_t xStride = sizeof(float) * image.channels;
    buffer->insert(request.ref.name, Imf::Slice::Make(Imf::FLOAT, &image.data[request.channel],
                                                      request.file->file().header(request.ref.part).dataWindow(),
                                                      xStride, xStride * image.width));
  }
  for (const auto& read : reads) {
    ExrFile& file = *read.first.first;
    guarded(file.path(), "cannot read pixel data", [&] {
      Imf::InputPart part(file.file(), read.first.second);
      const Imath::Box2i& window = part.header().dataWindow();
      for (const Imf::FrameBuffer& buffer : read.second) {
        part.setFrameBuffer(buffer);
        part.readPixels(window.min.y, window.max.y);
      }
    });
  }
  if (deepBack) {
    gbuffer.backDepth = detail::firstIntervalBack(detail::readDeepDepth(backPath));
    if (gbuffer.backDepth.width != first.ref.width || gbuffer.backDepth.height != first.ref.height)
      throw Error(ErrorCode::InvalidInput, backPath + ": the deep back-face depth is " +
                                               std::to_string(gbuffer.backDepth.width) + "x" +
                                               std::to_string(gbuffer.backDepth.height) + " but " +
                                               first.file->path() + " is " + std::to_string(first.ref.width) + "x" +
                                               std::to_string(first.ref.height) + "; all passes must have the same size");
  }
  if (!glossCol.empty()) {
    gbuffer.base = gbuffer.color;
    for (std::size_t k = 0; k < gbuffer.base.data.size(); ++k)
      gbuffer.base.data[k] -= glossCol.data[k] * (glossDir.data[k] + glossInd.data[k]);
    gbuffer.specular = std::move(glossCol);
  }
  return gbuffer;
}

}  // namespace ssrcl
