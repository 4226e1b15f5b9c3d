#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/device.hpp"
#include "ssrcl/environment.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl {

enum class Tracer {
  HiZ,     // hierarchical min-depth traversal (default)
  Linear,  // fixed sub-pixel steps; slow, the most thorough
  DDA,     // every pixel the ray crosses, in order (McGuire and Mara 2014)
};

// How far behind a pixel's surface a ray may pass and still hit it (see thicknessRelative).
enum class ThicknessModel {
  Adaptive,  // per pixel, from the visible extent of its surface (kernels/thickness.cl)
  Constant,  // thicknessRelative of every pixel's depth
};

enum class RoughnessMapping {
  Squared,  // GGX alpha = roughness^2 (Cycles, EEVEE, Unreal, most renderers)
  Linear,   // alpha = roughness
};

// Reflection-pass settings. Distances are in view-space units unless stated.
//
// What the pass estimates for a pixel with view direction o, normal n and GGX alpha:
//   rgb = integral of f(o,l) (n.l) L(l) V(l) dl / integral of f(o,l) (n.l) dl
//   A   = integral of f(o,l) (n.l) V(l) dl / integral of f(o,l) (n.l) dl
// with f = D G2 / (4 (n.o)(n.l)) (GGX, height-correlated Smith, no Fresnel) and V(l) = 1 where
// the reflected ray finds a surface on screen (times the screen-edge fade). So rgb is incident
// radiance averaged over the specular lobe, premultiplied by the found fraction A, and
// `rgb + environment * (1 - A)` completes it. Mirror pixels are the limit alpha -> 0.
struct TraceSettings {
  // Each pixel's surface is the plane through its point with its normal; rays crossing it hit.
  // A ray already behind a surface where it reaches it (at a silhouette) still hits when it is
  // less than the surface's thickness behind it along the viewing line. Thicker: fewer holes, more
  // streaks; thinner: the reverse. Adaptive: thicknessScale times the chord a round object would
  // have through the pixel, from its unbroken runs of surface along the row and the column (flat
  // runs count as thin slabs; kernels/thickness.cl), kept within [thicknessMinRelative,
  // thicknessMaxRelative] of its depth. Constant: thicknessRelative of its depth (0.002 = 0.2%).
  // Adaptive is the default: on the Cycles corpus it beats every constant (docs/BENCHMARKS.md,
  // "Thickness").
  ThicknessModel thicknessModel = ThicknessModel::Adaptive;
  float thicknessRelative = 0.002f;
  float thicknessScale = 0.75f;
  // Flat runs (slabs seen face-on) get the minimum. The tuning scenes cannot tell 1% from 0.2%;
  // 1% was picked with the held-out scores in view, so those do not check it independently
  // (docs/BENCHMARKS.md, "Thickness").
  float thicknessMinRelative = 0.01f;
  float thicknessMaxRelative = 0.08f;
  // Traversal steps per ray before it gives up; 0: the tracer's own, 512 for Hi-Z and unlimited
  // (2^20) for DDA and linear, which visit every pixel on the way.
  int maxIterations = 0;
  float maxRoughness = 1.0f;        // pixels rougher than this get no ray and A = 0
  // Fraction of the screen's smaller side over which A fades out toward its edges. 0 by default:
  // a hit there is as right as anywhere, and fading it took 0.5-0.9 dB off both corpora's means
  // (docs/BENCHMARKS.md, the edge fade); a fade softens the seam where a fill takes over.
  float edgeFade = 0.0f;
  // Hits auxiliary views find (Pipeline::setView) keep a mean rgb of at most this many times the
  // frame's 99th percentile; 0: no cap. A lamp only a view shows, met by a few rays of a lobe's
  // tail, is speckle that costs more than its light (wide_corridor: 28.82 dB capped at 2, 28.66
  // without). `ssrcl batch --temporal K` raises it to 2 sqrt(2K + 1): the blend averages as many
  // frames, which shrinks a rare hit's speckle by their square root but not the cap's loss of
  // light (docs/BENCHMARKS.md "The views' cap under the blend").
  float viewRadianceCap = 2.0f;
  // Set (in [0, 1]): every pixel has this roughness and no roughness image is read. Unset: the
  // "roughness" image gives each pixel's.
  std::optional<float> constantRoughness;

