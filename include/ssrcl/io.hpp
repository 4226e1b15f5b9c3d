#pragma once
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"

namespace ssrcl {

// What the depth pass holds (see docs/inputs.md):
//   Planar  positive view-space depth along the camera axis (Blender's Depth.Z)
//   Radial  distance from the camera centre along the pixel's ray (for an orthographic camera,
//           from the image plane: the same as planar)
enum class DepthKind { Planar, Radial };

// The space of the normal pass:
//   World     world space (Blender, Arnold)
//   Camera    OpenEXR/RenderMan camera space: x right, y up, +z the viewing direction (left-handed)
//   CameraGL  x right, y up, -z the viewing direction (right-handed, OpenGL's eye space)
//   CameraCV  x right, y down, +z the viewing direction (right-handed, OpenCV's; V-Ray for Maya's
//             Normals render element)
enum class NormalSpace { World, Camera, CameraGL, CameraCV };

const char* depthKindName(DepthKind kind);       // "planar", "radial": the --depth-kind values
const char* normalSpaceName(NormalSpace space);  // "world", "camera", "camera-gl", "camera-cv"

// Where each G-buffer pass comes from. File fields left empty use `file`. Channel names are full
// EXR names; empty means the default built from `layer` (Blender multilayer naming):
//   color     {layer}.Combined.R,G,B   depth {layer}.Depth.Z
//   normal    {layer}.Normal.X,Y,Z     roughness {layer}.roughness.X
// With layer == "" the defaults are plain names: R,G,B  Z  N.X,N.Y,N.Z  roughness
// In multi-part files a channel may also be found as part name + "." + channel name; a bare name
// that several parts hold is refused. A list may give alternatives, "N.x,N.y,N.z|N.R,N.G,N.B":
// the first one the file holds is read.
struct GBufferSource {
  std::string file;
  std::string colorFile, depthFile, normalFile, roughnessFile;
  std::string layer = "ViewLayer";
  std::string colorChannels;  // comma-separated "R,G,B" form
  std::string depthChannel;
  std::string normalChannels;  // comma-separated "X,Y,Z" form
  std::string roughnessChannel;
  // false: no roughness channel is read (TraceSettings::constantRoughness gives every pixel's).
  bool readRoughness = true;

  // Non-empty: world-space positions ("P.X,P.Y,P.Z" form) are read instead of the depth pass and
  // give its planar depth; (0,0,0) and non-finite positions mean "no surface".
  std::string positionChannels;
  std::string positionFile;
  DepthKind depthKind = DepthKind::Planar;
  NormalSpace normalSpace = NormalSpace::World;

  // Where the colour's file has Blender's glossy passes ({layer}.GlossDir, GlossInd and GlossCol,
  // R,G,B each), GBuffer::base and GBuffer::specular are made from them, for hits on glossy
  // surfaces: base = color - GlossCol * (GlossDir + GlossInd), specular = GlossCol.
  bool glossyPasses = true;

  // For the glossy-pass output form (glossy_pass_form.hpp), read only when named: the specular
  // colour at normal incidence (3 channels), or Principled base colour (3) and metallic (1).
  // With base and specular, Pipeline::setGBuffer also shades hits on glossy surfaces with them.
  // Full channel names, comma-separated; `materialFile` empty reads them from `file`.
  std::string f0Channels, baseColorChannels, metallicChannel;
  std::string materialFile;

