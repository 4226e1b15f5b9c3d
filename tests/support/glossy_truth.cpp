#include "support/glossy_truth.hpp"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <stdexcept>
#include <thread>

namespace ssrcl::test {
namespace {

using glm::dvec3;
constexpr double kPi = 3.14159265358979323846;

// Gauss-Kronrod 7-15 (QUADPACK qk15): Kronrod nodes >= 0, their weights, and the Gauss weights of
// the odd-indexed nodes.
constexpr double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

template <class F>
double adaptiveGk(const F& f, double a, double b, double tol, int depth) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double k = kWgk[7] * fc, g = kWg[3] * fc;
  for (int i = 0; i < 7; ++i) {
    const double s = f(c - h * kXgk[i]) + f(c + h * kXgk[i]);
    k += kWgk[i] * s;
    if (i % 2 == 1) g += kWg[i / 2] * s;
  }
  k *= h;
  g *= h;
  if (std::abs(k - g) <= tol || depth >= 40) return k;
  return adaptiveGk(f, a, c, 0.5 * tol, depth + 1) + adaptiveGk(f, c, b, 0.5 * tol, depth + 1);
}

// n-point Gauss-Legendre on [-1, 1] by Newton on P_n.
struct GaussLegendre {
  std::vector<double> x, w;
  explicit GaussLegendre(int n) : x(std::size_t(n)), w(std::size_t(n)) {
    for (int i = 0; i < n; ++i) {
      double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int k = 2; k <= n; ++k) {
          const double p2 = ((2 * k - 1) * z * p1 - (k - 1) * p0) / k;
          p0 = p1;
          p1 = p2;
        }
        dp = n * (z * p1 - p0) / (z * z - 1);
        const double dz = p1 / dp;
        z -= dz;
        if (std::abs(dz) < 1e-16) break;
      }
      x[std::size_t(i)] = z;
      w[std::size_t(i)] = 2 / ((1 - z * z) * dp * dp);
    }
  }
};

// The psi interval of [0, pi] where cos(psi) a + sin(psi) b > 0, i.e. R cos(psi - beta) > 0.
bool positiveArc(double a, double b, double& lo, double& hi) {
  if (a == 0 && b == 0) return false;
  const double beta = std::atan2(b, a);
  double best = 0;
  for (double shift : {0.0, 2 * kPi}) {
    const double l = std::max(0.0, beta + shift - kPi / 2), h = std::min(kPi, beta + shift + kPi / 2);
    if (h - l > best) best = h - l, lo = l, hi = h;
  }
  return best > 0;
}

void rectangleCorners(const Primitive& rect, dvec3 corners[4]) {
  if (rect.kind != Primitive::Kind::Rectangle) throw std::invalid_argument("glossy truth: emitter is not a rectangle");
  dvec3 u, v;
  planeAxes(rect.normal, u, v);
  const dvec3 du = rect.halfSize.x * u, dv = rect.halfSize.z * v;
  corners[0] = rect.center - du - dv;
  corners[1] = rect.center + du - dv;
  corners[2] = rect.center + du + dv;
  corners[3] = rect.center - du + dv;
}

}  // namespace

double ggxLobe(const dvec3& o, const dvec3& l, double alpha) {
  if (!(o.z > 0 && l.z > 0)) return 0;
  const double g2 = 1 / (1 / ggx::smithG1(o, alpha) + 1 / ggx::smithG1(l, alpha) - 1);
  return ggx::ndf(glm::normalize(o + l), alpha) * g2 / (4 * o.z);
}

dvec3 toLocal(const dvec3& n, const dvec3& w) {
  dvec3 u, v;
  planeAxes(n, u, v);
  return {glm::dot(w, u), glm::dot(w, v), glm::dot(w, n)};
}

Quadrature Quadrature::refined() const {
  Quadrature q = *this;
  q.gaussPoints *= 2;
  q.firstPiece /= 4;
  q.minPhiPanels *= 2;
  q.tolerance /= 100;
  return q;
}

