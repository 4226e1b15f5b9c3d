#include <pybind11/stl.h>

#include <map>
#include <memory>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "numpy_image.hpp"
#include "ssrcl/exr_output.hpp"
#include "ssrcl/frame.hpp"
#include "ssrcl/glossy_pass_form.hpp"

namespace ssrcl::python {
namespace {

// A frame's pass as a read-only view kept alive by the frame; None where the frame has none.
template <Image GBuffer::*pass>
py::object passView(py::object frame) {
  const Image& image = frame.cast<const Frame&>().gbuffer.*pass;
  return image.empty() ? py::none() : py::object(arrayView(image, frame));
}

Frame loadFrame(const std::string& path, const std::string& camera, const std::string& renderer,
                const std::string& depthKind, const std::string& normalSpace, std::optional<float> roughness,
                const std::string& roughnessChannel, const std::string& position, bool glossyPasses, bool inputCheck,
                const std::string& outputForm, const std::string& f0Channels, const std::string& baseColorChannels,
                const std::string& metallicChannel, const std::string& materialFile, std::optional<double> fov,
                const std::string& backDepthFile, const std::string& backDepthChannel) {
  FrameSource s;
  s.file = path;
  s.camera = camera;
  s.renderer = renderer;
  if (!depthKind.empty()) s.depthKind = depthKindNamed(depthKind);
  if (!normalSpace.empty()) s.normalSpace = normalSpaceNamed(normalSpace);
  s.readRoughness = !roughness;
  s.roughnessChannel = roughnessChannel;
  s.positionChannels = position;
  s.glossyPasses = glossyPasses;
  s.inputCheck = inputCheck;
  s.fov = fov;
  if (!outputForm.empty()) s.outputForm = outputFormNamed(outputForm);  // else chooseOutputForm decides
  s.f0Channels = f0Channels;
  s.baseColorChannels = baseColorChannels;
  s.metallicChannel = metallicChannel;
  s.materialFile = materialFile;
  s.backDepthFile = backDepthFile;
  s.backDepthChannel = backDepthChannel;
  return ssrcl::loadFrame(s);
}

void writeExr(const std::string& path, const FloatArray& rgba, const FloatArray& distance, const std::string& layer,
              bool half, const std::string& compression, const std::string& appendTo, const std::string& headerFrom,
              const std::optional<ExrWindows>& windows, const std::optional<Camera>& camera,
              const std::map<std::string, std::string>& attributes) {
  const ReflectionExrOptions options{layer, half, compression, appendTo, headerFrom, windows, camera, attributes};
  writeReflectionExr(path, imageFromArray(rgba, "rgba"), imageFromArray(distance, "distance"), options);
}

}  // namespace

void bindIo(py::module_& m) {
  py::class_<Frame, std::shared_ptr<Frame>>(m, "Frame",
                                            "A G-buffer read as `ssrcl trace` reads it: passes in the pipeline's "
                                            "conventions (planar depth, world normals) as read-only HxWxC arrays, "
                                            "and the camera of its pixels.")
      .def_property_readonly("color", &passView<&GBuffer::color>)
      .def_property_readonly("depth", &passView<&GBuffer::depth>)
      .def_property_readonly("normal", &passView<&GBuffer::normal>)
      .def_property_readonly("roughness", &passView<&GBuffer::roughness>)
      .def_property_readonly("base", &passView<&GBuffer::base>)
      .def_property_readonly("specular", &passView<&GBuffer::specular>)
      .def_property_readonly("backDepth", &passView<&GBuffer::backDepth>,
                             "Planar back-face depth, 0 where unknown; None without a back-face pass.")
      .def_property_readonly("camera", [](const Frame& f) { return f.camera; })
      .def_property_readonly("displayCamera", [](const Frame& f) { return f.displayCamera; },
                             "The camera of the display window (the one written into the output's header).")
      .def_property_readonly("windows", [](const Frame& f) { return f.windows; })
      .def_property_readonly("cameraSource", [](const Frame& f) { return f.cameraSource; })
      .def_property_readonly(
          "outputForm", [](const Frame& f) { return std::string(outputFormName(f.outputForm)); },
          "The form its pass is wanted in: loadFrame's outputForm, or the one `ssrcl trace` would take "
          "('glossy-pass': turn the pipeline's pass into it with applyGlossyPassForm).");

  m.def("loadFrame", &loadFrame, py::arg("path"), py::arg("camera") = "", py::arg("renderer") = "blender",
        py::arg("depthKind") = "", py::arg("normalSpace") = "", py::arg("roughness") = py::none(),
        py::arg("roughnessChannel") = "", py::arg("position") = "", py::arg("glossyPasses") = true,
        py::arg("inputCheck") = true, py::arg("outputForm") = "", py::arg("f0Channels") = "",
        py::arg("baseColorChannels") = "", py::arg("metallicChannel") = "", py::arg("materialFile") = "",
        py::arg("fov") = py::none(), py::arg("backDepthFile") = "", py::arg("backDepthChannel") = "",
        py::call_guard<py::gil_scoped_release>(),
        "Reads a G-buffer EXR and its camera as `ssrcl trace` does: the camera JSON `camera`, by default "
        "<stem>.camera.json beside the EXR or else the EXR header's camera; the renderer preset's channel names "
        "and conventions (depthKind, normalSpace override them); roughness (a number, as TraceSettings.constantRoughness) replaces the roughness channel; "
        "position names world-position channels to use instead of depth; runs the input check unless "
        "inputCheck=False. outputForm='glossy-pass' also reads the material passes applyGlossyPassForm needs "
        "(f0Channels, or baseColorChannels + metallicChannel, by default Blender AOVs base_color and metallic; "
        "materialFile: another EXR holding them); '' (the default) reads them where `ssrcl trace` would take that "
        "form (defaultOutputForm), 'incident' never. fov (degrees, horizontal) completes a header camera that has a "
        "pose and no projection (Karma's), as `--fov`. backDepthFile / backDepthChannel: the back-face depth pass, as "
        "`--back-depth-file` / `--back-depth-channel` (by default the file's own BackFaces.Depth.Z, if any).");

  m.def(
      "defaultOutputForm",
      [](const std::string& path, const std::string& renderer) {
        FrameSource s;
        s.file = path;
        s.renderer = renderer;
        return std::string(outputFormName(chooseOutputForm(s).form));
      },
      py::arg("path"), py::arg("renderer") = "blender",
      "The output form `ssrcl trace` gives the pass of this G-buffer EXR when no --output-form is given: "
      "'glossy-pass' for a Blender file holding the base_color and metallic AOVs (ViewLayer.base_color.R,G,B and "
      "ViewLayer.metallic.X), else 'incident' (other renderers: always; docs/renderers.md, Output forms per renderer).");

  m.def(
      "applyGlossyPassForm",
      [](const FloatArray& rgba, const Frame& frame, std::optional<float> constantRoughness) {
        auto* pass = new Image(imageFromArray(rgba, "rgba"));
        py::capsule owner(pass, [](void* p) { delete static_cast<Image*>(p); });
        applyGlossyPassForm(*pass, frame.gbuffer, frame.camera, constantRoughness);
        return arrayView(*pass, owner);
      },
      py::arg("rgba"), py::arg("frame"), py::arg("constantRoughness") = py::none(),
      "The reflection pass in the glossy-pass form (`--output-form glossy-pass`): rgb times the specular lobe's "
      "albedo E(view, roughness, F0), A unchanged (pure metal pixels, metallic >= 0.999: their colour, A 1), as a "
      "new array; `frame` from loadFrame(..., "
      "outputForm='glossy-pass'); constantRoughness (None: the roughness pass) as the pipeline's.");

  m.def("writeReflectionExr", &writeExr, py::arg("path"), py::arg("rgba"), py::arg("distance"), py::arg("layer") = "",
        py::arg("half") = false, py::arg("compression") = "", py::arg("appendTo") = "", py::arg("headerFrom") = "",
        py::arg("windows") = std::nullopt, py::arg("camera") = std::nullopt,
        py::arg("attributes") = std::map<std::string, std::string>{},
        "Writes the pass as `ssrcl trace` does (include/ssrcl/exr_output.hpp, ReflectionExrOptions): R,G,B,A and "
        "distance, or layer.R, ...; half floats; compression (exrCompressionNames()); appendTo: a copy of that EXR "
        "with the pass added; headerFrom: an EXR whose pixel aspect, screen window and chromaticities are carried "
        "over; windows and camera written into the header; string attributes.");
  m.def("exrCompressionNames", &exrCompressionNames);
  m.def("setExrThreads", &setExrThreads, py::arg("count"),
        "Threads OpenEXR (de)compresses every EXR with, process-wide (0, the default: the calling thread); the "
        "files are the same bytes whatever the count. A script that owns its process sets its core count, as the "
        "CLI does; one inside a host application leaves the host's setting alone.");
}

}  // namespace ssrcl::python
