// Which way an orthographic header camera looks. Its worldToCamera + worldToNDC read the same
// whether the file's camera space looks down +z (OpenEXR's) or -z (Houdini's): with no
// perspective divide, nothing in the matrices tells. The passes do: visible surfaces lie in front
// of the camera and, over the frame, face it.
#include <cmath>
#include <glm/glm.hpp>
#include <string>

#include "conventions.hpp"
#include "ssrcl/error.hpp"

namespace ssrcl {
namespace {

// A reading is chosen when at least this share of the counted pixels agrees with it: shading
// normals (bumps, back faces) disagree at some pixels, a reading that is wrong at most of them.
constexpr double kMajority = 0.8;
// Normals this close to the image plane (|eye z| of a unit normal) face neither way clearly.
constexpr double kGrazing = 0.1;
// Fewer counted pixels than this decide nothing.
constexpr long long kMinPixels = 100;

struct Votes {
  long long forFirst = 0, counted = 0;
  std::string evidence;  // what was counted, for the message
};

// Under the first reading, a world position lies in front of the camera when its eye z < 0.
Votes positionVotes(const Image& positions, const glm::dmat4& view) {
  Votes v{0, 0, "world positions in front of the camera"};
  for (int i = 0; i < positions.width * positions.height; ++i) {
    const glm::dvec3 p(positions.data[3 * i], positions.data[3 * i + 1], positions.data[3 * i + 2]);
    if (!std::isfinite(p.x + p.y + p.z) || p == glm::dvec3(0.0)) continue;  // no surface
    const double z = (view * glm::dvec4(p, 1.0)).z;
    if (z == 0.0) continue;
    ++v.counted;
    v.forFirst += z < 0.0;
  }
  return v;
}

// Under the first reading, a world normal faces the camera when its eye z > 0.
Votes normalVotes(const Image& normals, const glm::dmat4& view) {
  Votes v{0, 0, "world-space normals facing the camera"};
  const glm::dmat3 toEye(view);
  for (int i = 0; i < normals.width * normals.height; ++i) {
    const glm::dvec3 n(normals.data[3 * i], normals.data[3 * i + 1], normals.data[3 * i + 2]);
    const double length = glm::length(n);
    if (!(length > 0.0) || !std::isfinite(length)) continue;  // no surface
    const double z = detail::normalToEye(n / length, NormalSpace::World, toEye).z;
    if (std::abs(z) < kGrazing) continue;
    ++v.counted;
    v.forFirst += z > 0.0;
  }
  return v;
}

std::string percent(double share) { return std::to_string(int(std::lround(100.0 * share))) + "%"; }

}  // namespace

void orientHeaderCamera(HeaderCamera& h, const GBuffer& g, const GBufferSource& source, const std::string& file) {
  if (!h.reversed) return;
  const std::string what = file + ": the header camera (" + h.attributes +
                           ") is orthographic, which its matrices cannot tell looking down its +z axis "
                           "(OpenEXR's camera space) from -z (Houdini's)";
  Votes votes;
  if (!source.positionChannels.empty())
    votes = positionVotes(g.position, h.camera.view);
  else if (source.normalSpace == NormalSpace::World)
    votes = normalVotes(g.normal, h.camera.view);
  else
    throw Error(ErrorCode::InvalidInput, what + ", and " + normalSpaceName(source.normalSpace) +
                                             "-space normals without --position cannot tell either; give --camera");
  const double share = votes.counted > 0 ? double(votes.forFirst) / votes.counted : 0.5;
  if (votes.counted < kMinPixels || (share < kMajority && share > 1.0 - kMajority))
    throw Error(ErrorCode::InvalidInput, what + ", and the frame does not tell either (" + votes.evidence + ": " +
                                             percent(share) + " looking down +z, " + percent(1.0 - share) +
                                             " down -z, of " + std::to_string(votes.counted) +
                                             " pixels); give --camera");
  const bool first = share >= kMajority;
  if (!first) h.camera = *h.reversed;
  h.reversed.reset();
  h.attributes += first ? ", looking down +z" : ", looking down -z";
  h.attributes += " (" + percent(first ? share : 1.0 - share) + " of " + votes.evidence + ")";
}

}  // namespace ssrcl
