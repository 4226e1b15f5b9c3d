#include "pipeline_inputs.hpp"

#include <algorithm>
#include <array>

#include "image_views.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::detail {
namespace {

struct InputKind {
  const char* name;
  int channels;  // colour takes 3 or 4
};
constexpr std::array<InputKind, 10> kInputs = {{{"color", 3},
                                               {"depth", 1},
                                               {"normal", 3},
                                               {"roughness", 1},
                                               {"base", 3},
                                               {"specular", 3},
                                               {"f0", 3},
                                               {"base_color", 3},
                                               {"metallic", 1},
                                               {"back_depth", 1}}};

// Inputs a frame may go without.
bool optional(const std::string& name, const TraceSettings& s) {
  return (name == "roughness" && s.constantRoughness) || name == "base" || name == "specular" || name == "f0" ||
         name == "base_color" || name == "metallic" || name == "back_depth";
}

void checkName(const std::string& name) {
  if (std::none_of(kInputs.begin(), kInputs.end(), [&](const InputKind& k) { return name == k.name; }))
    throw Error(ErrorCode::InvalidArgument,
                "unknown input image '" + name +
                    "' (expected color, depth, normal, roughness, base, specular, f0, base_color, metallic or back_depth)");
}

std::string shapeText(const PipelineInputs::Shape& s) {
  return std::to_string(s.width) + "x" + std::to_string(s.height) + " with " + std::to_string(s.channels) +
         (s.channels == 1 ? " channel" : " channels");
}

}  // namespace

void PipelineInputs::set(const std::string& name, const Image& image) {
  checkName(name);
  // An empty image unsets the input: nothing of it is kept, so a temporary Image() is safe.
  if (image.empty()) {
    sources_.erase(name);
    return;
  }
  sources_[name] = {&image, {}};
}

void PipelineInputs::set(const std::string& name, const ImageView& view) {
  checkName(name);
  sources_[name] = {nullptr, view};
}

ImageView PipelineInputs::view(const std::string& name) const {
  const Source& s = sources_.at(name);
  return s.image ? viewOf(*s.image) : s.view;
}

bool PipelineInputs::has(const std::string& name) const {
  auto it = sources_.find(name);
  return it != sources_.end() && !emptyView(view(name));
}

const float* PipelineInputs::pixels(const std::string& name) { return packedFloats(view(name), staging_[name]); }

void PipelineInputs::validate(const Camera& camera, const TraceSettings& s) const {
  if (has("base") != has("specular"))
    throw Error(ErrorCode::InvalidArgument, "pipeline: input images 'base' and 'specular' go together");
  if (has("base_color") != has("metallic"))
    throw Error(ErrorCode::InvalidArgument, "pipeline: input images 'base_color' and 'metallic' go together");
  if (has("f0") && has("base_color"))
    throw Error(ErrorCode::InvalidArgument, "pipeline: set input image 'f0' or 'base_color' and 'metallic', not both");
  for (const InputKind& kind : kInputs) {
    const std::string name = kind.name;
    if (!has(name)) {
      if (optional(name, s)) continue;
      throw Error(ErrorCode::InvalidArgument, "pipeline: input image '" + name + "' not set");
    }
    const ImageView v = view(name);
    const bool channelsOk = name == "color" ? (v.channels == 3 || v.channels == 4) : v.channels == kind.channels;
    if (!channelsOk)
      throw Error(ErrorCode::InvalidArgument,
                  "pipeline: input image '" + name + "' has " + std::to_string(v.channels) + " channels");
    if (v.width != camera.width || v.height != camera.height)
      throw Error(ErrorCode::InvalidInput, "pipeline: input image '" + name + "' is " + std::to_string(v.width) + "x" +
                                               std::to_string(v.height) + " but the camera is " +
                                               std::to_string(camera.width) + "x" + std::to_string(camera.height));
    const Source& source = sources_.at(name);
    if (source.image && source.image->data.size() != size_t(v.width) * v.height * v.channels)
      throw Error(ErrorCode::InvalidArgument,
                  "pipeline: input image '" + name + "' data size does not match its shape");
  }
}

std::map<std::string, PipelineInputs::Shape> PipelineInputs::shapes() const {
  std::map<std::string, Shape> result;
  for (const auto& [name, source] : sources_)
    if (has(name)) {
      const ImageView v = view(name);
      result[name] = {v.width, v.height, v.channels};
    }
  return result;
}

void PipelineInputs::checkUnchanged(const std::map<std::string, Shape>& committed) const {
  const std::map<std::string, Shape> now = shapes();
  if (now == committed) return;
  for (const InputKind& kind : kInputs) {
    const auto was = committed.find(kind.name), is = now.find(kind.name);
    if (was == committed.end() && is == now.end()) continue;
    const std::string what = "pipeline: input image '" + std::string(kind.name) + "' ";
    const char* remedy = " since commit(); call commit() again";
    if (was == committed.end()) throw Error(ErrorCode::InvalidOperation, what + "was set" + remedy);
    if (is == now.end()) throw Error(ErrorCode::InvalidOperation, what + "was removed" + remedy);
    if (!(was->second == is->second))
      throw Error(ErrorCode::InvalidOperation,
                  what + "changed from " + shapeText(was->second) + " to " + shapeText(is->second) + remedy);
  }
}

}  // namespace ssrcl::detail