double integrateAround(const std::function<double(const dvec3&)>& g, const dvec3& centre, double scale,
                       const ArcClip& clip, const std::vector<double>& phiBreaks, const Quadrature& q) {
  const GaussLegendre gl(q.gaussPoints);
  dvec3 e1, e2;
  planeAxes(centre, e1, e2);
  // Along the half great circle toward e, psi pieces halve toward lo down to firstPiece * scale
  // (the peak at psi = 0 or the region's nearest edge, and the heavy GGX tail, both resolved). A
  // fixed number of pieces, scaled to [lo, hi], keeps the rule a smooth function of phi, so the
  // adaptive phi quadrature does not chase jumps of the psi rule's error.
  const int levels = std::max(1, int(std::ceil(std::log2(kPi / (q.firstPiece * scale)))));
  const auto radial = [&](double phi) {
    const dvec3 e = std::cos(phi) * e1 + std::sin(phi) * e2;
    double lo, hi;
    if (!clip(centre, e, lo, hi)) return 0.0;
    double sum = 0, b = hi;
    for (int k = 1; k <= levels + 1; ++k) {
      const double a = k <= levels ? lo + (hi - lo) * std::ldexp(1.0, -k) : lo;
      const double c = 0.5 * (a + b), h = 0.5 * (b - a);
      for (std::size_t i = 0; i < gl.x.size(); ++i) {
        const double psi = c + h * gl.x[i];
        sum += h * gl.w[i] * g(std::cos(psi) * centre + std::sin(psi) * e) * std::sin(psi);
      }
      b = a;
    }
    return sum;
  };
  if (phiBreaks.empty()) {
    // Smooth and periodic in phi: the trapezoidal rule converges exponentially; double the nodes
    // until the estimate settles (the last doubling's change far exceeds the remaining error).
    int count = 8 * q.minPhiPanels;
    double sum = 0;
    for (int k = 0; k < count; ++k) sum += radial(2 * kPi * k / count);
    double estimate = sum * 2 * kPi / count;
    for (;;) {
      for (int k = 0; k < count; ++k) sum += radial(2 * kPi * (k + 0.5) / count);
      count *= 2;
      const double next = sum * 2 * kPi / count;
      const bool settled = std::abs(next - estimate) <= q.tolerance;
      estimate = next;
      if (settled || count >= (1 << 20)) return estimate;
    }
  }
  std::vector<double> breaks = {0.0, 2 * kPi};
  for (double b : phiBreaks) {
    const double w = b - 2 * kPi * std::floor(b / (2 * kPi));
    if (w > 0 && w < 2 * kPi) breaks.push_back(w);
  }
  std::sort(breaks.begin(), breaks.end());
  double total = 0;
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double len = (breaks[i + 1] - breaks[i]) / q.minPhiPanels;
    if (!(len > 1e-15)) continue;
    for (int k = 0; k < q.minPhiPanels; ++k) {
      const double a = breaks[i] + k * len;
      total += adaptiveGk(radial, a, a + len, q.tolerance * len / (2 * kPi), 0);
    }
  }
  return total;
}

ArcClip hemisphereClip(const dvec3& n) {
  return [n](const dvec3& m, const dvec3& e, double& lo, double& hi) {
    return positiveArc(glm::dot(m, n), glm::dot(e, n), lo, hi);
  };
}