  // Hits on pixels smoother than this are hits on glossy surfaces, whose screen colour is what
  // they reflect toward the camera. With the "base" and "specular" images set, such a hit's
  // radiance is base + specular * (what one more ray reflected at the hit finds), the screen colour
  // where that ray leaves the screen; without them, or at 0, hits take the screen colour. With
  // material images too ("f0", or "base_color" and "metallic"), what that ray finds is weighted
  // by the hit's Fresnel, E(its F0, its roughness, toward the reflecting pixel) (specular_albedo.hpp),
  // as Cycles' GlossCol (about 1) leaves it out; where the ray finds nothing the guess is the
  // glossy light the camera sees there times E(toward the pixel) / E(toward the camera), at
  // most 1 (docs/BENCHMARKS.md, "Hits on glossy surfaces").
  // 1 = every hit that is not fully rough: any glossy component is view-dependent, whatever its
  // roughness.
  float glossyHitRoughness = 1.0f;

  int samplesPerPixel = 4;  // rays per glossy pixel
  // > 0: ray counts follow roughness. Glossy pixels at or above this roughness get samplesPerPixel
  // rays, smoother ones proportionally fewer (at least 1): narrow lobes see a small part of the
  // scene and their neighbours' reused rays cover it. 0: every glossy pixel gets samplesPerPixel.
  float fullRaysRoughness = 0.0f;
  uint32_t seed = 0;  // same inputs and seed, same output (on one device)
  RoughnessMapping roughnessMapping = RoughnessMapping::Squared;
  float mirrorRoughness = 0.02f;  // at or below: one deterministic mirror ray, no reuse
  int reuseRadius = 2;            // resolve reuses rays of (2r+1)^2 neighbours (Stachowiak); 0 = own only
  // Rough hits read a colour mip matched to the ray's share of the lobe: small bright emitters
  // then light many rays a little instead of a few rays a lot (speckle). Its texels are weighted
  // by where the batch's hits land, which keeps the pass's mean that of full-resolution hits
  // (docs/BENCHMARKS.md, "Speckle").
  bool prefilter = true;
  // A hit on a pixel beside a nearer object's edge reads the light of the surface behind it (held
  // within the pixels wholly on that surface), not the colour pass's antialiased mix with the
  // object's: rays that pass behind a lamp to the wall beside it took the lamp's light
  // (docs/BENCHMARKS.md, "Edge colours"). False: every hit reads the colour pass as written.
  bool edgeColors = true;
  Tracer tracer = Tracer::HiZ;
  float linearStepPixels = 0.5f;  // Tracer::Linear step along the ray's major screen axis
  // Edge-aware spatial filter after the resolve (the resolve then takes a quarter of each
  // neighbour's rays). On in every preset but "reference": it gains on both corpora, procedural
  // and real (docs/BENCHMARKS.md, "Quality presets").
  bool denoise = true;
  // The filter as two passes, along y then along x (2r + 1 taps a pass against the square's
  // (2r + 1)^2): draft's, where the filter was 60% of a 1080p frame's device time; within 0.03 dB
  // of the square on both corpora (docs/BENCHMARKS.md, "A separable filter for draft").
  bool separableDenoise = false;
  // 2: glossy pixels trace in one pixel of each 2x2 block (a quarter of the rays) and the others
  // resolve from their neighbours' rays (needs reuseRadius >= 1). Mirror pixels always trace.
  int traceStride = 1;
  bool countWork = false;  // count texel reads and iterations per ray (StageTimes); slower
  // Rays are dispatched for the pixels that reflect only, and the resolve for the 8x8 tiles that
  // hold one: sky and pixels above maxRoughness cost nothing past setup. false dispatches every
  // pixel and tile (the others exit at once), the same output: the baseline for benchmarks.
  bool classifyWork = true;

