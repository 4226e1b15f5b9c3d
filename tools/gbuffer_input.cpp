#include "gbuffer_input.hpp"

#include <filesystem>

#include "renderer_presets.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl::cli {
namespace {

bool given(const CLI::Option* option) { return option && option->count() > 0; }

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

// The file whose header camera is read: the depth's (or positions').
std::string headerCameraFile(const GBufferSource& source) {
  if (source.positionFile.empty() && source.depthFile.empty()) return source.file;
  return source.positionChannels.empty() ? source.depthFile : source.positionFile;
}

}  // namespace

GBufferSource GBufferInputOptions::sourceFor(const std::string& file) const {
  GBufferSource s = source;
  s.file = file;
  s.readRoughness = !roughness;
  const RendererPreset& preset = rendererPreset(renderer);
  if (!given(layerOption)) s.layer = preset.layer;
  if (!given(colorOption)) s.colorChannels = preset.colorChannels;
  if (!given(depthOption)) s.depthChannel = preset.depthChannel;
  if (!given(normalOption)) s.normalChannels = preset.normalChannels;
  s.depthKind = depthKind.empty() ? preset.depthKind : depthKind == "radial" ? DepthKind::Radial : DepthKind::Planar;
  s.normalSpace = normalSpace.empty() ? preset.normalSpace
                  : normalSpace == "camera"    ? NormalSpace::Camera
                  : normalSpace == "camera-gl" ? NormalSpace::CameraGL
                  : normalSpace == "camera-cv" ? NormalSpace::CameraCV
                                               : NormalSpace::World;
  form.nameMaterialPasses(s);
  return s;
}

TraceSettings GBufferInputOptions::applyTo(TraceSettings settings) const {
  settings.constantRoughness = roughness;
  return settings;
}

void addChannelOptions(CLI::App& cmd, GBufferInputOptions& o) {
  const char* in = "Input channels";
  cmd.add_option("--renderer", o.renderer,
                 "Channel names, depth kind, normal space of this renderer's passes (docs/renderers.md); each option "
                 "below overrides its part")
      ->group(in)
      ->check(CLI::IsMember(rendererNames()))
      ->capture_default_str();
  o.layerOption =
      cmd.add_option("--layer", o.source.layer, "Layer prefix of the default channel names; \"\" for plain R,G,B / Z / N.X")
          ->group(in);
  o.colorOption =
      cmd.add_option("--color-channels", o.source.colorChannels,
                     "Color channel names, e.g. R,G,B ('|' separates alternatives, the first present is read)")
          ->group(in);
  o.depthOption =
      cmd.add_option("--depth-channel", o.source.depthChannel, "Depth channel name ('|' separates alternatives)")
          ->group(in);
  o.normalOption = cmd.add_option("--normal-channels", o.source.normalChannels,
                                  "Normal channel names, e.g. N.X,N.Y,N.Z ('|' separates alternatives)")
                       ->group(in);
  cmd.add_option("--position", o.source.positionChannels,
                 "World-position channels (e.g. P.X,P.Y,P.Z) to take depth from instead of a depth pass")
      ->group(in);
  cmd.add_option("--depth-kind", o.depthKind,
                 "planar: view depth along the camera axis (Blender); radial: distance along each pixel's ray")
      ->group(in)
      ->check(CLI::IsMember({"planar", "radial"}));
  cmd.add_option("--normal-space", o.normalSpace,
                 "world; camera: x right, y up, +z forward (OpenEXR/RenderMan); camera-gl: x right, y up, -z forward; "
                 "camera-cv: x right, y down, +z forward (V-Ray for Maya)")
      ->group(in)
      ->check(CLI::IsMember({"world", "camera", "camera-gl", "camera-cv"}));
  cmd.add_option("--fov", o.fov,
                 "Horizontal field of view (degrees) of a header camera that has a pose and no projection (Karma's "
                 "worldToCamera); from Houdini's camera: 2 atan(aperture / (2 focal length)). Checked against a "
                 "header that has its own; refused with a camera JSON")
      ->group(in);
  cmd.add_option("--roughness-channel", o.source.roughnessChannel, "Roughness channel name")->group(in);
  // Its range is the library's check (validateSettings).
  cmd.add_option("--roughness", o.roughness, "Constant roughness for every pixel instead of a channel")->group(in);
  cmd.add_flag("!--no-glossy-passes", o.source.glossyPasses,
               "Ignore Blender's glossy passes (GlossDir/GlossInd/GlossCol): hits on glossy surfaces then take their "
               "screen colour instead of a second bounce")
      ->group(in);
  cmd.add_flag("!--no-input-check", o.inputCheck,
               "Trace even when the normal pass disagrees with the depth under the declared conventions")
      ->group(in);
}

