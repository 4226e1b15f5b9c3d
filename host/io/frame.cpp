// Reading a frame: the one order of the steps in io.hpp (passes, header camera, field of view,
// orientation, reframing, input check, conventions, clip planes), so every caller reads a frame
// the same way.
#include "ssrcl/frame.hpp"

#include <filesystem>

#include "exr_files.hpp"
#include "renderer_presets.hpp"
#include "shading/glossy_pass_form.hpp"
#include "ssrcl/error.hpp"
#include "ssrcl/pipeline.hpp"

namespace ssrcl {
namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

// The file whose header camera is read: the depth's (or positions').
std::string headerCameraFile(const GBufferSource& source) {
  if (source.positionFile.empty() && source.depthFile.empty()) return source.file;
  return source.positionChannels.empty() ? source.depthFile : source.positionFile;
}

// Whether `s` names any material pass (which asks for the glossy-pass form).
bool namesMaterialPasses(const FrameSource& s) {
  return !s.f0Channels.empty() || !s.baseColorChannels.empty() || !s.metallicChannel.empty() || !s.materialFile.empty();
}

// The material passes in `passes` (whose layer is resolved): the F0 channels given, or the base
// colour and metallic channels, by default Blender AOVs named base_color (colour) and metallic
// (value). The glossy-pass form needs them. The incident form reads them too where they are named
// or the file holds the default AOVs: the pipeline shades hits on glossy pixels with their own
// Fresnel (TraceSettings::glossyHitRoughness), whatever form the pass is written in.
void nameMaterialPasses(const FrameSource& s, GBufferSource& passes, detail::ExrFiles& files) {
  passes.materialFile = s.materialFile;
  if (!s.f0Channels.empty()) {
    if (!s.baseColorChannels.empty() || !s.metallicChannel.empty())
      throw Error(ErrorCode::InvalidArgument,
                  "give --f0-channels or --base-color-channels/--metallic-channel, not both");
    passes.f0Channels = s.f0Channels;
    return;
  }
  const std::string prefix = passes.layer.empty() ? "" : passes.layer + ".";
  passes.baseColorChannels = !s.baseColorChannels.empty()
                                 ? s.baseColorChannels
                                 : prefix + "base_color.R," + prefix + "base_color.G," + prefix + "base_color.B";
  passes.metallicChannel = !s.metallicChannel.empty() ? s.metallicChannel
                           : prefix.empty()           ? std::string("metallic")
                                                      : prefix + "metallic.X";
  const bool optional = s.outputForm.value_or(OutputForm::Incident) != OutputForm::GlossyPass && !namesMaterialPasses(s);
  if (optional && detail::defaultOutputForm(passes, files).form != OutputForm::GlossyPass) {
    passes.baseColorChannels.clear();
    passes.metallicChannel.clear();
  }
}

// The passes `s` names, the renderer preset filling in what it leaves unset.
GBufferSource passesOf(const FrameSource& s, detail::ExrFiles& files) {
  const detail::RendererPreset& preset = detail::rendererPreset(s.renderer);
  GBufferSource p;
  p.file = s.file;
  p.colorFile = s.colorFile;
  p.depthFile = s.depthFile;
  p.normalFile = s.normalFile;
  p.roughnessFile = s.roughnessFile;
  p.positionFile = s.positionFile;
  p.layer = s.layer.value_or(preset.layer);
  p.colorChannels = s.colorChannels.value_or(preset.colorChannels);
  p.depthChannel = s.depthChannel.value_or(preset.depthChannel);
  p.normalChannels = s.normalChannels.value_or(preset.normalChannels);
  p.roughnessChannel = s.roughnessChannel;
  p.readRoughness = s.readRoughness;
  p.positionChannels = s.positionChannels;
  p.depthKind = s.depthKind.value_or(preset.depthKind);
  p.normalSpace = s.normalSpace.value_or(preset.normalSpace);
  p.glossyPasses = s.glossyPasses;
  p.backDepthFile = s.backDepthFile;
  p.backDepthChannel = s.backDepthChannel;
  nameMaterialPasses(s, p, files);
  return p;
}

// `name` among `values` by `nameOf`; throws Error(InvalidArgument) naming `what` and the known names.
template <class Enum, size_t N>
Enum named(const std::string& name, const Enum (&values)[N], const char* (*nameOf)(Enum), const char* what) {
  std::string known;
  for (Enum v : values) {
    if (name == nameOf(v)) return v;
    known += (known.empty() ? "" : ", ") + std::string(nameOf(v));
  }
  throw Error(ErrorCode::InvalidArgument, std::string(what) + ": unknown value '" + name + "' (known: " + known + ")");
}

OutputFormChoice chooseOutputForm(const FrameSource& s, detail::ExrFiles& files) {
  if (s.outputForm) return {*s.outputForm, ""};
  if (namesMaterialPasses(s)) return {OutputForm::GlossyPass, ""};  // naming the material passes asks for the form that reads them
  if (!detail::rendererPreset(s.renderer).glossyPassByDefault) return {OutputForm::Incident, ""};
  FrameSource probe = s;
  probe.outputForm = OutputForm::GlossyPass;
  const DefaultOutputForm d = detail::defaultOutputForm(passesOf(probe, files), files);
  return {d.form, d.why};
}

}  // namespace

