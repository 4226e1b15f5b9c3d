#include <pybind11/stl.h>

#include "bindings.hpp"
#include "ssrcl/device.hpp"

namespace ssrcl::python {

void bindDevice(py::module_& m) {
  py::class_<DeviceInfo>(m, "DeviceInfo")
      .def_readonly("index", &DeviceInfo::index)
      .def_readonly("platform", &DeviceInfo::platform)
      .def_readonly("name", &DeviceInfo::name)
      .def_readonly("version", &DeviceInfo::version)
      .def_readonly("isGpu", &DeviceInfo::isGpu)
      .def_readonly("globalMemory", &DeviceInfo::globalMemory)
      .def_readonly("computeUnits", &DeviceInfo::computeUnits)
      .def("__repr__", [](const DeviceInfo& d) {
        return "DeviceInfo(index=" + std::to_string(d.index) + ", name='" + d.name + "', platform='" + d.platform + "')";
      });

  m.def("devices", &Device::list, "Every OpenCL device, as `ssrcl devices` lists them (empty when none).");

  py::class_<Device>(m, "Device",
                     "An OpenCL device: Device() the preferred one, Device('cpu'), Device('gpu'), or Device(index) "
                     "from devices(). Share one among pipelines.")
      .def(py::init<int>(), py::arg("index"))
      .def(py::init(&openDevice), py::arg("kind") = "default")
      .def_property_readonly("info", &Device::info);
}

}  // namespace ssrcl::python
