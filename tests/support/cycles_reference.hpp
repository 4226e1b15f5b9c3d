#pragma once
// Cycles' path-traced answer for the reflecting surfaces of a Blender render (samples/blender,
// samples/corpus), in the units of our reflection pass. Cycles' Glossy Direct + Indirect on a
// metal of F0 = `specular` is
//   E(o, alpha, F0 = specular) * (lobe-weighted mean incident radiance),
// E being ssrcl::specularAlbedo (Cycles 3.4's GGX with its Fresnel, separable Smith), while our pass
// holds that mean times the found fraction A and nothing for the rest. The renders make whatever
// lies off screen black to glossy rays, so the rest is black there too and every pixel compares.
#include <string>
#include <utility>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"
#include "ssrcl/io.hpp"

namespace ssrcl::test {

struct CyclesReference {
  GBuffer gbuffer;  // as `ssrcl trace` reads it: base and specular from the glossy passes
  Camera camera;
  std::vector<int> pixels;     // the reflector's pixel indices (see loadCyclesReference)
  std::vector<double> scale;   // per pixel: E(F0 = specular), what turns our rgb into Cycles'
  std::vector<double> cycles;  // per pixel, 3 channels: GlossDir + GlossInd
  double peak = 0;             // 99.9th percentile of those channels: the PSNR peak
  // "all" first; for renders without an object index, then each roughness of more than 1000
  // pixels ("r=0.2500").
  std::vector<std::pair<std::string, std::vector<size_t>>> groups;
};

// Reads the render and its camera sidecar (<stem>.camera.json beside it unless given). The
// reflector is the pixels of object index 1 (IndexOB pass) where the render has one; else the
// bundled samples' floor: upward normal, roughness below 0.9, Cycles' glossy colour 1.
CyclesReference loadCyclesReference(const std::string& exr, const std::string& cameraJson = {},
                                    double specular = 1.0);

// `gbuffer` with the render's Principled material AOVs added (Blender's base_color colour and
// metallic value, the names `ssrcl trace --output-form glossy-pass` reads by default). Throws
// ssrcl::Error naming the channel where the render has none.
GBuffer withMaterialAovs(GBuffer gbuffer, const std::string& exr);

// The reflection pass (incident form) of the render's G-buffer g at a quality preset, on a device
// of its own (it builds the programs the environment's SSRCL_KERNEL_BUILD_OPTIONS asks for).
Image traceRender(const GBuffer& g, const Camera& camera, const std::string& preset = "medium");

// Error of E * our rgb against Cycles over a group of reference pixels.
struct ReferenceError {
  double rmse = 0, meanAbs = 0;
  double bias = 0;             // mean of (ours - Cycles): negative where the pass is too dark
  double psnr = 0;             // dB, peak = ref.peak
  double lowConfidence = 0;    // share of the squared error on pixels with A < 0.5
  double p99 = 0;              // 99th percentile of per-pixel mean |error|, relative to the peak
  // Share of the group's pixels whose mean |error| exceeds 4x Cycles' local mean (over the
  // reflector pixels of the 7x7 window around it) and 1% of the peak: speckle and fireflies, which
  // a smooth error (a blur, a dim pass) does not count.
  double fireflies = 0;
};
ReferenceError referenceError(const CyclesReference& ref, const Image& reflection, const std::vector<size_t>& group);

// Blender EEVEE's SSR from <scene>.eevee.exr: its Specular Light pass (GlossDir), the same quantity
// as our pass with A = 1 wherever it rendered; withColor: times its Specular Color (GlossCol), which
// holds the Fresnel as Cycles' glossy passes do (compare with Cycles unscaled).
Image eeveeSpecular(const std::string& path, bool withColor);

}  // namespace ssrcl::test
