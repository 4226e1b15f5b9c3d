#include <pybind11/stl.h>

#include <string>

#include "bindings.hpp"
#include <nlohmann/json.hpp>
#include "ssrcl/pipeline.hpp"

namespace ssrcl::python {
namespace {

// Every field, from the record the CLI writes into each output (settingsJson lists every field),
// so keyword checks and the bound attributes cannot drift apart unseen (tests/python/test_ssrcl.py
// compares them).
nlohmann::ordered_json fieldsOf(const TraceSettings& s) { return nlohmann::ordered_json::parse(settingsJson(s)); }

std::string knownFields() {
  const auto fields = fieldsOf(TraceSettings{});
  std::string names;
  for (const auto& item : fields.items()) names += (names.empty() ? "" : ", ") + item.key();
  return names;
}

}  // namespace

void bindSettings(py::module_& m) {
  py::enum_<ThicknessModel>(m, "ThicknessModel")
      .value("Adaptive", ThicknessModel::Adaptive)
      .value("Constant", ThicknessModel::Constant);
  py::enum_<RoughnessMapping>(m, "RoughnessMapping")
      .value("Squared", RoughnessMapping::Squared)
      .value("Linear", RoughnessMapping::Linear);
  py::enum_<Tracer>(m, "Tracer").value("HiZ", Tracer::HiZ).value("Linear", Tracer::Linear).value("DDA", Tracer::DDA);

  py::class_<TraceSettings> cls(m, "TraceSettings",
                                "Reflection-pass settings: every field of ssrcl::TraceSettings under its C++ name, "
                                "with the library's defaults (include/ssrcl/pipeline.hpp documents each).");
  cls.def(py::init([](const py::kwargs& kwargs) {
            TraceSettings settings;
            const auto known = fieldsOf(settings);
            py::object target = py::cast(&settings, py::return_value_policy::reference);
            for (const auto& [key, value] : kwargs) {
              const std::string name = py::str(key);
              if (!known.contains(name))
                throw py::type_error("TraceSettings has no setting '" + name + "' (settings: " + knownFields() + ")");
              py::setattr(target, key, value);
            }
            return settings;
          }),
          "TraceSettings(**fields): the defaults with the given fields changed; an unknown name raises TypeError.")
      .def_readwrite("thicknessModel", &TraceSettings::thicknessModel)
      .def_readwrite("thicknessRelative", &TraceSettings::thicknessRelative)
      .def_readwrite("thicknessScale", &TraceSettings::thicknessScale)
      .def_readwrite("thicknessMinRelative", &TraceSettings::thicknessMinRelative)
      .def_readwrite("thicknessMaxRelative", &TraceSettings::thicknessMaxRelative)
      .def_readwrite("maxIterations", &TraceSettings::maxIterations)
      .def_readwrite("maxRoughness", &TraceSettings::maxRoughness)
      .def_readwrite("edgeFade", &TraceSettings::edgeFade)
      .def_readwrite("viewRadianceCap", &TraceSettings::viewRadianceCap)
      .def_readwrite("constantRoughness", &TraceSettings::constantRoughness)
      .def_readwrite("glossyHitRoughness", &TraceSettings::glossyHitRoughness)
      .def_readwrite("samplesPerPixel", &TraceSettings::samplesPerPixel)
      .def_readwrite("fullRaysRoughness", &TraceSettings::fullRaysRoughness)
      .def_readwrite("seed", &TraceSettings::seed)
      .def_readwrite("roughnessMapping", &TraceSettings::roughnessMapping)
      .def_readwrite("mirrorRoughness", &TraceSettings::mirrorRoughness)
      .def_readwrite("reuseRadius", &TraceSettings::reuseRadius)
      .def_readwrite("prefilter", &TraceSettings::prefilter)
      .def_readwrite("edgeColors", &TraceSettings::edgeColors)
      .def_readwrite("tracer", &TraceSettings::tracer)
      .def_readwrite("linearStepPixels", &TraceSettings::linearStepPixels)
      .def_readwrite("denoise", &TraceSettings::denoise)
      .def_readwrite("separableDenoise", &TraceSettings::separableDenoise)
      .def_readwrite("traceStride", &TraceSettings::traceStride)
      .def_readwrite("countWork", &TraceSettings::countWork)
      .def_readwrite("classifyWork", &TraceSettings::classifyWork)
      .def_readwrite("environmentRotation", &TraceSettings::environmentRotation)
      .def_readwrite("environmentIntensity", &TraceSettings::environmentIntensity)
      .def(
          "json", [](const TraceSettings& s) { return settingsJson(s); },
          "Every field as JSON, as `ssrcl trace` records it in the output's ssrcl/settings attribute.")
      .def("__eq__", [](const TraceSettings& a, const TraceSettings& b) { return settingsJson(a) == settingsJson(b); })
      .def("__copy__", [](const TraceSettings& s) { return s; })
      .def("__deepcopy__", [](const TraceSettings& s, const py::dict&) { return s; })
      .def("__repr__", [](const TraceSettings& s) { return "TraceSettings(" + settingsJson(s) + ")"; });

  m.def("qualityPreset", &qualityPreset, py::arg("name"),
        "The settings of a named preset: draft, medium (the defaults), high or reference.");
}

}  // namespace ssrcl::python