ArcClip rectangleClip(const dvec3& p, const dvec3& n, const Primitive& rect) {
  std::vector<dvec3> c(4);
  rectangleCorners(rect, c.data());
  return [p, n, c](const dvec3& m, const dvec3& e, double& lo, double& hi) {
    // The rectangle cut by the plane through p spanned by m and e is a segment (convex polygon);
    // its end points lie on the edges whose corners are on opposite sides.
    const dvec3 w = glm::cross(m, e);
    double s[4], ang[2];
    for (int k = 0; k < 4; ++k) s[k] = glm::dot(w, c[std::size_t(k)] - p);
    int found = 0;
    for (int k = 0; k < 4 && found < 2; ++k) {
      const int j = (k + 1) % 4;
      if ((s[k] <= 0) == (s[j] <= 0)) continue;
      const dvec3 x = c[std::size_t(k)] + (s[k] / (s[k] - s[j])) * (c[std::size_t(j)] - c[std::size_t(k)]);
      ang[found++] = std::atan2(glm::dot(x - p, e), glm::dot(x - p, m));
    }
    if (found < 2) return false;
    // The segment subtends less than pi from p; if its angles straddle +-pi it covers -m.
    double l = std::min(ang[0], ang[1]), h = std::max(ang[0], ang[1]);
    if (h - l > kPi) l = h, h = kPi;
    l = std::max(l, 0.0);
    double hl, hh;
    if (!positiveArc(glm::dot(m, n), glm::dot(e, n), hl, hh)) return false;
    lo = std::max(l, hl);
    hi = std::min(h, hh);
    return hi > lo;
  };
}

std::vector<double> rectangleBreaks(const dvec3& p, const dvec3& centre, const Primitive& rect) {
  dvec3 c[4], e1, e2;
  rectangleCorners(rect, c);
  planeAxes(centre, e1, e2);
  std::vector<double> out;
  for (const dvec3& corner : c) {
    const dvec3 d = corner - p;
    const double phi = std::atan2(glm::dot(d, e2), glm::dot(d, e1));
    out.push_back(phi);
    out.push_back(phi + kPi);
  }
  return out;
}

LobeFraction lobeFraction(const dvec3& p, const dvec3& n, const dvec3& o, double alpha, const Primitive& rect,
                          const Quadrature& q) {
  const dvec3 m = glm::normalize(2 * glm::dot(n, o) * n - o);
  dvec3 u, v;
  planeAxes(n, u, v);
  const dvec3 oLocal = toLocal(n, o);
  const auto g = [&](const dvec3& l) {
    return ggxLobe(oLocal, dvec3(glm::dot(l, u), glm::dot(l, v), glm::dot(l, n)), alpha);
  };
  LobeFraction r;
  r.total = integrateAround(g, m, alpha, hemisphereClip(n), {}, q);
  r.found = integrateAround(g, m, alpha, rectangleClip(p, n, rect), rectangleBreaks(p, m, rect), q);
  return r;
}

dvec3 ndfHalfVector(double alpha, double u1, double u2) {
  const double tan2 = alpha * alpha * u1 / (1 - u1), cosT = 1 / std::sqrt(1 + tan2);
  const double sinT = std::sqrt(tan2) * cosT, phi = 2 * kPi * u2;
  return {sinT * std::cos(phi), sinT * std::sin(phi), cosT};
}

LobeFraction lobeFractionBruteForce(const Scene& scene, int emitter, const dvec3& p, const dvec3& n, const dvec3& o,
                                    double alpha, int grid) {
  dvec3 u, v;
  planeAxes(n, u, v);
  const dvec3 oLocal = toLocal(n, o);
  LobeFraction r;
  const double tMin = 1e-9 * (1 + glm::length(p));
  for (int i = 0; i < grid; ++i)
    for (int j = 0; j < grid; ++j) {
      // u1 = 1 - (1 - s)^2 puts more rows near u1 = 1, where the lobe meets the horizon.
      const double s = (i + 0.5) / grid, u1 = 1 - (1 - s) * (1 - s);
      const dvec3 h = ndfHalfVector(alpha, u1, (j + 0.5) / grid);
      const double oh = glm::dot(oLocal, h);
      if (!(oh > 0)) continue;
      const dvec3 l = 2 * oh * h - oLocal;
      // dl = 4 (o.h) dh, dh = du1 du2 / (D cos theta_h), du1 = 2 (1 - s) ds.
      const double w = ggxLobe(oLocal, l, alpha) * 4 * oh * 2 * (1 - s) / (ggx::ndf(h, alpha) * h.z);
      if (!(w > 0)) continue;
      r.total += w;
      if (intersect(scene, Ray{p, glm::normalize(l.x * u + l.y * v + l.z * n)}, tMin).primitive == emitter)
        r.found += w;
    }
  r.total /= double(grid) * grid;
  r.found /= double(grid) * grid;
  return r;
}

