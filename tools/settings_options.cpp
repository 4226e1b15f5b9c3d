#include "settings_options.hpp"

namespace ssrcl::cli {

TraceSettings SettingsOptions::resolve() const {
  TraceSettings s = qualityPreset(quality);
  auto apply = [](auto& field, const auto& value) {
    if (value) field = *value;
  };
  apply(s.maxRoughness, maxRoughness);
  if (thicknessModel) s.thicknessModel = *thicknessModel == "constant" ? ThicknessModel::Constant : ThicknessModel::Adaptive;
  if (thickness) {  // an explicit thickness is a constant one
    s.thicknessRelative = *thickness;
    s.thicknessModel = ThicknessModel::Constant;
  }
  apply(s.edgeFade, edgeFade);
  apply(s.viewRadianceCap, viewRadianceCap);
  apply(s.mirrorRoughness, mirrorRoughness);
  apply(s.linearStepPixels, linearStep);
  apply(s.samplesPerPixel, spp);
  apply(s.fullRaysRoughness, fullRaysRoughness);
  apply(s.reuseRadius, reuseRadius);
  apply(s.seed, seed);
  apply(s.prefilter, prefilter);
  apply(s.edgeColors, edgeColors);
  apply(s.denoise, denoise);
  apply(s.separableDenoise, separableDenoise);
  if (roughnessMapping)
    s.roughnessMapping = *roughnessMapping == "linear" ? RoughnessMapping::Linear : RoughnessMapping::Squared;
  if (tracer) selectTracer(s, *tracer);
  apply(s.maxIterations, maxIterations);
  apply(s.traceStride, traceStride);
  apply(s.environmentRotation, environmentRotation);
  apply(s.environmentIntensity, environmentIntensity);
  validateSettings(s);  // the library's ranges: a bad value fails before any frame is traced
  return s;
}

EnvironmentMap SettingsOptions::loadEnvironment() const {
  return environment.empty() ? EnvironmentMap{} : loadEnvironmentMap(environment);
}

void selectTracer(TraceSettings& s, const std::string& name) {
  s.tracer = name == "linear" ? Tracer::Linear : name == "dda" ? Tracer::DDA : Tracer::HiZ;
  // DDA and linear take their own cap (TraceSettings::maxIterations 0), not a Hi-Z preset's.
  if (s.tracer != Tracer::HiZ) s.maxIterations = 0;
}

void addSettingsOptions(CLI::App& cmd, SettingsOptions& o) {
  const char* q = "Quality";
  cmd.add_option("--quality", o.quality,
                 "Preset: draft, medium (Hi-Z, 4 rays, 5x5 reuse), high or reference (linear march, 256 rays)")
      ->group(q)
      ->capture_default_str()
      ->check(CLI::IsMember({"draft", "medium", "high", "reference"}));
  cmd.add_option("--spp", o.spp, "Rays per glossy pixel")->group(q);
  cmd.add_option("--full-rays-roughness", o.fullRaysRoughness,
                 "Ray counts follow roughness: --spp rays from this roughness up, fewer below (0 = off)")
      ->group(q);
  cmd.add_option("--seed", o.seed, "Seed of the sample sequence (same seed, same output)")->group(q);
  cmd.add_option("--tracer", o.tracer, "hiz (hierarchical), dda (every pixel crossed) or linear (fine steps)")
      ->group(q)
      ->check(CLI::IsMember({"hiz", "dda", "linear"}));
  cmd.add_option("--trace-stride", o.traceStride, "2: glossy rays in one pixel of each 2x2, the rest borrow")
      ->group(q);
  cmd.add_option("--linear-step", o.linearStep, "Step of the linear tracer, in pixels")
      ->group(q);
  cmd.add_option("--max-iterations", o.maxIterations,
                 "Traversal steps per ray (default: the preset's for hiz, unlimited for dda and linear)")
      ->group(q);
  cmd.add_option("--reuse-radius", o.reuseRadius, "Resolve reuses rays of (2r+1)^2 neighbours; 0 = own rays only")
      ->group(q);
  cmd.add_flag_callback(
         "--prefilter", [&o] { o.prefilter = true; }, "Rough hits read a colour mip matched to the ray's cone")
      ->group(q);
  cmd.add_flag_callback(
         "--no-prefilter", [&o] { o.prefilter = false; }, "Rough hits read full-resolution colour")
      ->group(q);
  cmd.add_flag_callback(
         "--edge-colors", [&o] { o.edgeColors = true; },
         "Hits beside a nearer object's edge read the surface behind it, not the antialiased mix")
      ->group(q);
  cmd.add_flag_callback(
         "--no-edge-colors", [&o] { o.edgeColors = false; }, "Every hit reads the colour pass as written")
      ->group(q);
  cmd.add_flag_callback(
         "--denoise", [&o] { o.denoise = true; }, "Edge-aware spatial filter after the resolve")
      ->group(q);
  cmd.add_flag_callback(
         "--no-denoise", [&o] { o.denoise = false; }, "No spatial filter")
      ->group(q);
  cmd.add_flag_callback(
         "--separable-denoise", [&o] { o.separableDenoise = true; },
         "The filter in two passes, along y then x (draft's; a fraction of the square's taps)")
      ->group(q);
  cmd.add_flag_callback(
         "--square-denoise", [&o] { o.separableDenoise = false; }, "The filter over the square of taps")
      ->group(q);

  const char* m = "Surfaces";
  cmd.add_option("--max-roughness", o.maxRoughness, "Pixels rougher than this get no ray (A = 0)")
      ->group(m);
  cmd.add_option("--mirror-roughness", o.mirrorRoughness, "At or below: one exact mirror ray per pixel")
      ->group(m);
  cmd.add_option("--roughness-mapping", o.roughnessMapping,
                 "GGX alpha = roughness^2 (squared, Cycles) or roughness (linear)")
      ->group(m)
      ->check(CLI::IsMember({"squared", "linear"}));
  auto* model = cmd.add_option("--thickness-model", o.thicknessModel,
                 "adaptive (from each surface's visible extent, the default) or constant (--thickness of depth)")
      ->group(m)
      ->check(CLI::IsMember({"adaptive", "constant"}));
  cmd.add_option("--thickness", o.thickness,
                 "Constant surface thickness relative to depth (e.g. 0.005); implies --thickness-model constant")
      ->group(m)
      ->excludes(model);
  cmd.add_option("--edge-fade", o.edgeFade,
                 "Fraction of the screen over which A fades at its edges (default 0: no fade)")
      ->group(m);
  cmd.add_option("--view-radiance-cap", o.viewRadianceCap,
                 "Hits found in views or neighbouring frames keep at most this many times the frame's 99th "
                 "percentile of brightness (0: no cap; default 2, and 2 sqrt(2K + 1) in a batch that blends K "
                 "frames on each side)")
      ->group(m);

  const char* e = "Environment";
  auto* env = cmd.add_option("--environment", o.environment,
                             "Equirectangular HDR EXR (Blender's world mapping): the part of each lobe not found "
                             "on screen (1 - A) takes its radiance, so RGB is the complete reflection")
                  ->group(e);
  cmd.add_option("--environment-rotation", o.environmentRotation,
                 "Degrees the environment turns about world +Z (Blender: a Mapping node's Rotation Z)")
      ->group(e)
      ->needs(env);
  cmd.add_option("--environment-intensity", o.environmentIntensity,
                 "Factor on the environment's radiance (Blender: the Background's Strength)")
      ->group(e)
      ->needs(env);
}

}  // namespace ssrcl::cli
