#pragma once
// A double-precision CPU implementation of the mirror trace, for differential tests of the OpenCL
// kernels. Written from the semantics kernels/trace.cl and kernels/setup.cl document, not from
// their code (no float, no Hi-Z, no shared helpers):
//
//   * A pixel has a surface where its depth is finite, within [near, far] and below 1e10 (Cycles'
//     background); its surface is the plane through the point on the pixel centre's viewing line
//     at that planar depth, with the pixel's normal taken to view space (inverse transpose of the
//     view matrix) and normalised. Zero or non-finite normals, and normals facing away from the
//     viewer, give the pixel no ray.
//   * The ray is the exact mirror direction from that point. Its segment ends on the near plane
//     (times 1.001) for rays toward the camera, on the far plane for rays away from it, and is
//     never longer than 1e6 times the pixel's depth; it is followed in screen space, clipped to
//     the screen, with its 3D point at each screen position interpolated perspective-correctly.
//     A segment with an end behind the camera is not traced.
//   * Leaving its own pixel first, the ray is tested against each pixel's plane over the stretch
//     of the ray assigned to that pixel: it hits where it crosses the plane from the front, or
//     where it is behind the plane by at most thickness * that pixel's depth along its viewing
//     line (along the normal: that times |n . v|, v the pixel centre's viewing direction) at the
//     start of the stretch; planes facing away from the ray (n . dir >= 0) are never hit, sky
//     pixels never. Where a back-face depth b is given and lies beyond the pixel's depth, the
//     bound along the normal is instead the distance behind the plane of the point at planar
//     depth b on the pixel centre's viewing line.
//   * A ray that hits nothing but passed behind such a pixel's plane within the constant's bound
//     (facing it, not hit, behind it at the end of the pixel's stretch and by at most the
//     constant's bound at its start) takes the first such pixel instead, at the start of its
//     stretch there: the constant's hit (kernels/trace.cl SSRCL_BACK_KNOWN).
//   * Stretches: EveryPixel gives each pixel the ray crosses exactly its own stretch, in order
//     (the limit of infinitely fine linear steps); Linear takes fixed steps of `linearStepPixels`
//     along the major screen axis and tests each step against the pixel it ends in, as the
//     kernel's reference tracer documents.
#include <glm/vec3.hpp>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"

namespace ssrcl::test {

struct CpuTraceOptions {
  enum class Stepping { EveryPixel, Linear };
  Stepping stepping = Stepping::EveryPixel;
  double linearStepPixels = 0.5;
  double thicknessRelative = 0.002;  // TraceSettings::thicknessRelative (ThicknessModel::Constant)
  const Image* backDepth = nullptr;  // planar back-face depth (GBuffer::backDepth), or none
};

struct CpuRay {
  bool traced = false;  // the pixel has a surface and a usable normal facing the viewer
  bool hit = false;
  bool pastBack = false;  // the hit is a passage behind a known back, within the constant's bound
  bool enteredBack = false;                // the hit is where the ray entered a surface through its back
  int hitX = -1, hitY = -1;                // the pixel whose plane was hit
  glm::dvec3 origin{0.0}, direction{0.0};  // view space
  glm::dvec3 hitPoint{0.0};
  double distance = 0.0;  // |hitPoint - origin|
};

// One mirror ray per pixel (row-major, y = 0 the top row), from the G-buffer as the pipeline gets
// it: planar depth and world-space normals.
std::vector<CpuRay> cpuMirrorTrace(const Camera& camera, const Image& depth, const Image& normal,
                                   const CpuTraceOptions& options = {});

}  // namespace ssrcl::test