void addPassFileOptions(CLI::App& cmd, GBufferInputOptions& o) {
  const char* in = "Input channels";
  cmd.add_option("--color", o.source.colorFile, "Read color from this EXR instead")->group(in);
  cmd.add_option("--depth", o.source.depthFile, "Read depth from this EXR instead")->group(in);
  cmd.add_option("--normal", o.source.normalFile, "Read normals from this EXR instead")->group(in);
  cmd.add_option("--roughness-file", o.source.roughnessFile, "Read roughness from this EXR instead")->group(in);
  cmd.add_option("--position-file", o.source.positionFile, "Read positions (--position) from this EXR instead")
      ->group(in);
}

std::string sidecarCameraPath(const std::string& exr) {
  std::filesystem::path p(exr);
  return (p.parent_path() / (p.stem().string() + ".camera.json")).string();
}

Frame loadFrame(const GBufferInputOptions& o, const std::string& input, const std::string& cameraPath,
                bool headerFallback) {
  const GBufferSource source = o.sourceFor(input);
  Frame frame;
  GBuffer& g = frame.gbuffer;
  g = loadGBuffer(source);

  std::error_code ec;
  const bool useHeader = headerFallback && !std::filesystem::exists(cameraPath, ec);
  // A camera file is a whole camera: a field of view beside it would be ignored or contradict it.
  if (o.fov && !useHeader)
    throw Error(ErrorCode::InvalidArgument, "--fov completes a header camera, but the camera comes from " +
                                                cameraPath + ": drop --fov (or the camera file)");
  if (useHeader && !g.headerCamera)
    throw Error(ErrorCode::InvalidInput,
                cameraPath + ": no such camera file, and " + headerCameraFile(source) +
                    (o.fov ? " has no worldToCamera in its header for --fov to complete; give --camera"
                           : " has no camera in its header (worldToCamera with worldToNDC or worldToScreen, or "
                             "V-Ray's cameraTransform with cameraFov); give --camera"));
  if (useHeader && !g.headerCamera->problem.empty()) throw Error(ErrorCode::InvalidInput, g.headerCamera->problem);
  // A given --fov is not second-guessed by the fit (whose refusals would then name the wrong cause):
  // the input check's positions-on-their-pixels rule still catches a wrong one.
  if (useHeader && !g.headerCamera->unprojected.empty() && !source.positionChannels.empty() && !o.fov)
    fitFieldOfView(*g.headerCamera, g, headerCameraFile(source));
  if (useHeader && o.fov) applyFieldOfView(*g.headerCamera, *o.fov, headerCameraFile(source));
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
  if (o.inputCheck) checkInputConventions(g, source, frame.camera);
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

GBufferInputOptions viewInputOptions(const GBufferInputOptions& o) {
  GBufferInputOptions viewOptions = o;  // a view has its own file for every pass, and no material passes
  GBufferSource& s = viewOptions.source;
  s.colorFile = s.depthFile = s.normalFile = s.roughnessFile = s.positionFile = s.materialFile = "";
  s.glossyPasses = false;
  viewOptions.form = OutputFormOptions{};
  return viewOptions;
}

Views loadViews(const GBufferInputOptions& o, const std::vector<std::string>& files,
                const std::vector<std::string>& cameras) {
  if (cameras.size() > files.size())
    throw Error(ErrorCode::InvalidArgument, "--view-camera is given " + std::to_string(cameras.size()) +
                                                " times but --view " + std::to_string(files.size()) +
                                                " (each --view-camera belongs to the --view in the same place)");
  const GBufferInputOptions viewOptions = viewInputOptions(o);
  Views views;
  views.files = files;
  for (size_t k = 0; k < files.size(); ++k) {
    const bool ownCamera = k < cameras.size() && !cameras[k].empty();
    try {
      views.frames.push_back(
          loadFrame(viewOptions, files[k], ownCamera ? cameras[k] : sidecarCameraPath(files[k]), !ownCamera));
    } catch (const Error& e) {
      throw Error(e.code(), "view " + files[k] + ": " + e.what());
    }
  }
  return views;
}

void addViewOptions(CLI::App& cmd, std::vector<std::string>& files, std::vector<std::string>& cameras,
                    const std::string& viewHelp) {
  cmd.add_option("--view", files, viewHelp)->allow_extra_args(false);
  cmd.add_option("--view-camera", cameras,
                 "Camera JSON of the --view in the same place (default: its sidecar, else its EXR header)")
      ->allow_extra_args(false);
}

void setViews(Pipeline& pipeline, const Views& views) {
  pipeline.clearViews();
  addViews(pipeline, views, ViewTime::Same);
}

void addViews(Pipeline& pipeline, const Views& views, ViewTime time) {
  for (size_t k = 0; k < views.frames.size(); ++k)
    pipeline.setView(pipeline.viewCount(), views.frames[k].gbuffer, views.frames[k].camera, views.files[k], time);
}

}  // namespace ssrcl::cli
