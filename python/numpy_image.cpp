#include "numpy_image.hpp"

#include <cstring>
#include <string>

#include "ssrcl/error.hpp"

namespace ssrcl::python {

namespace {

void checkShape(const py::array& array, const char* name) {
  if (array.ndim() != 2 && array.ndim() != 3)
    throw Error(ErrorCode::InvalidArgument, std::string("image '") + name + "' must be an HxWxC or HxW array, got " +
                                                std::to_string(array.ndim()) + " dimensions");
}

bool readableInPlace(const py::array& a) {
  const bool half = a.dtype().is(py::dtype("float16")), single = a.dtype().is(py::dtype::of<float>());
  if (!half && !single) return false;
  for (py::ssize_t d = 0; d < a.ndim(); ++d)
    if (a.strides(d) <= 0) return false;
  return a.ndim() == 2 || a.strides(2) == a.itemsize();  // ImageView's channels are packed
}

}  // namespace

Image imageFromArray(const FloatArray& array, const char* name) {
  checkShape(array, name);
  const py::ssize_t channels = array.ndim() == 3 ? array.shape(2) : 1;
  Image image(int(array.shape(1)), int(array.shape(0)), int(channels));
  if (!image.data.empty()) std::memcpy(image.data.data(), array.data(), image.data.size() * sizeof(float));
  return image;
}

py::array viewableArray(const py::array& array, const char* name) {
  checkShape(array, name);
  if (readableInPlace(array)) return array;
  return FloatArray(array);  // converts, or raises for what cannot be
}

ImageView viewOfArray(const py::array& array, const char* name) {
  checkShape(array, name);
  const int channels = array.ndim() == 3 ? int(array.shape(2)) : 1;
  const PixelFormat format = array.itemsize() == 2 ? PixelFormat::Half : PixelFormat::Float;
  return ImageView(const_cast<void*>(array.data()), format, int(array.shape(1)), int(array.shape(0)), channels,
                   std::size_t(array.strides(1)), std::size_t(array.strides(0)));
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
