#pragma once
// Exact (double-precision quadrature) truth for glossy SSR: the GGX-lobe-weighted fraction of
// directions that reach a constant-radiance rectangle, as defined on ssrcl::TraceSettings:
//   A = integral of f (n.l) V(l) dl / integral of f (n.l) dl,  f = D G2 / (4 (n.o)(n.l)),
// GGX D, height-correlated Smith G2, no Fresnel; rgb = radiance * A for a constant emitter.
//
// Method (independent of the kernels' sampling): both integrals in polar coordinates (psi, phi)
// around the mirror direction m, where the lobe peaks. Along each half great circle from m the
// region (upper hemisphere, or the directions that hit the rectangle) is one psi interval, found
// exactly (the rectangle is a convex spherical polygon seen from p), so the integrands have no
// discontinuity inside the quadrature: Gauss-Legendre in psi on pieces halving toward the
// interval's start (down to a fraction of alpha: the peak and GGX's heavy tail both resolved);
// in phi, adaptive Gauss-Kronrod split at the corners' azimuths (where the interval's end points
// change edges), or for the whole hemisphere the periodic trapezoidal rule.
#include <functional>
#include <glm/vec3.hpp>
#include <vector>

#include "scenes/analytic_scene.hpp"
#include "support/ggx_reference.hpp"

namespace ssrcl::test {

// f(o, l) (n.l) = D(h) G2(o, l) / (4 n.o) in the local frame (normal +Z), the integrand of both
// integrals: ggx_reference.hpp's D and G1, height-correlated G2 = 1 / (1 + Lambda_o + Lambda_l)
// with Lambda = 1 / G1 - 1; 0 below either horizon.
double ggxLobe(const glm::dvec3& o, const glm::dvec3& l, double alpha);
// World vector w in the frame (u, v, n) of planeAxes(n).
glm::dvec3 toLocal(const glm::dvec3& n, const glm::dvec3& w);

struct Quadrature {
  int gaussPoints = 6;         // per psi piece
  double firstPiece = 0.5;     // the psi pieces halve down to firstPiece * scale
  int minPhiPanels = 1;        // each phi piece is split at least this many times before adaptivity
  double tolerance = 1e-7;     // absolute, on an integral over the full circle of phi
  Quadrature refined() const;  // twice the points and panels, finer pieces, 1/100 of the tolerance
};

// The psi interval [lo, hi] (0 <= lo < hi <= pi) of directions cos(psi) m + sin(psi) e that lie in
// a region; false when empty. e is unit and orthogonal to m.
using ArcClip = std::function<bool(const glm::dvec3& m, const glm::dvec3& e, double& lo, double& hi)>;

// Integral of g over a region of the unit sphere, polar around `centre` (unit); `scale` is the
// region-independent angular width of g's peak; the integrand of phi may only have kinks at
// `phiBreaks` (radians, any range): adaptive Gauss-Kronrod between them, or with none (a smooth
// periodic integrand) the trapezoidal rule, doubled until it settles.
double integrateAround(const std::function<double(const glm::dvec3&)>& g, const glm::dvec3& centre, double scale,
                       const ArcClip& clip, const std::vector<double>& phiBreaks, const Quadrature& q);

// Regions: the hemisphere n.l > 0, and the directions from p that hit a Rectangle primitive
// (intersected with the hemisphere of n).
ArcClip hemisphereClip(const glm::dvec3& n);
ArcClip rectangleClip(const glm::dvec3& p, const glm::dvec3& n, const Primitive& rect);
// Azimuths (in the frame integrateAround uses around `centre`) of the rectangle's corners seen
// from p, and of their opposites.
std::vector<double> rectangleBreaks(const glm::dvec3& p, const glm::dvec3& centre, const Primitive& rect);

struct LobeFraction {
  double found = 0.0;  // integral of f (n.l) over the rectangle's directions
  double total = 0.0;  // integral of f (n.l) over the hemisphere (the lobe's directional albedo)
  double a() const { return total > 0 ? found / total : 0.0; }
};
// Surface point p, unit normal n, unit o toward the eye, GGX alpha; V(l) = "l hits `rect`"
// (the caller guarantees nothing else is in the way).
LobeFraction lobeFraction(const glm::dvec3& p, const glm::dvec3& n, const glm::dvec3& o, double alpha,
                          const Primitive& rect, const Quadrature& q = {});

// Independent cross-check by brute force: midpoints of a grid x grid (u1, u2) stratification of the
// GGX normal distribution (tan^2 theta_h = alpha^2 u1 / (1 - u1), phi_h = 2 pi u2, density
// D cos theta_h), each reflected direction ray-cast against the whole scene; V = it hits `emitter`.
// Converges as 1 / grid (V is discontinuous).
LobeFraction lobeFractionBruteForce(const Scene& scene, int emitter, const glm::dvec3& p, const glm::dvec3& n,
                                    const glm::dvec3& o, double alpha, int grid);
// The half vector of that stratification for (u1, u2), local frame (normal +Z).
glm::dvec3 ndfHalfVector(double alpha, double u1, double u2);

// The glossy test scene: a rough textured floor (index kGlossyFloor, y = 0, x in [-2.2, 2.2],
// z in [-3, 1]) ending at a vertical constant-radiance panel facing the camera (index
// kGlossyPanel, plane z = -3, x in [-3, 3], y in [0, ~1.63], roughness 1), sky elsewhere; the eye
// at (0, 1.9, 3) looks at (0, 0, -3). Every floor point lies in front of the panel (rays can only
// reach its front face). The eye is above the panel's top, so a ray passing over the top edge
// projects onto sky, never onto the panel it is behind (no thickness false hits there); the floor
// is narrower than the panel, so few rays pass its sides.
inline constexpr int kGlossyFloor = 0;
inline constexpr int kGlossyPanel = 1;
Scene makeGlossyScene(double floorRoughness);
glm::dvec3 glossyPanelRadiance();
// The same with the floor folded into a ridge along x = 0: its halves (kGlossyFloor for x < 0,
// kCreaseRightHalf for x > 0) slope down from it at `degrees`, so their normals differ by twice
// that. Convex: neither half is in the way of the other's reflected rays (each lies below the
// other's plane), so each half's truth is glossyTruth's for it alone.
inline constexpr int kCreaseRightHalf = 2;
Scene makeCreasedGlossyScene(double floorRoughness, double degrees);

struct GlossyPixel {
  bool receiver = false;  // the pixel shows the floor
  LobeFraction lobe;
  double a = 0.0;
  glm::dvec3 rgb{0.0};  // premultiplied: panel radiance * a
};
struct GlossyTruth {
  int width = 0, height = 0;
  std::vector<GlossyPixel> pixels;
  const GlossyPixel& at(int x, int y) const { return pixels[std::size_t(y) * width + x]; }
};
// The truth at every pixel of `g` that shows primitive `receiver` (exact hit point and normal,
// o toward the eye, alpha = roughness^2), V = hits primitive `emitter` (a Rectangle). Rows are
// shared among hardware threads (~0.3 ms per pixel on one core).
GlossyTruth glossyTruth(const Scene& scene, const Camera& camera, const AnalyticGBuffer& g, int receiver, int emitter,
                        const Quadrature& q = {});

}  // namespace ssrcl::test
