// G-buffer input. Every pass may come from its own file; channels are found by full name in any
// part, or as part name + "." + channel (how multi-part writers such as Nuke name layers; a file
// with a single named part is stored as single-part but keeps its name, so that counts too).
// Images cover the data window (row 0 = its top row); the display window is ignored, so passes
// line up by data-window-relative position and only their sizes have to agree.

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>

#include <algorithm>
#include <map>
#include <memory>
#include <new>
#include <string>
#include <utility>
#include <vector>

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

struct ChannelRef {
  int part = -1;
  std::string name;  // the name inside that part
  int width = 0, height = 0;
};

class ExrFile {
 public:
  explicit ExrFile(std::string path) : path_(std::move(path)) {
    guarded(path_, "not a readable OpenEXR file",
            [&] { file_ = std::make_unique<Imf::MultiPartInputFile>(path_.c_str()); });
  }

  const std::string& path() const { return path_; }
  Imf::MultiPartInputFile& file() { return *file_; }

  ChannelRef find(const std::string& fullName) const {
    for (int p = 0; p < file_->parts(); ++p)
      if (file_->header(p).channels().findChannel(fullName)) return ref(p, fullName);
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
    const Imf::Channel& channel = *header.channels().findChannel(name);
    if (channel.xSampling != 1 || channel.ySampling != 1)
      throw Error(ErrorCode::InvalidInput, path_ + ": channel '" + name + "' is subsampled, which is not supported");
    const Imath::Box2i& window = header.dataWindow();
    return {part, name, window.max.x - window.min.x + 1, window.max.y - window.min.y + 1};
  }

  std::string path_;
  std::unique_ptr<Imf::MultiPartInputFile> file_;
};

std::vector<std::string> splitNames(const std::string& list) {
  std::vector<std::string> names;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = list.find(',', start);
    std::string name = list.substr(start, end == std::string::npos ? std::string::npos : end - start);
    name.erase(0, name.find_first_not_of(' '));
    name.erase(name.find_last_not_of(' ') + 1);
    names.push_back(name);
    if (end == std::string::npos) return names;
    start = end + 1;
  }
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

GBuffer loadGBuffer(const GBufferSource& source) {
  GBuffer gbuffer;
  std::vector<Pass> passes = {
      {"color", &gbuffer.color, 3, source.colorFile, source.colorChannels, "Combined.R,Combined.G,Combined.B", "R,G,B"},
      {"depth", &gbuffer.depth, 1, source.depthFile, source.depthChannel, "Depth.Z", "Z"},
      {"normal", &gbuffer.normal, 3, source.normalFile, source.normalChannels, "Normal.X,Normal.Y,Normal.Z",
       "N.X,N.Y,N.Z"},
  };
  if (!source.constantRoughness)
    passes.push_back({"roughness", &gbuffer.roughness, 1, source.roughnessFile, source.roughnessChannel, "roughness.X",
                      "roughness"});

  std::map<std::string, ExrFile> files;  // each file is opened once
  std::vector<Request> requests;
  for (const Pass& pass : passes) {
    const std::string& path = pass.file.empty() ? source.file : pass.file;
    if (path.empty())
      throw Error(ErrorCode::InvalidArgument, std::string("no input file given for the ") + pass.label + " pass");
    std::vector<std::string> names;
    if (!pass.names.empty()) {
      names = splitNames(pass.names);
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
    ExrFile& file = files.try_emplace(path, path).first->second;
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

  const Request& first = requests.front();
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
  return gbuffer;
}

}  // namespace ssrcl