  // The back-face depth pass (GBuffer::backDepth), in the depth pass's kind: from `backDepthFile`
  // when given (channel `backDepthChannel`, by default Blender's ViewLayer.Depth.Z; a deep EXR
  // gives each pixel's first sample's ZBack), else from the depth's file where it holds the
  // add-on's BackFaces.Depth.Z, else none.
  std::string backDepthFile, backDepthChannel;
};

// The camera an EXR header describes, for its display window: OpenEXR's standard worldToCamera
// with worldToNDC or worldToScreen (OpenEXR's, OpenImageIO's and Houdini's conventions, told apart
// from the matrices), or V-Ray's
// cameraTransform with cameraFov. Near/far come from the header where it has them (RenderMan's,
// Arnold's or V-Ray's clip attributes; checkClipPlanes checks them against the depth);
// otherwise `clipPlanesKnown` is false and fitClipPlanes sets them from the depth.
struct HeaderCamera {
  Camera camera;
  bool clipPlanesKnown = false;
  std::string attributes;  // which attributes it came from, for messages
  // Orthographic worldToCamera + worldToNDC only: the matrices cannot tell OpenEXR's camera space
  // (+z forward) from Houdini's (-z forward), so `camera` is the first reading and `reversed` the
  // same camera looking the other way; orientHeaderCamera chooses from the passes.
  std::optional<Camera> reversed;
  // Non-empty when the header has camera attributes that cannot be used: why (naming the file and
  // attribute). Only an error when the header camera is needed (no sidecar, no --camera).
  std::string problem;
  // Non-empty when the header has the camera's pose but no projection (Karma's worldToNDC, a copy
  // of worldToCamera): why, naming the file and attribute. `camera` then holds that pose (OpenEXR
  // camera space, +z forward) with a placeholder projection until applyFieldOfView completes it.
  std::string unprojected;
};

struct GBuffer {
  Image color;      // 3 channels
  // 1 channel: as declared until applyInputConventions, then planar view depth. With positions it
  // holds the file's depth pass where it has one (for the input check) until then.
  Image depth;
  Image normal;     // 3 channels: as declared until applyInputConventions, then world space
  Image roughness;  // 1 channel; empty when readRoughness was false
  // Optional, for hits on glossy surfaces (TraceSettings::glossyHitRoughness): radiance without
  // the specular reflection, and the specular colour, 3 channels each.
  Image base, specular;
  Image position;   // 3 channels, world space; only when positionChannels was given
  Image f0, baseColor, metallic;  // as read, where GBufferSource names them (3, 3, 1 channels)
  // 1 channel, optional: the depth of the first back-facing surface behind each pixel's visible
  // one, in the depth's kind until applyInputConventions, then planar view depth with 0 where it
  // is unknown (NaN, negative, 1e10 and beyond, or not behind the front surface).
  Image backDepth;
  // The EXR windows of the depth (or position) pass's file: the images cover the data window;
  // a camera describes the display window.
  PixelBox dataWindow, displayWindow;
  // The camera in that file's header, when it has camera attributes.
  std::optional<HeaderCamera> headerCamera;
};

// The passes of `g` a pipeline takes, by their Pipeline::setImage names: the three it needs, then
// the optional ones (empty where `g` lacks them). Pipeline::setGBuffer and the bindings set them all.
inline std::array<std::pair<const char*, const Image*>, 10> pipelinePasses(const GBuffer& g) {
  return {{{"color", &g.color},
           {"depth", &g.depth},
           {"normal", &g.normal},
           {"roughness", &g.roughness},
           {"base", &g.base},
           {"specular", &g.specular},
           {"f0", &g.f0},
           {"base_color", &g.baseColor},
           {"metallic", &g.metallic},
           {"back_depth", &g.backDepth}}};
}

// A horizontal field of view (degrees, across the display window, of a pinhole whose axis is at the
// window's centre: 2 atan(aperture / (2 focal length))) for the header camera of `file`: completes
// one that has a pose and no projection (HeaderCamera::unprojected), and is checked against one that
// has its own. Throws Error(InvalidInput) naming both when they differ by more than 0.1 degree, when
// the header's camera is orthographic, or for a field of view outside (0, 180).
void applyFieldOfView(HeaderCamera& camera, double fovDegrees, const std::string& file);

// Completes a header camera that has a pose and no projection, as applyFieldOfView does, with the
// field of view that puts the world positions of `gbuffer` (GBuffer::position, as loaded) on their
// pixel centres: least squares over the pixels, after dropping those more than a pixel (or three
// median residuals) off, which antialiased edges are. Named in HeaderCamera::attributes with its
// median residual. Throws Error(InvalidInput) naming `file`, --camera and --fov when the positions
// do not fit the pose (half of them behind it, or a median residual over half a pixel).
void fitFieldOfView(HeaderCamera& camera, const GBuffer& gbuffer, const std::string& file);

// Reads and checks every pass (half or float, any compression, single- or multi-part), as stored:
// depth and normals in the conventions `source` declares (applyInputConventions converts them).
// Throws Error(IoError) for unreadable files and Error(InvalidInput) for missing channels or
// mismatched sizes; the message starts with the file name and names the channel.
GBuffer loadGBuffer(const GBufferSource& source);

// Whether `file` holds every channel of the comma-separated `names` ("a|b": of one of the
// alternatives), found as loadGBuffer finds them (multi-part files included; a name several parts
// hold counts, loadGBuffer then refuses it naming them). Throws Error(IoError) naming the file
// when it is not a readable EXR.
bool holdsChannels(const std::string& file, const std::string& names);

// Turns the passes into the pipeline's conventions: planar depth (from radial depth, or from
// positions) and world-space normals. `camera` is the camera of the G-buffer's pixels (its data
// window). Pixels with no surface stay without one. Run it once: it converts what `source`
// declares, whatever the images already hold.
void applyInputConventions(GBuffer& gbuffer, const GBufferSource& source, const Camera& camera);

// The check run before tracing: normals derived from the depth (or positions) are compared,
// over the frame, with the normal pass read under the declared conventions and under the others
// (radial/planar depth, each normal space, one flipped axis). `gbuffer` is as loaded (not yet
// converted), `camera` that of its data window. Throws Error(InvalidInput) with a one-line
// message naming the pass and the option that fixes it when another reading explains the passes
// clearly better, or when none explains them (a camera that does not match). Returns the
// statistics otherwise.
struct ConventionFit {
  std::string depth, normals;   // a reading: depth ("planar", "radial", "position") and normals
  double meanAngleDegrees = 0;  // mean angle between pass normals and depth-derived normals
  // Against the declared reading, summed over the frame: how much closer the pass normals are to
  // this reading, as a share of how far apart the two readings put them (-1 .. 1; above 0.5 the
  // check prefers this reading).
  double score = 0;
};
struct InputCheckReport {
  ConventionFit declared;
  ConventionFit best;       // the smallest mean angle
  ConventionFit preferred;  // the reading the check prefers (the declared one when it passes)
  std::vector<ConventionFit> readings;  // every reading tried, the declared one included
  long long comparedPixels = 0;  // of the sampling grid (at most 65536 pixels) where both normals exist
};
InputCheckReport checkInputConventions(const GBuffer& gbuffer, const GBufferSource& source, const Camera& camera);

// Settles a header camera that HeaderCamera::reversed says could look either way, from the
// passes `gbuffer` holds as loaded: visible surfaces face the camera and lie in front of it, so
// world positions (when `source` names them) or world-space normals pick the reading under which
// most of the frame does. Clears `reversed`. Throws Error(InvalidInput) naming `file` when the
// frame does not decide it (camera-space normals and no positions, or no clear majority).
void orientHeaderCamera(HeaderCamera& camera, const GBuffer& gbuffer, const GBufferSource& source,
                        const std::string& file);

// Near = half the nearest surface in `planarDepth` (no surface lost), far = infinity (for an
// orthographic camera twice the farthest surface: its depth row has no infinite form); the
// projection's depth row is rebuilt to match (OpenGL layout).
void fitClipPlanes(Camera& camera, const Image& planarDepth);

// For clip planes a file gives: throws Error(InvalidInput) naming `cameraName` when a surface in
// `planarDepth` lies nearer than the near plane or beyond the far plane.
void checkClipPlanes(const Camera& camera, const Image& planarDepth, const std::string& cameraName);

// How many threads OpenEXR (de)compresses every EXR file with, in this whole process: 0 (the
// default) on the calling thread only. Chunks are independent, so files are the same bytes
// whatever the count; a program that owns its process sets its core count.
void setExrThreads(int count);

// Camera sidecar: {"view": 4x4 row-major world->camera, "projection": 4x4 row-major OpenGL clip,
// "width": W, "height": H, optional "near", "far"}. Validated; errors name the file and field.
Camera loadCameraJson(const std::string& path);
void saveCameraJson(const std::string& path, const Camera& camera);

// Writes the reflection pass (R,G,B,A from rgba, plus "distance") as float EXR with RLE
// compression (defaultExrCompression()), through a temporary file in the same directory renamed
// over `path`, so a failure leaves any existing file untouched. Throws Error(IoError).
// `windows` (data, display) are written as given, so an overscan or crop render's pass lines up
// with it; the data window must be the images' size. Default: both 0,0 - width-1,height-1.
struct ExrWindows {
  PixelBox data, display;
};
void writeReflectionExr(const std::string& path, const Image& rgba, const Image& distance,
                        const std::optional<ExrWindows>& windows = std::nullopt);

}  // namespace ssrcl
