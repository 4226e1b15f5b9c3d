#include <pybind11/stl.h>

#include "bindings.hpp"
#include "numpy_image.hpp"
#include "ssrcl/temporal.hpp"

namespace ssrcl::python {
namespace {

// One frame of the window as Python passes it: the pipeline's outputs, the G-buffer, the camera.
struct PyTemporalFrame {
  Image reflection, distance, depth, normal, roughness;
  Camera camera;
};

py::array temporalBlendArrays(const std::vector<py::dict>& frames, size_t centre, std::optional<float> roughness,
                              float mirrorRoughness) {
  std::vector<PyTemporalFrame> images;
  for (const py::dict& f : frames) {
    PyTemporalFrame t;
    t.reflection = imageFromArray(f["reflection"].cast<FloatArray>(), "reflection");
    t.distance = imageFromArray(f["distance"].cast<FloatArray>(), "distance");
    t.depth = imageFromArray(f["depth"].cast<FloatArray>(), "depth");
    t.normal = imageFromArray(f["normal"].cast<FloatArray>(), "normal");
    if (f.contains("roughness") && !f["roughness"].is_none())
      t.roughness = imageFromArray(f["roughness"].cast<FloatArray>(), "roughness");
    t.camera = f["camera"].cast<Camera>();
    images.push_back(std::move(t));
  }
  std::vector<TemporalFrame> window;
  for (const PyTemporalFrame& t : images)
    window.push_back(
        {&t.reflection, &t.distance, &t.depth, &t.normal, t.roughness.empty() ? nullptr : &t.roughness, t.camera,
         nullptr});  // one blend: its statistics computed in it
  TemporalSettings settings;
  settings.constantRoughness = roughness;
  settings.mirrorRoughness = mirrorRoughness;
  Image out;
  {
    py::gil_scoped_release release;
    out = temporalBlend(window, centre, settings);
  }
  py::array_t<float> result({py::ssize_t(out.height), py::ssize_t(out.width), py::ssize_t(out.channels)});
  std::copy(out.data.begin(), out.data.end(), result.mutable_data());
  return std::move(result);
}

}  // namespace

void bindTemporal(py::module_& m) {
  m.def("temporalBlend", &temporalBlendArrays, py::arg("frames"), py::arg("centre"), py::arg("roughness") = py::none(),
        py::arg("mirror_roughness") = 0.02f,
        "Frame `centre`'s reflection blended with the other frames' (ssrcl::temporalBlend): each frame a dict of "
        "reflection (HxWx4), distance (HxW), depth (HxW, planar), normal (HxWx3, world), roughness (HxW, or "
        "None with `roughness` given) and camera; returns HxWx4");
}

}  // namespace ssrcl::python
