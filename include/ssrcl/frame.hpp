#pragma once
#include <optional>
#include <string>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/glossy_pass_form.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl {

class Pipeline;

// Where a frame's passes and camera are, and in which conventions (docs/library.md). The
// renderer preset gives the channel names, depth kind and normal space; each field set below
// overrides its part. Plain data: fill in what differs from the defaults.
struct FrameSource {
  std::string file;  // the G-buffer EXR; may be empty when colorFile, depthFile and normalFile are given
  // Camera JSON (loadCameraJson). Empty: <stem>.camera.json beside the EXR (or beside colorFile
  // when `file` is empty), and where that does not exist, the camera in the EXR header.
  std::string camera;
  std::string renderer = "blender";  // rendererNames()

  // Overrides of the preset: channel names ("a|b" lists alternatives, as GBufferSource), conventions.
  std::optional<std::string> layer, colorChannels, depthChannel, normalChannels;
  std::optional<DepthKind> depthKind;
  std::optional<NormalSpace> normalSpace;

  std::string positionChannels;  // world positions ("P.X,P.Y,P.Z") to take depth from instead of a depth pass
  std::string roughnessChannel;  // empty: {layer}.roughness.X (or roughness)
  bool readRoughness = true;     // false: no roughness pass (TraceSettings::constantRoughness gives it)
  bool glossyPasses = true;      // GBufferSource::glossyPasses
  // Passes read from files of their own (empty: from `file`).
  std::string colorFile, depthFile, normalFile, roughnessFile, positionFile;

  // Horizontal field of view (degrees) completing a header camera that has a pose and no
  // projection (Karma's), checked against a header that has its own (applyFieldOfView).
  std::optional<double> fov;
  // Refuse passes the declared conventions do not explain (checkInputConventions).
  bool inputCheck = true;

  // The material passes: F0, or base colour and metallic (by default the layer's Blender AOVs
  // base_color and metallic), from materialFile when given. The glossy-pass form needs them
  // (applyGlossyPassForm); either form shades hits on glossy pixels with them, the incident form
  // reading the default AOVs where the file holds them. outputForm unset: chooseOutputForm decides.
  std::optional<OutputForm> outputForm;
  std::string f0Channels, baseColorChannels, metallicChannel, materialFile;

  // The back-face depth pass (GBufferSource::backDepthFile, backDepthChannel): each pixel's
  // surface thickness where it is known (docs/inputs.md, "Back-face depth").
  std::string backDepthFile, backDepthChannel;
};

// A frame ready for the pipeline: planar depth, world normals, the camera of its pixels.
struct Frame {
  GBuffer gbuffer;
  Camera camera;             // of the data window (the pixels)
  ExrWindows windows;        // the input's data and display windows, for the output
  Camera displayCamera;      // of the display window, as written into the output's header
  std::string cameraSource;  // the camera file, or which header attributes it came from
  GBufferSource passes;      // the files and channels it was read from, the preset resolved
  // The form its pass is wanted in (FrameSource::outputForm, or chooseOutputForm's): for
  // GlossyPass, turn the pipeline's reflection into it with applyGlossyPassForm.
  OutputForm outputForm = OutputForm::Incident;
  std::string outputFormWhy;  // OutputFormChoice::why where chooseOutputForm chose it
};

// The form an unset FrameSource::outputForm takes: glossy-pass where material fields are given,
// or where the renderer preset takes it by default (Blender's: its glossy passes keep the
// Fresnel) and the file holds the material passes; incident otherwise. `why` names the file and
// channels behind a preset's choice (empty for the other cases).
struct OutputFormChoice {
  OutputForm form;
  std::string why;
};
OutputFormChoice chooseOutputForm(const FrameSource& source);

// Reads every pass and the camera, checks that the declared conventions explain the passes
// (unless inputCheck is false) and converts them to the pipeline's. Throws Error: IoError for an
// unreadable file, InvalidInput for passes or a camera that do not fit (the message names the file
// and the channel or option), InvalidArgument for contradictory fields.
Frame loadFrame(const FrameSource& source);

// Gives the pipeline the frame's images and camera; `frame` must stay alive until execute() is done.
void setFrame(Pipeline& pipeline, const Frame& frame);

// shot.exr -> shot.camera.json beside it.
std::string sidecarCameraPath(const std::string& exr);

// The renderer presets' names ("blender", "arnold", ...): README, Input.
std::vector<std::string> rendererNames();

// The inverses of depthKindName, normalSpaceName and outputFormName; throw Error(InvalidArgument)
// listing the known names.
DepthKind depthKindNamed(const std::string& name);
NormalSpace normalSpaceNamed(const std::string& name);
OutputForm outputFormNamed(const std::string& name);

}  // namespace ssrcl