  // With an environment set (Pipeline::setEnvironment): degrees the environment turns about world
  // +Z (a Mapping node's Rotation Z in front of Blender's Environment Texture), and the factor its
  // radiance is scaled by (the world Background's Strength).
  float environmentRotation = 0.0f;
  float environmentIntensity = 1.0f;
};
// Throws Error(InvalidArgument) naming the first parameter out of its range (commit() does too).
void validateSettings(const TraceSettings& settings);

// Field by field (a new field joins them in host/pipeline/settings_validation.cpp).
bool operator==(const TraceSettings& a, const TraceSettings& b);
bool operator!=(const TraceSettings& a, const TraceSettings& b);

// Every field of `settings` under its C++ name, in declaration order, as one line of JSON (enums
// by their option names, floats as their shortest decimal): what `ssrcl trace` records in an
// output's ssrcl/settings attribute (a field added to TraceSettings joins it in settings_json.cpp).
std::string settingsJson(const TraceSettings& settings);

// Named bundles of the settings above (all with the adaptive thickness and prefiltered hits):
//   "draft"     Hi-Z, 2 rays in one pixel of each 2x2 block, 5x5 reuse, 64 iterations, filter.
//   "medium"    (the default TraceSettings) Hi-Z, 4 rays, 5x5 ray reuse, edge-aware filter.
//   "high"      Hi-Z, 16 rays, 5x5 ray reuse, edge-aware filter.
// (With the filter the resolve takes a quarter of each neighbour's rays.)
//   "reference" Linear march at half-pixel steps, 256 rays per pixel, no reuse, no filter: the
//               best answer screen-space information allows, the yardstick.
// Their accuracy against Cycles and their cost: docs/BENCHMARKS.md.
// Throws Error(InvalidArgument) for an unknown name.
TraceSettings qualityPreset(const std::string& name);

// Per-stage device time of the last execute(), from OpenCL profiling events (milliseconds).
struct StageTimes {
  // "upload", "setup", "hzb", "color_mips", "trace", "resolve", "environment", "download"
  std::map<std::string, double> ms;
  long long tracedPixels = 0;   // pixels that got rays (not sky, not above max roughness)
  long long tracedRays = 0;     // rays: one per mirror-like pixel, samplesPerPixel (or fewer) per glossy one
  long long resolvedTiles = 0;  // 8x8 tiles the resolve ran on (those holding a pixel that reflects)
  // With TraceSettings::countWork: depth-buffer texels read by all rays, and how many rays took
  // 0, 1, 2-3, 4-7, ... traversal iterations (bin b counts [2^(b-1), 2^b)).
  long long depthFetches = 0;
  std::vector<long long> iterationHistogram;
};

// When an auxiliary view (Pipeline::setView) was rendered: at the frame's moment (Same: a
// wide or reverse render of the same frame, or of a static scene), or at another one (Other: a
// neighbouring frame of the shot, for static geometry). A hit found in an Other view is not taken
// where the frame shows that it has moved: reprojected into the frame, it lies in front of
// every surface the frame shows within a pixel of there (by more than 2% of their depth), so the
// frame would see it if it were still there. Hits outside the frame or hidden behind its surfaces
// are taken (nothing there tells); Same views take every hit.
enum class ViewTime { Same, Other };

