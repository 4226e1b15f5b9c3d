#pragma once
// Temporal reuse over a shot: a frame's reflection pass averaged with its neighbours' (frames
// before and after, each traced alone with its own seed), each neighbour read where it shows the
// same reflection. An offline tool has every frame's exact camera and depth, so the reuse is a
// reprojection, not a guess from motion vectors.
//
// Where a neighbour shows the same reflection: the reflected point (the hit's mirror image
// behind the reflector, at the pass's hit distance along the viewing ray: fixed in the world for
// a planar reflector, whichever camera looks) is projected into the neighbour. Each of the four
// pixels around it is taken when it lies on the frame pixel's tangent plane, its normal is within
// maxNormalDegrees, and its own hit distance matches the distance from it to the reflected point;
// and refused when the frame's hit, seen from the neighbour, is in front of what the neighbour
// shows there (the object has moved), where the frame itself shows the hit (a hit on no surface,
// or off the screen, stands in front of what the frame shows as well). A tap taken weighs its
// bilinear share times its frame's weight: the frames lie in shot order one apart, and frame j
// weighs 1 - |j - centre| / (R + 1), R the window's longer side (the frame itself 1). Both tests
// widen with roughness: a rough lobe's hit distance is a mean over hits spread across the lobe,
// which moves with the view, and its hit (taken along the lobe's centre) need not lie on a surface.
// Geometry cannot see a light that changes over the window: a tap is also refused where the
// neighbour's radiance around it (the mean of a 5x5 neighbourhood) differs from the frame's own
// around the pixel by more than noise and a ratio allow. The noise is the smaller of the two
// neighbourhoods' spreads: a light's change scales the texture's spread with it, which would
// otherwise hide the change on a textured reflection. The ratio: a camera move's views of one
// reflection disagree locally by up to 2x beyond their noise (the view-dependent errors that the
// blend averages away), so a light that changes by less is averaged too.
// Pixels whose rays found nothing (hit distance 0) keep their own pass, and a neighbour's such
// pixels are never taken: a miss holds the environment's lookup for its own normal (or nothing),
// which has no noise to average, and a neighbour's is another normal's (a rippled surface, a
// pixel mixing two surfaces).
#include <memory>
#include <optional>
#include <vector>

#include "ssrcl/camera.hpp"
#include "ssrcl/image.hpp"

namespace ssrcl {

// What the blend derives from a frame alone (its pixels' neighbourhood radiance statistics, their
// world points and normals, its camera's inverse; 96 bytes a pixel): computed once per frame by
// temporalFrameStatistics and shared by every window that holds the frame, instead of once per
// window (2K + 1 times for `--temporal K`).
struct TemporalFrameStatistics;

// One traced frame of the window: its pipeline outputs and G-buffer (same size), not owned.
struct TemporalFrame {
  const Image* reflection = nullptr;  // 4 channels, the pipeline's "reflection" (incident form)
  const Image* distance = nullptr;    // 1 channel, the pipeline's "distance" (0: no hit)
  const Image* depth = nullptr;       // 1 channel, planar view depth (as Pipeline reads it)
  const Image* normal = nullptr;      // 3 channels, world space
  const Image* roughness = nullptr;   // 1 channel; nullptr: constantRoughness
  Camera camera;
  // temporalFrameStatistics of this very frame (its reflection, depth and camera), or empty:
  // temporalBlend then computes them for this call.
  std::shared_ptr<const TemporalFrameStatistics> statistics;
};

struct TemporalSettings {
  float planeTolerance = 0.02f;    // off the tangent plane by more than this share of depth: refused
  float maxNormalDegrees = 45.0f;  // normals further apart: refused
  float distanceTolerance = 0.2f;  // hit distance off by more than this share: refused
  float movedTolerance = 0.02f;    // the hit this share of depth in front of the neighbour's surface: moved
  // Both tests widen by this times roughness times the hit distance: measured on Cycles shots
  // (docs/BENCHMARKS.md "Shots"), a rough floor's hit distance is off by more than 20% between
  // views for most of its pixels, and its hit lies in front of the surface the neighbour shows.
  float roughnessSpread = 2.0f;
  // Radiance test: refused where a colour channel's neighbourhood means differ by more than
  // radianceSigmas times sqrt(2 x the smaller of their variances) plus radianceShare of the larger
  // mean. Measured on Cycles shots (docs/BENCHMARKS.md "Shots"): a share of 0.1 refused much of
  // what the blend gains on living_truck; 1.5 sigmas, not 3, keeps the analytic light switch out.
  float radianceSigmas = 1.5f;
  float radianceShare = 0.5f;
  float mirrorRoughness = 0.02f;           // pixels at or below keep their own pass (sharp, no noise)
  std::optional<float> constantRoughness;  // every pixel's roughness where frames have no image
};
// Throws Error(InvalidArgument) naming the first setting out of range.
void validateTemporalSettings(const TemporalSettings& settings);

// A frame's statistics for temporalBlend (TemporalFrame::statistics). Throws
// Error(InvalidArgument) where its reflection, depth or normal is missing or of another size than its camera.
std::shared_ptr<const TemporalFrameStatistics> temporalFrameStatistics(const TemporalFrame& frame);

// The reflection of frames[centre] blended with the other frames: per pixel with a hit, the
// weighted mean of its own pass (weight 1) and every neighbour's accepted pixels (bilinear weight
// times the distance-mismatch weight). Same inputs, same output, whatever the thread count and whether the
// frames' statistics were given. Throws Error(InvalidArgument) for frames of different sizes or
// missing images, or statistics of another size.
Image temporalBlend(const std::vector<TemporalFrame>& frames, size_t centre, const TemporalSettings& settings);

}  // namespace ssrcl
