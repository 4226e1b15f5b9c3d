#pragma once
#include <pybind11/pybind11.h>

// Each part of the public API (include/ssrcl/) bound into the module, one file each.
namespace ssrcl::python {

namespace py = pybind11;

void bindErrors(py::module_& m);
void bindSettings(py::module_& m);
void bindCamera(py::module_& m);
void bindDevice(py::module_& m);
void bindPipeline(py::module_& m);
void bindIo(py::module_& m);
void bindEnvironment(py::module_& m);
void bindTemporal(py::module_& m);

}  // namespace ssrcl::python