// The SSR pipeline, shaped like an OIDN filter:
//   Pipeline p(device);
//   p.setImage("color", img); p.setImage("depth", d); p.setImage("normal", n); p.setImage("roughness", r);
//   p.setCamera(cam); p.settings() = {...};
//   p.commit();   // validates, compiles kernels once per device, allocates
//   p.execute();  // runs setup, HZB, trace, resolve
//   const Image& out = p.output("reflection");  // RGBA premultiplied, A = confidence
//   const Image& dist = p.output("distance");   // view-space hit distance, 0 where no hit
//   const Image& v = p.output("view");          // with views: 2 channels, (source, views' share)
//     source: which source supplied most of the pixel's found weight, 0 the frame itself, k its
//     k-th view (setView index + 1), -1 none; share: the fraction of A found in views
// Input images: color 3 or 4 channels (only RGB used), depth 1 (planar view depth, values beyond
// the far plane or not finite mean "no surface"), normal 3 (world space), roughness 1 (not read
// when settings().constantRoughness is set). Optional, together: base 3 (each pixel's radiance
// without its specular reflection, e.g. Combined minus Glossy) and specular 3 (its specular
// colour), for hits on glossy surfaces (TraceSettings::glossyHitRoughness); with them, the
// material: f0 3 (specular colour at normal incidence, clamped to [0, 1]) or, together,
// base_color 3 and metallic 1 (Principled's, F0 = mix(0.04, base colour, metallic)).
//
// Images set after commit() with the committed size and channels are read by the next execute()
// without another commit (OIDN's way): a sequence sets each frame's images and executes. Another
// size, an input added or removed, or a new camera needs commit(), which reuses the buffers of the
// last one where the sizes allow. Settings changed after commit() are validated again (and buffers
// replanned) by execute().
class Pipeline {
 public:
  static constexpr int kMaxViews = 16;  // auxiliary views (setView)
  explicit Pipeline(const Device& device);
  ~Pipeline();
  Pipeline(Pipeline&&) noexcept;
  Pipeline& operator=(Pipeline&&) noexcept;

  // The image is copied at execute time; it must stay alive until then.
  void setImage(const std::string& name, const Image& image);
  // The same from caller-owned memory of any layout (float or half, strides), read at execute.
  void setImage(const std::string& name, const ImageView& view);
  // Caller-owned memory that execute() writes the output ("reflection": 4 channels, "distance": 1)
  // into, in its layout; output(name) keeps working as well.
  void setOutput(const std::string& name, const ImageView& view);
  // Every pass of a loaded G-buffer, same lifetime rule; the optional ones it lacks (roughness,
  // material, back-face depth) are unset, so set any of those by setImage after it.
  void setGBuffer(const GBuffer& gbuffer);
  void setCamera(const Camera& camera);
  // Auxiliary view `index` (0, 1, ...; index viewCount() adds one, at most kMaxViews): another G-buffer
  // of the same scene (color, planar depth and world normals as above, roughness optional: none
  // means no glossy pixels) seen by its own camera, of any size. Rays the frame leaves unresolved
  // (misses, hits faded at its edge, hits found after passing behind a surface the frame shows)
  // continue in up to 3 views, those that hold the ray's origin and that it heads into first,
  // traced the same way against each view's own depth; the hit's colour is the view's. A is then
  // the fraction of the lobe found in any view, and output("view") says where (see there).
  // `label` names the view in messages (e.g. its file); `time` says when it was rendered (ViewTime).
  // The G-buffer must stay alive while it is a view (until it is replaced or the views cleared):
  // every commit() checks its shape, and a commit that configures or reallocates the stages
  // uploads it again; otherwise later executes (other frames, through commits that keep the
  // settings and sizes) reuse what the view uploaded, so setView again after changing its pixels.
  // Replacing view k leaves the others' device images as they are.
  void setView(int index, const GBuffer& gbuffer, const Camera& camera, const std::string& label = {},
               ViewTime time = ViewTime::Same);
  void clearViews();
  int viewCount() const;
  TraceSettings& settings();
  // Environment fill: the part of each pixel's lobe not found on screen (1 - A, the edge fade
  // included) takes the environment's radiance filtered for the lobe, so "reflection" RGB is
  // the complete reflection; A still reports the screen-space fraction. Every pixel with a surface
  // facing the camera is filled, those above maxRoughness (A = 0) included. An empty map turns it
  // off. The map must stay alive until execute().
  void setEnvironment(const EnvironmentMap& environment);

  // Called during execute() with the fraction done (0..1); returning false cancels it: execute()
  // then throws Error(Cancelled) and the outputs keep their previous content.
  using ProgressMonitor = std::function<bool(double fraction)>;
  void setProgressMonitor(ProgressMonitor monitor);

  void commit();
  // Throws Error(InvalidOperation) before commit(), after the camera, an output or the environment
  // changed since, or when an input was set, removed or resized since (naming it).
  void execute();

  const Image& output(const std::string& name) const;
  const StageTimes& stageTimes() const;
  // Device memory the committed pipeline holds, in bytes (inputs, pyramids, ray records, outputs).
  size_t deviceBytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ssrcl
