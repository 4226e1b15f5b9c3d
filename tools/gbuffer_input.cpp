#include "gbuffer_input.hpp"

#include "ssrcl/error.hpp"

namespace ssrcl::cli {

FrameSource GBufferInputOptions::sourceFor(const std::string& file, const std::string& camera) const {
  FrameSource s = source;
  s.file = file;
  s.camera = camera;
  s.readRoughness = !roughness;
  if (!form.form.empty()) s.outputForm = form.resolved();  // else chooseOutputForm decides
  s.f0Channels = form.f0Channels;
  s.baseColorChannels = form.baseColorChannels;
  s.metallicChannel = form.metallicChannel;
  s.materialFile = form.materialFile;
  return s;
}

TraceSettings GBufferInputOptions::applyTo(TraceSettings settings) const {
  settings.constantRoughness = roughness;
  return settings;
}

void addChannelOptions(CLI::App& cmd, GBufferInputOptions& o) {
  const char* in = "Input channels";
  cmd.add_option("--renderer", o.source.renderer,
                 "Channel names, depth kind, normal space of this renderer's passes (docs/renderers.md); each option "
                 "below overrides its part")
      ->group(in)
      ->check(CLI::IsMember(rendererNames()))
      ->capture_default_str();
  // Set only when given, overriding the preset's (even with the preset's own value).
  const auto setter = [](std::optional<std::string>& field) {
    return [&field](const std::string& value) { field = value; };
  };
  cmd.add_option_function<std::string>("--layer", setter(o.source.layer),
                                       "Layer prefix of the default channel names; \"\" for plain R,G,B / Z / N.X")
      ->group(in);
  cmd.add_option_function<std::string>(
         "--color-channels", setter(o.source.colorChannels),
         "Color channel names, e.g. R,G,B ('|' separates alternatives, the first present is read)")
      ->group(in);
  cmd.add_option_function<std::string>("--depth-channel", setter(o.source.depthChannel),
                                       "Depth channel name ('|' separates alternatives)")
      ->group(in);
  cmd.add_option_function<std::string>("--normal-channels", setter(o.source.normalChannels),
                                       "Normal channel names, e.g. N.X,N.Y,N.Z ('|' separates alternatives)")
      ->group(in);
  cmd.add_option("--position", o.source.positionChannels,
                 "World-position channels (e.g. P.X,P.Y,P.Z) to take depth from instead of a depth pass")
      ->group(in);
  cmd.add_option_function<std::string>(
         "--depth-kind", [&o](const std::string& v) { o.source.depthKind = depthKindNamed(v); },
         "planar: view depth along the camera axis (Blender); radial: distance along each pixel's ray")
      ->group(in)
      ->check(CLI::IsMember({"planar", "radial"}));
  cmd.add_option_function<std::string>(
         "--normal-space", [&o](const std::string& v) { o.source.normalSpace = normalSpaceNamed(v); },
         "world; camera: x right, y up, +z forward (OpenEXR/RenderMan); camera-gl: x right, y up, -z forward; "
         "camera-cv: x right, y down, +z forward (V-Ray for Maya)")
      ->group(in)
      ->check(CLI::IsMember({"world", "camera", "camera-gl", "camera-cv"}));
  cmd.add_option("--fov", o.source.fov,
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
  cmd.add_flag("!--no-input-check", o.source.inputCheck,
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
  cmd.add_option("--back-depth-file", o.source.backDepthFile,
                 "Back-face depth of the same camera (planar, or the depth's kind; 1e10 = none): exact surface "
                 "thickness where known. A deep EXR gives its first sample's ZBack. Default: the frame's "
                 "BackFaces.Depth.Z where it has one")
      ->group(in);
  cmd.add_option("--back-depth-channel", o.source.backDepthChannel,
                 "Its channel (default ViewLayer.Depth.Z in --back-depth-file; without it, a channel of the frame's "
                 "depth file)")
      ->group(in);
}

GBufferInputOptions viewInputOptions(const GBufferInputOptions& o) {
  GBufferInputOptions viewOptions = o;  // a view has its own file for every pass, and no material passes
  FrameSource& s = viewOptions.source;
  s.colorFile = s.depthFile = s.normalFile = s.roughnessFile = s.positionFile = "";
  s.backDepthFile = s.backDepthChannel = "";
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
      views.frames.push_back(loadFrame(viewOptions.sourceFor(files[k], ownCamera ? cameras[k] : "")));
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
