#pragma once
// Temporal error of a reflection pass over a shot, against path-traced references of every frame
// (bench/score_shots, tests/shot_metric_test): how much the pass's error changes from frame to
// frame along the surface. Each reflector pixel of frame t is reprojected into frame t-1 with its
// exact depth and both cameras (nearest pixel: the same pixel of both images, so their noise is
// compared as it is); pixels that land off the reflector, off its tangent plane or on a normal
// turned away (disoccluded) are left out. With O the pass, R the reference and ' reprojected:
//   TE = RMS over channels and pixels of (O_t - O'_{t-1}) - (R_t - R'_{t-1})
//   tPSNR = 20 log10(peak_t / TE)
// A noise-free exact answer leaves TE = the references' own noise, sqrt(2) sigma, which two
// renders of one frame with different seeds measure (noiseFloor).
#include <vector>

#include "support/cycles_reference.hpp"

namespace ssrcl::test {

struct TemporalError {
  double te = 0;      // RMS, in the references' units
  double tpsnr = 0;   // dB, peak = the current frame's
  size_t pixels = 0;  // reflector pixels of frame t found in frame t-1
};

// `prev` / `cur`: references of frames t-1 and t (compare with their glossy passes as they are:
// the passes' scale is not applied); `passPrev` / `passCur`: the passes, RGB(A) per pixel.
// `perPixel`, if given: each pixel of frame t's squared error summed over the channels, NaN for
// pixels left out (where that error is, bench/score_shots --breakdown).
TemporalError temporalError(const CyclesReference& prev, const Image& passPrev, const CyclesReference& cur,
                            const Image& passCur, std::vector<double>* perPixel = nullptr);

// tPSNR of a noise-free exact answer: RMS of the difference of two references of one frame
// (another seed), over the pixels both call reflector, against a's peak.
TemporalError noiseFloor(const CyclesReference& a, const CyclesReference& b);

// RGBA of a pass `ssrcl trace` or `ssrcl batch` wrote (R, G, B, A channels).
Image readReflectionPass(const std::string& path);

}  // namespace ssrcl::test
