#pragma once
// Where a pass's temporal error lies (ssrcl_score_shots --breakdown): the pooled TE of every pair
// of a shot split by what each pixel of frame t shows in the medium pass (a hit, or a miss the
// environment fills), whether it lies in the band along the frame's edges (rays that leave the
// screen; each side's part of it too), and, for a blended pass, whether the blend took no neighbour there (the pass
// equals the frame traced alone with the same seed). Each class also gets the references' own change along the surface
// (their noise, and what truly changes: the TE a pass of zeros would have) and the pass's own change (its TE against
// references of zeros).
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "ssrcl/image.hpp"
#include "support/cycles_reference.hpp"

namespace ssrcl::bench {

// Per frame, per pixel: kMiss where the medium pass has no hit, kEdge in the edge band, and which
// of its sides (a corner is in two).
enum PixelClass : uint8_t { kMiss = 1, kEdge = 2, kLeft = 4, kRight = 8, kTop = 16, kBottom = 32 };
std::vector<std::vector<uint8_t>> classifyPixels(const std::vector<std::string>& mediumPasses);

// One line per class: share of the pixels, share of TE^2, tPSNR of the pass over those pixels,
// of the references' own change there and of the pass's own change. `alone`: the frames traced alone (nullptr: no
// "unblended" class).
void printBreakdown(std::ostream& out, const std::string& label, const std::vector<test::CyclesReference>& refs,
                    const std::vector<Image>& passes, const std::vector<std::vector<uint8_t>>& classes,
                    const std::vector<Image>* alone);

// Frame t of a shot as a binary PPM of five panels, each divided by the reference's peak (gamma
// 2.2): the pass, the reference, and per pixel the temporal error, the references' own change and
// the pass's own change from frame t-1 (the three RMS over the channels; black where left out).
void writeTemporalPanels(const std::string& path, const test::CyclesReference& prevRef, const Image& prevPass,
                         const test::CyclesReference& ref, const Image& pass);

}  // namespace ssrcl::bench
