#include "support/cpu_trace_reference.hpp"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <limits>

namespace ssrcl::test {
namespace {

using glm::dvec2;
using glm::dvec3;
using glm::dvec4;
constexpr double kInf = std::numeric_limits<double>::infinity();

// Row r of a glm (column-major) matrix.
dvec4 row(const glm::dmat4& m, int r) { return {m[0][r], m[1][r], m[2][r], m[3][r]}; }

// The camera-space point at planar depth d on the viewing line through continuous pixel position
// s: with X = (x, y, -d, 1), NDC x * w = clip x and NDC y * w = clip y are two linear equations
// in x and y, whatever the projection's depth row.
dvec3 pointAtDepth(const Camera& c, dvec2 s, double d) {
  const double nx = 2.0 * s.x / c.width - 1.0, ny = 1.0 - 2.0 * s.y / c.height;
  const dvec4 ex = row(c.projection, 0) - nx * row(c.projection, 3);
  const dvec4 ey = row(c.projection, 1) - ny * row(c.projection, 3);
  // ex.x x + ex.y y = -(ex.z (-d) + ex.w), likewise ey.
  const double bx = -(ex.z * -d + ex.w), by = -(ey.z * -d + ey.w);
  const double det = ex.x * ey.y - ex.y * ey.x;
  return {(bx * ey.y - ex.y * by) / det, (ex.x * by - bx * ey.x) / det, -d};
}

struct Segment {
  dvec2 s0, ds;  // screen position s0 + t ds, t in [0, 1] the on-screen part
  dvec4 q0, dq;  // (X / w, 1 / w) interpolated linearly in t
  dvec3 at(double t) const {
    const dvec4 q = q0 + t * dq;
    return dvec3(q) / q.w;
  }
  dvec2 screen(double t) const { return s0 + t * ds; }
};

bool makeSegment(const Camera& c, const dvec3& a, const dvec3& b, Segment& seg) {
  const dvec4 ha = c.projection * dvec4(a, 1.0), hb = c.projection * dvec4(b, 1.0);
  if (!(ha.w > 0 && hb.w > 0)) return false;
  const auto toScreen = [&](const dvec4& h) {
    return dvec2((h.x / h.w + 1.0) * 0.5 * c.width, (1.0 - h.y / h.w) * 0.5 * c.height);
  };
  seg.s0 = toScreen(ha);
  seg.ds = toScreen(hb) - seg.s0;
  seg.q0 = dvec4(a / ha.w, 1.0 / ha.w);
  seg.dq = dvec4(b / hb.w, 1.0 / hb.w) - seg.q0;
  double tMax = 1.0;
  for (int k = 0; k < 2; ++k) {
    const double size = k == 0 ? c.width : c.height;
    if (seg.ds[k] > 0) tMax = std::min(tMax, (size - seg.s0[k]) / seg.ds[k]);
    if (seg.ds[k] < 0) tMax = std::min(tMax, -seg.s0[k] / seg.ds[k]);
  }
  seg.ds *= tMax;
  seg.dq *= tMax;
  return std::isfinite(seg.s0.x) && std::isfinite(seg.s0.y) && std::isfinite(seg.ds.x) && std::isfinite(seg.ds.y) &&
         std::max(std::abs(seg.ds.x), std::abs(seg.ds.y)) > 0;
}

struct Surfaces {
  const Camera& camera;
  std::vector<bool> valid;
  std::vector<dvec3> point, normal;
  std::vector<double> depth;
  std::vector<double> viewCos;  // |n . v|, v the unit viewing direction of the pixel's centre
  std::vector<double> behind;   // how far behind its plane a ray may pass and hit it, along the normal
  std::vector<double> guess;    // with a back-face depth there: the thickness's bound (else 0)
  int index(int x, int y) const { return y * camera.width + x; }
};

}  // namespace

std::vector<CpuRay> cpuMirrorTrace(const Camera& camera, const Image& depth, const Image& normal,
                                   const CpuTraceOptions& options) {
  const int w = camera.width, h = camera.height;
  const size_t n = size_t(w) * h;
  const glm::dmat3 normalMatrix = glm::inverseTranspose(glm::dmat3(camera.view));
  Surfaces sf{camera, std::vector<bool>(n, false), std::vector<dvec3>(n), std::vector<dvec3>(n),
              std::vector<double>(n, 0.0), std::vector<double>(n, 0.0), std::vector<double>(n, 0.0),
              std::vector<double>(n, 0.0)};
  std::vector<bool> normalOk(n, false);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int i = sf.index(x, y);
      const double d = depth.at(x, y, 0);
      sf.valid[i] = std::isfinite(d) && d >= camera.nearPlane && d <= camera.farPlane && d < 1e10;
      sf.depth[i] = d;
      if (sf.valid[i]) sf.point[i] = pointAtDepth(camera, dvec2(x + 0.5, y + 0.5), d);
      const dvec3 nv = normalMatrix * dvec3(normal.at(x, y, 0), normal.at(x, y, 1), normal.at(x, y, 2));
      const double len = glm::length(nv);
      normalOk[i] = std::isfinite(len) && len > 0;
      // An unusable normal leaves the pixel's plane facing the camera.
      sf.normal[i] = normalOk[i] ? nv / len : dvec3(0, 0, 1);
      const dvec2 centre(x + 0.5, y + 0.5);
      const dvec3 view = glm::normalize(pointAtDepth(camera, centre, 2.0) - pointAtDepth(camera, centre, 1.0));
      sf.viewCos[i] = std::abs(glm::dot(view, sf.normal[i]));
      sf.behind[i] = options.thicknessRelative * d * sf.viewCos[i];
      const double b = options.backDepth ? options.backDepth->at(x, y, 0) : 0.0;
      if (sf.valid[i] && b > d && b < 1e10) {
        sf.guess[i] = sf.behind[i];
        sf.behind[i] = std::abs(glm::dot(pointAtDepth(camera, centre, b) - sf.point[i], sf.normal[i]));
      }
    }