Scene makeGlossyScene(double floorRoughness) {
  Scene s;
  s.name = "glossy_panel";
  Material floor{dvec3(0.45, 0.45, 0.5), floorRoughness};
  Material panel{glossyPanelRadiance(), 1.0, 1.0, false};
  // planeAxes(+Z) gives u = +Y, v = +X: halfU is the half height, halfV the half width.
  s.view.eye = dvec3(0, 1.9, 3.0);
  s.view.target = dvec3(0, 0.0, -3.0);
  // The top edge is a horizontal screen line, so its G-buffer staircase is offset from it by the
  // same fraction of a pixel in every column, a coherent bias for every lobe straddling it. Put
  // it on the boundary above pixel row 16 of 90 (for any image height multiple of 90): top ~1.63.
  const Camera camera = makeCamera(s.view, 160, 90);
  double lo = 1.0, hi = 1.8;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    (projectToScreen(camera, dvec3(0, mid, -3)).y > 16.0 ? lo : hi) = mid;
  }
  const double top = 0.5 * (lo + hi);
  s.primitives = {rectangle("floor", dvec3(0, 0, -1.0), dvec3(0, 1, 0), 2.2, 2.0, floor),
                  rectangle("panel", dvec3(0, 0.5 * top, -3.0), dvec3(0, 0, 1), 0.5 * top, 3.0, panel)};
  return s;
}

Scene makeCreasedGlossyScene(double floorRoughness, double degrees) {
  Scene s = makeGlossyScene(floorRoughness);
  s.name = "glossy_panel_creased";
  const Primitive flat = s.primitives[kGlossyFloor];
  const double t = degrees * std::acos(-1.0) / 180.0, halfX = flat.halfSize.x, halfZ = flat.halfSize.z;
  for (int side : {-1, 1}) {
    // The half's centre lies halfway down its slope; u (its in-plane x axis) runs along the slope.
    const dvec3 centre(side * 0.5 * halfX, -0.5 * halfX * std::tan(t), flat.center.z);
    const dvec3 normal(side * std::sin(t), std::cos(t), 0.0);
    const Primitive half = rectangle(side < 0 ? "floor_left" : "floor_right", centre, normal,
                                     0.5 * halfX / std::cos(t), halfZ, flat.material);
    if (side < 0)
      s.primitives[kGlossyFloor] = half;
    else
      s.primitives.push_back(half);
  }
  return s;
}

dvec3 glossyPanelRadiance() { return {0.9, 0.55, 0.25}; }

GlossyTruth glossyTruth(const Scene& scene, const Camera& camera, const AnalyticGBuffer& g, int receiver, int emitter,
                        const Quadrature& q) {
  const Primitive& rect = scene.primitives.at(std::size_t(emitter));
  if (rect.material.textured) throw std::invalid_argument("glossy truth: the emitter must be untextured");
  const double r = scene.primitives.at(std::size_t(receiver)).material.roughness;
  GlossyTruth t;
  t.width = g.width;
  t.height = g.height;
  t.pixels.resize(g.hits.size());
  const auto rows = [&](int first, int step) {
    for (int y = first; y < g.height; y += step)
      for (int x = 0; x < g.width; ++x) {
        const Hit& hit = g.hit(x, y);
        if (hit.primitive != receiver) continue;
        GlossyPixel& px = t.pixels[std::size_t(y) * g.width + x];
        px.receiver = true;
        const dvec3 o = -primaryRay(camera, x + 0.5, y + 0.5).direction;
        px.lobe = lobeFraction(hit.position, hit.normal, o, r * r, rect, q);
        px.a = px.lobe.a();
        px.rgb = rect.material.base * px.a;
      }
  };
  const int workers = int(std::max(1u, std::min(16u, std::thread::hardware_concurrency())));
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(rows, w, workers);
  rows(0, workers);
  for (std::thread& th : pool) th.join();
  return t;
}

}  // namespace ssrcl::test
