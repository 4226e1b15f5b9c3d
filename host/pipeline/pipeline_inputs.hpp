#pragma once
// The pipeline's named input images: the caller's Image objects or views, read at execute.
#include <map>
#include <string>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl::detail {

class PipelineInputs {
 public:
  // Throw Error(InvalidArgument) for a name that is not an input.
  void set(const std::string& name, const Image& image);
  void set(const std::string& name, const ImageView& view);
  bool has(const std::string& name) const;
  ImageView view(const std::string& name) const;  // as the image is now
  // Packed floats of a set input (converted into a buffer kept for the next frame when needed).
  const float* pixels(const std::string& name);
  // Throws Error naming the image and what is wrong: a missing one, channels, size.
  void validate(const Camera& camera, const TraceSettings& s) const;

  // Which inputs are set, at which size: what a commit's buffers and kernels depend on.
  struct Shape {
    int width = 0, height = 0, channels = 0;
    bool operator==(const Shape& o) const { return width == o.width && height == o.height && channels == o.channels; }
  };
  std::map<std::string, Shape> shapes() const;
  // Throws Error(InvalidOperation) naming the first input set, removed or resized since `committed`.
  void checkUnchanged(const std::map<std::string, Shape>& committed) const;

 private:
  struct Source {
    const Image* image = nullptr;  // followed to its current content, or
    ImageView view;
  };
  std::map<std::string, Source> sources_;
  std::map<std::string, std::vector<float>> staging_;
};

}  // namespace ssrcl::detail