  std::vector<CpuRay> rays(n);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int i = sf.index(x, y);
      CpuRay& ray = rays[i];
      if (!sf.valid[i] || !normalOk[i]) continue;
      const dvec3 p = sf.point[i], nrm = sf.normal[i];
      const dvec3 view = glm::normalize(pointAtDepth(camera, dvec2(x + 0.5, y + 0.5), sf.depth[i] + 1.0) - p);
      const dvec3 o = -view;
      if (!(glm::dot(o, nrm) > 0)) continue;
      ray.traced = true;
      ray.origin = p;
      ray.direction = glm::normalize(2.0 * glm::dot(o, nrm) * nrm - o);
      const dvec3 dir = ray.direction;

      double len = dir.z > 0   ? (-camera.nearPlane * 1.001 - p.z) / dir.z
                   : dir.z < 0 ? (-camera.farPlane - p.z) / dir.z
                               : kInf;
      len = std::min(len, 1e6 * sf.depth[i]);
      Segment seg;
      if (!(len > 0) || !makeSegment(camera, p, p + dir * len, seg)) continue;

      // The first known back's pixel the ray passes behind, and where.
      int pastX = -1, pastY = -1;
      double pastT = -1;
      // Tests pixel (cx, cy) over [t0, t1]; true on a hit.
      const auto test = [&](int cx, int cy, double t0, double t1) {
        cx = std::clamp(cx, 0, w - 1);
        cy = std::clamp(cy, 0, h - 1);
        const int q = sf.index(cx, cy);
        if (!sf.valid[q]) return false;
        const dvec3 nq = sf.normal[q];
        // Signed distance to the plane times 1 / w: affine in t, so its root is exact.
        const auto side = [&](double t) {
          const dvec4 qq = seg.q0 + t * seg.dq;
          return glm::dot(dvec3(qq), nq) - qq.w * glm::dot(sf.point[q], nq);
        };
        const double g0 = side(t0), g1 = side(t1);
        double tHit = -1;
        if (!(glm::dot(nq, dir) < 0)) {
          // Facing away: its back (known, or one thickness behind) is entered from behind it
          // (g + thickness / w crosses 0 upward).
          const double h0 = g0 + sf.behind[q] * (seg.q0.w + t0 * seg.dq.w);
          const double h1 = g1 + sf.behind[q] * (seg.q0.w + t1 * seg.dq.w);
          // Not through a plane seen within cos 0.1 of edge-on (kernels/trace.cl entry_facing).
          const dvec3 at = seg.at(t0);
          if (!(h0 < 0 && h1 >= 0) || std::abs(glm::dot(nq, at)) < 0.1 * glm::length(at)) return false;
          tHit = t0 + (t1 - t0) * (h0 / (h0 - h1));
          ray.enteredBack = true;
        } else if (g0 > 0 && g1 <= 0) {
          tHit = t0 + (t1 - t0) * (g0 / (g0 - g1));
        } else if (g0 <= 0 &&
                   -g0 / (seg.q0.w + t0 * seg.dq.w) <= sf.behind[q]) {
          tHit = t0;
        }
        if (tHit < 0) {
          if (g1 <= 0 && -g0 / (seg.q0.w + t0 * seg.dq.w) <= sf.guess[q] && pastT < 0) {
            pastX = cx;
            pastY = cy;
            pastT = t0;
          }
          return false;
        }
        ray.hit = true;
        ray.hitX = cx;
        ray.hitY = cy;
        ray.hitPoint = seg.at(tHit);
        ray.distance = glm::length(ray.hitPoint - p);
        return true;
      };

      // Where the ray leaves the pixel containing screen(t + a hair): per axis, the next
      // integer boundary in its direction.
      const auto exitOf = [&](double t, int& cx, int& cy) {
        const double major = std::max(std::abs(seg.ds.x), std::abs(seg.ds.y));
        const dvec2 s = seg.screen(t + 1e-9 / major);
        cx = int(std::floor(s.x));
        cy = int(std::floor(s.y));
        double te = kInf;
        for (int k = 0; k < 2; ++k) {
          const int cell = k == 0 ? cx : cy;
          if (seg.ds[k] > 0) te = std::min(te, (cell + 1 - seg.s0[k]) / seg.ds[k]);
          if (seg.ds[k] < 0) te = std::min(te, (cell - seg.s0[k]) / seg.ds[k]);
        }
        return te;
      };

      int cx = 0, cy = 0;
      double t = exitOf(0.0, cx, cy);  // leave the origin pixel first
      if (options.stepping == CpuTraceOptions::Stepping::EveryPixel) {
        while (t < 1.0) {
          const double tExit = exitOf(t, cx, cy);
          if (test(cx, cy, t, std::min(tExit, 1.0))) break;
          t = tExit;
        }
      } else {
        const double dt = options.linearStepPixels / std::max(std::abs(seg.ds.x), std::abs(seg.ds.y));
        while (t < 1.0) {
          const double t1 = std::min(t + dt, 1.0);
          const dvec2 s = seg.screen(t1);
          if (test(int(std::floor(s.x)), int(std::floor(s.y)), t, t1)) break;
          t = t1;
        }
      }
      if (!ray.hit && pastT >= 0) {
        ray.hit = ray.pastBack = true;
        ray.hitX = pastX;
        ray.hitY = pastY;
        ray.hitPoint = seg.at(pastT);
        ray.distance = glm::length(ray.hitPoint - p);
      }
    }
  return rays;
}

}  // namespace ssrcl::test
