#pragma once
#include <pybind11/numpy.h>

#include "ssrcl/image.hpp"

namespace ssrcl::python {

namespace py = pybind11;

// float32 C-contiguous arrays arrive as they are; anything else (other dtypes, strides) is
// converted by pybind11 on the way in.
using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// An HxWxC (or HxW, one channel) array as the library's Image. The Image owns its pixels, so this
// is the one copy the current API needs (one memcpy, no per-pixel conversion).
Image imageFromArray(const FloatArray& array, const char* name);

// `array` itself where the library can read it in place (float32 or float16, HxW or HxWxC,
// channels packed, positive strides), else a packed float32 copy. Throws for other shapes.
py::array viewableArray(const py::array& array, const char* name);
// An ImageView over an array viewableArray() returned (the array must outlive its use).
ImageView viewOfArray(const py::array& array, const char* name);

// A read-only HxWxC float32 array over `image`'s pixels, no copy; `owner` is kept alive by the
// array and must keep `image` unchanged as long as it lives.
py::array arrayView(const Image& image, py::handle owner);

}  // namespace ssrcl::python
