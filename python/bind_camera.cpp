#include <pybind11/numpy.h>

#include <string>

#include "bindings.hpp"
#include "ssrcl/camera.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::python {
namespace {

using Matrix = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Matrices cross as 4x4 arrays indexed [row, column] (p' = M @ p), as the camera sidecar writes
// them; glm stores columns first.
Matrix toArray(const glm::dmat4& m) {
  Matrix a({4, 4});
  auto r = a.mutable_unchecked<2>();
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) r(row, col) = m[col][row];
  return a;
}

glm::dmat4 toMatrix(const Matrix& a, const char* name) {
  if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
    throw Error(ErrorCode::InvalidArgument, std::string("camera ") + name + " must be a 4x4 matrix");
  glm::dmat4 m;
  auto r = a.unchecked<2>();
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) m[col][row] = r(row, col);
  return m;
}

}  // namespace

void bindCamera(py::module_& m) {
  py::class_<Camera>(m, "Camera",
                     "A pinhole or orthographic camera (include/ssrcl/camera.hpp): view (world -> camera, looking "
                     "down -Z) and projection (OpenGL clip space) as 4x4 arrays [row, column], size in pixels, "
                     "near/far (both 0: derived from the projection).")
      .def(py::init([](const Matrix& view, const Matrix& projection, int width, int height, double nearPlane,
                       double farPlane) {
             Camera c;
             c.view = toMatrix(view, "view");
             c.projection = toMatrix(projection, "projection");
             c.width = width;
             c.height = height;
             c.nearPlane = nearPlane;
             c.farPlane = farPlane;
             // As the camera sidecar's loader does when it has no near/far.
             if (nearPlane == 0.0 && farPlane == 0.0) deriveClipPlanes(c.projection, c.nearPlane, c.farPlane);
             return c;
           }),
           py::arg("view"), py::arg("projection"), py::arg("width"), py::arg("height"), py::arg("nearPlane") = 0.0,
           py::arg("farPlane") = 0.0)
      .def_property(
          "view", [](const Camera& c) { return toArray(c.view); },
          [](Camera& c, const Matrix& a) { c.view = toMatrix(a, "view"); })
      .def_property(
          "projection", [](const Camera& c) { return toArray(c.projection); },
          [](Camera& c, const Matrix& a) { c.projection = toMatrix(a, "projection"); })
      .def_readwrite("width", &Camera::width)
      .def_readwrite("height", &Camera::height)
      .def_readwrite("nearPlane", &Camera::nearPlane)
      .def_readwrite("farPlane", &Camera::farPlane);

  py::class_<PixelBox>(m, "PixelBox", "An inclusive pixel rectangle in EXR window coordinates (y down).")
      .def(py::init([](int minX, int minY, int maxX, int maxY) { return PixelBox{minX, minY, maxX, maxY}; }),
           py::arg("minX"), py::arg("minY"), py::arg("maxX"), py::arg("maxY"))
      .def_readwrite("minX", &PixelBox::minX)
      .def_readwrite("minY", &PixelBox::minY)
      .def_readwrite("maxX", &PixelBox::maxX)
      .def_readwrite("maxY", &PixelBox::maxY)
      .def_property_readonly("width", &PixelBox::width)
      .def_property_readonly("height", &PixelBox::height)
      .def("__eq__", &PixelBox::operator==);
  py::class_<ExrWindows>(m, "ExrWindows", "An EXR's data and display windows.")
      .def(py::init([](const PixelBox& data, const PixelBox& display) { return ExrWindows{data, display}; }),
           py::arg("data"), py::arg("display"))
      .def_readwrite("data", &ExrWindows::data)
      .def_readwrite("display", &ExrWindows::display);

  m.def("loadCameraJson", &loadCameraJson, py::arg("path"), "Reads and validates a camera sidecar (.camera.json).");
  m.def("saveCameraJson", &saveCameraJson, py::arg("path"), py::arg("camera"));
}

}  // namespace ssrcl::python
