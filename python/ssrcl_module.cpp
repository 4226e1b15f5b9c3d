#include "bindings.hpp"
#include "ssrcl/version.hpp"

PYBIND11_MODULE(ssrcl, m) {
  m.doc() = "Screen-space reflections for rendered passes (OpenCL). Names follow the C++ API "
            "(include/ssrcl/): Device, Pipeline, TraceSettings, qualityPreset, loadFrame, writeReflectionExr.";
  m.attr("__version__") = ssrcl::versionString();  // the library loaded, as SSRCL_VERSION names the headers
  using namespace ssrcl::python;
  bindErrors(m);  // first: the others' docstrings and calls may raise them
  bindSettings(m);
  bindCamera(m);
  bindDevice(m);
  bindEnvironment(m);
  bindTemporal(m);
  bindPipeline(m);
  bindIo(m);
}
