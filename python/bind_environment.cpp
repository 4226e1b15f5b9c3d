#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "bindings.hpp"
#include "numpy_image.hpp"
#include "ssrcl/environment.hpp"

namespace ssrcl::python {

void bindEnvironment(py::module_& m) {
  py::class_<EnvironmentMap, std::shared_ptr<EnvironmentMap>>(
      m, "EnvironmentMap",
      "An equirectangular HDR environment prefiltered for GGX lobes (include/ssrcl/environment.hpp), for "
      "Pipeline.setEnvironment: Blender's world mapping, +Z up.")
      .def_readonly("source", &EnvironmentMap::source)
      .def_property_readonly("levelCount", [](const EnvironmentMap& e) { return e.levels.size(); })
      .def(
          "level",
          [](py::object self, size_t index) {
            const EnvironmentMap& e = self.cast<const EnvironmentMap&>();
            if (index >= e.levels.size())
              throw py::index_error("level " + std::to_string(index) + " of " + std::to_string(e.levels.size()));
            return arrayView(e.levels[index], self);
          },
          py::arg("index"), "Prefiltered level `index` (0: the map itself) as a read-only HxWx3 array.");

  m.def("loadEnvironmentMap", &loadEnvironmentMap, py::arg("path"), py::call_guard<py::gil_scoped_release>(),
        "Reads an equirectangular EXR (R, G, B) and prefilters it, as `ssrcl trace --environment` does.");
  m.def(
      "prefilterEnvironment",
      [](const FloatArray& equirect, const std::string& source) {
        return prefilterEnvironment(imageFromArray(equirect, "environment"), source);
      },
      py::arg("equirect"), py::arg("source") = "",
      "Prefilters an HxWx3 (or 4) float32 equirectangular array (W = 2H) as loadEnvironmentMap does.");
}

}  // namespace ssrcl::python