std::string sidecarCameraPath(const std::string& exr) {
  std::filesystem::path p(exr);
  return (p.parent_path() / (p.stem().string() + ".camera.json")).string();
}

OutputFormChoice chooseOutputForm(const FrameSource& s) {
  detail::ExrFiles files;
  return chooseOutputForm(s, files);
}

Frame loadFrame(const FrameSource& given) {
  detail::ExrFiles files;  // each file's headers read once: for the form's material passes, then to load
  const OutputFormChoice form = chooseOutputForm(given, files);
  FrameSource s = given;
  s.outputForm = form.form;
  Frame frame;
  frame.outputForm = form.form;
  frame.outputFormWhy = form.why;
  frame.passes = passesOf(s, files);
  const GBufferSource& source = frame.passes;
  GBuffer& g = frame.gbuffer;
  g = detail::loadGBuffer(source, files);

  const std::string cameraPath =
      !s.camera.empty() ? s.camera : sidecarCameraPath(s.file.empty() ? s.colorFile : s.file);
  std::error_code ec;
  const bool useHeader = s.camera.empty() && !std::filesystem::exists(cameraPath, ec);
  // A camera file is a whole camera: a field of view beside it would be ignored or contradict it.
  if (s.fov && !useHeader)
    throw Error(ErrorCode::InvalidArgument, "--fov completes a header camera, but the camera comes from " + cameraPath +
                                                ": drop --fov (or the camera file)");
  if (useHeader && !g.headerCamera)
    throw Error(ErrorCode::InvalidInput,
                cameraPath + ": no such camera file, and " + headerCameraFile(source) +
                    (s.fov ? " has no worldToCamera in its header for --fov to complete; give --camera"
                           : " has no camera in its header (worldToCamera with worldToNDC or worldToScreen, or "
                             "V-Ray's cameraTransform with cameraFov); give --camera"));
  if (useHeader && !g.headerCamera->problem.empty()) throw Error(ErrorCode::InvalidInput, g.headerCamera->problem);
  // A given --fov is not second-guessed by the fit (whose refusals would then name the wrong cause):
  // the input check's positions-on-their-pixels rule still catches a wrong one.
  if (useHeader && !g.headerCamera->unprojected.empty() && !source.positionChannels.empty() && !s.fov)
    fitFieldOfView(*g.headerCamera, g, headerCameraFile(source));
  if (useHeader && s.fov) applyFieldOfView(*g.headerCamera, *s.fov, headerCameraFile(source));
  if (useHeader && !g.headerCamera->unprojected.empty())
    throw Error(ErrorCode::InvalidInput, g.headerCamera->unprojected);
  if (useHeader) orientHeaderCamera(*g.headerCamera, g, source, headerCameraFile(source));
  const std::string cameraName = useHeader ? "the header camera (" + g.headerCamera->attributes + ")" : cameraPath;
  const Camera display = useHeader ? g.headerCamera->camera : loadCameraJson(cameraPath);
  if (display.width != g.displayWindow.width() || display.height != g.displayWindow.height())
    throw Error(ErrorCode::InvalidInput, cameraName + ": camera is " + sizeText(display.width, display.height) +
                                             " but the G-buffer's display window is " +
                                             sizeText(g.displayWindow.width(), g.displayWindow.height()));

  frame.windows = {g.dataWindow, g.displayWindow};
  frame.displayCamera = display;
  frame.cameraSource = cameraName;
  frame.camera = g.dataWindow == g.displayWindow ? display : reframeCamera(display, g.displayWindow, g.dataWindow);
  if (s.inputCheck) checkInputConventions(g, source, frame.camera);
  applyInputConventions(g, source, frame.camera);
  if (useHeader && g.headerCamera->clipPlanesKnown)
    checkClipPlanes(frame.camera, g.depth, headerCameraFile(source) + ": " + cameraName);
  if (useHeader && !g.headerCamera->clipPlanesKnown) fitClipPlanes(frame.camera, g.depth);
  validateCamera(frame.camera, cameraName.c_str());
  return frame;
}

void setFrame(Pipeline& pipeline, const Frame& frame) {
  pipeline.setGBuffer(frame.gbuffer);
  pipeline.setCamera(frame.camera);
}

DepthKind depthKindNamed(const std::string& name) {
  static const DepthKind all[] = {DepthKind::Planar, DepthKind::Radial};
  return named(name, all, depthKindName, "depth kind");
}

NormalSpace normalSpaceNamed(const std::string& name) {
  static const NormalSpace all[] = {NormalSpace::World, NormalSpace::Camera, NormalSpace::CameraGL,
                                    NormalSpace::CameraCV};
  return named(name, all, normalSpaceName, "normal space");
}

OutputForm outputFormNamed(const std::string& name) {
  static const OutputForm all[] = {OutputForm::Incident, OutputForm::GlossyPass};
  return named(name, all, outputFormName, "output form");
}

}  // namespace ssrcl
