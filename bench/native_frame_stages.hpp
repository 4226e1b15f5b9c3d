#pragma once
// The frame's stages around the trace in native C++, the kernels' float arithmetic on
// std::threads (row loops cloned for AVX-512 / AVX2): the adaptive thickness model
// (kernels/thickness.cl), the range pyramid (kernels/back_pyramid.cl) and the colour pyramid's
// reduction (kernels/color_pyramid.cl). NativeMirrorTrace::runFrame runs them on its setup's
// output; bench/ssrcl_roofline sets the OpenCL stages against them.
#include <glm/glm.hpp>
#include <vector>

#include "packet_hiz_trace.hpp"  // HzbLevel

namespace ssrcl::bench {

// The stages before the trace, milliseconds (native here, OpenCL in bench/device_frame_stages).
struct FrameStageMs {
  double setup = 0, hzb = 0, thickness = 0, rangePyramid = 0, colorPyramid = 0;
};

// TraceSettings' thicknessScale, thicknessMinRelative, thicknessMaxRelative.
struct AdaptiveThickness {
  float scale, minRel, maxRel;
};

// surface_thickness over the rows (each pixel's row run and chord into rowRuns), then the
// columns: rescales each surface pixel's plane (positions: view-space point, planar depth in w).
void adaptiveThickness(int width, int height, const glm::vec4* positions, glm::vec4* planes, glm::vec2* rowRuns,
                       AdaptiveThickness model, int threads);
// back_level0 from the HZB's level 0 and the final planes, then range_reduce down the levels.
void buildRangePyramid(const std::vector<HzbLevel>& levels, const glm::mat4& invProj, const float* hzb,
                  const glm::vec4* planes, glm::vec2* range, int threads);
// color_reduce over levels 1.. of a pyramid whose level 0 setup wrote (colour, weight).
void reduceColorPyramid(const std::vector<HzbLevel>& levels, glm::vec4* pyramid, int threads);

}  // namespace ssrcl::bench
