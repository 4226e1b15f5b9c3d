#include "numpy_image.hpp"

#include <cstring>
#include <string>

#include "ssrcl/error.hpp"

namespace ssrcl::python {

Image imageFromArray(const FloatArray& array, const char* name) {
  if (array.ndim() != 2 && array.ndim() != 3)
    throw Error(ErrorCode::InvalidArgument, std::string("image '") + name + "' must be an HxWxC or HxW array, got " +
                                                std::to_string(array.ndim()) + " dimensions");
  const py::ssize_t channels = array.ndim() == 3 ? array.shape(2) : 1;
  Image image(int(array.shape(1)), int(array.shape(0)), int(channels));
  if (!image.data.empty()) std::memcpy(image.data.data(), array.data(), image.data.size() * sizeof(float));
  return image;
}

py::array arrayView(const Image& image, py::handle owner) {
  const py::ssize_t c = image.channels, row = py::ssize_t(image.width) * c;
  py::array_t<float> view({py::ssize_t(image.height), py::ssize_t(image.width), c},
                          {row * py::ssize_t(sizeof(float)), c * py::ssize_t(sizeof(float)), py::ssize_t(sizeof(float))},
                          image.data.data(), owner);
  // Only the library writes these pixels.
  view.attr("setflags")(py::arg("write") = false);
  return std::move(view);
}

}  // namespace ssrcl::python
