#include "native_mirror_trace.hpp"

#include <algorithm>
#include <cfloat>
#include <chrono>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <glm/glm.hpp>
#include <glm/gtc/matrix_inverse.hpp>
#include <time.h>

#include "native_frame_stages.hpp"
#include "native_rows.hpp"
#include "packet_hiz_trace.hpp"

namespace ssrcl::bench {
namespace {

using glm::vec2;
using glm::vec3;
using glm::vec4;
using Clock = std::chrono::steady_clock;
constexpr float kNoSurface = FLT_MAX;  // SSRCL_NO_SURFACE
constexpr float kBackgroundDepth = 1e10f;
const vec4 kNoPlane(0.0f, 0.0f, 0.0f, -INFINITY);  // SSRCL_NO_PLANE

// common.cl sanitize_radiance (SSRCL_MAX_RADIANCE 1e20).
float sanitizeRadiance(float v) { return std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1e20f); }

// surface_plane.cl surface_plane.
vec4 surfacePlane(vec3 p, vec3 n, float thickness) {
  const float distance = glm::length(p);
  return vec4(n, glm::dot(p, n)) * (1.0f / std::clamp(thickness, FLT_EPSILON * distance, 1e6f * distance));
}

// This thread's CPU time: on a shared machine, what the work cost where wall time also counts
// the other processes' turns.
double threadCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) * 1e3 + double(t.tv_nsec) * 1e-6;
}

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

struct ScreenRay {
  vec2 s0, ds;
  vec4 q0, dq;  // xyz = Q, w = k
  vec4 q(float t) const { return q0 + t * dq; }
  vec2 screen(float t) const { return s0 + t * ds; }
  float depth(float t) const { const vec4 v = q(t); return -v.z / v.w; }
};

}  // namespace

struct NativeMirrorTrace::Impl {
  int w, h;
  glm::mat4 proj, invProj;
  glm::mat3 normalMatrix;
  float nearPlane, farPlane, thicknessRel, maxRoughness, constantRoughness;
  int maxIterations;
  bool edgeColors;
  bool adaptive;  // setup's planes for the adaptive thickness model (runFrame's thickness stage rescales them)
  AdaptiveThickness thicknessModel;
  const GBuffer& g;
  std::vector<HzbLevel> levels;
  std::vector<float> hzb, thickness, distance, packetHits, linearHits;
  MinMaxPyramid pyramid;
  std::vector<uint32_t> pyramidWords;
  PacketStats packetStats;
  PacketIsa packetIsa = packetTraceIsa();
  std::vector<vec4> positions, normals, planes, colors;  // colors: the colour pyramid, every level
  std::vector<vec2> range, rowRuns;                        // range: the range pyramid, every level
  std::vector<unsigned char> reflects;
  long long rays = 0;

  Impl(const GBuffer& gbuffer, const Camera& camera, const TraceSettings& s)
      : w(camera.width),
        h(camera.height),
        proj(camera.projection),
        invProj(glm::inverse(camera.projection)),
        normalMatrix(glm::inverseTranspose(glm::dmat3(camera.view))),
        nearPlane(float(camera.nearPlane)),
        farPlane(float(camera.farPlane)),
        thicknessRel(s.thicknessRelative),
        maxRoughness(s.maxRoughness),
        constantRoughness(s.constantRoughness.value_or(-1.0f)),
        maxIterations(s.maxIterations > 0 ? s.maxIterations : 512),
        edgeColors(s.edgeColors),
        adaptive(s.thicknessModel == ThicknessModel::Adaptive),
        thicknessModel{s.thicknessScale, s.thicknessMinRelative, s.thicknessMaxRelative},
        g(gbuffer) {
    // The pyramid as host/pipeline/stage_support.cpp lays it out: each level ceil(half) of the last, to 1x1.
    int offset = 0;
    for (int lw = w, lh = h;; lw = (lw + 1) / 2, lh = (lh + 1) / 2) {
      levels.push_back({offset, lw, lh});
      offset += lw * lh;
      if (lw == 1 && lh == 1) break;
    }
    buildPixelLines();
    const size_t n = size_t(w) * h;
    hzb.resize(offset);
    thickness.resize(n);
    distance.resize(n);
    packetHits.resize(3 * n);
    linearHits.resize(3 * n);
    positions.resize(n);
    normals.resize(n);
    planes.resize(n);
    colors.resize(offset);
    range.resize(offset);
    rowRuns.resize(n);
    reflects.resize(n);
  }

  vec2 pixelToNdc(vec2 p) const { return {2.0f * p.x / float(w) - 1.0f, 1.0f - 2.0f * p.y / float(h)}; }
  vec2 ndcToPixel(vec2 n) const { return {(n.x + 1.0f) * 0.5f * float(w), (1.0f - n.y) * 0.5f * float(h)}; }

  void viewLine(vec2 ndc, vec3& origin, vec3& step) const { bench::viewLine(invProj, ndc, origin, step); }

  // setup.cl pixel_lines / pixel_line: viewing lines as an affine map of pixel coordinates.
  vec4 lineAtOrigin, linePerX, linePerY, lineEye;
  void buildPixelLines() {
    linePerX = invProj[0] * (2.0f / float(w));
    linePerY = invProj[1] * (-2.0f / float(h));
    lineAtOrigin = invProj[3] - invProj[0] + invProj[1];
    lineEye = invProj[2].w != 0.0f ? invProj[2] / invProj[2].w : invProj[2];
  }
  vec3 pixelLine(vec2 pixel, vec3& v) const {
    const vec4 a = lineAtOrigin + pixel.x * linePerX + pixel.y * linePerY;
    v = vec3(a) * lineEye.w - vec3(lineEye) * a.w;
    return lineEye.w != 0.0f ? vec3(lineEye) : vec3(a) / a.w;
  }

  // setup.cl plane_depth_at.
  float planeDepthAt(vec2 pixel, vec3 p, vec3 n) const {
    vec3 v;
    const vec3 origin = pixelLine(pixel, v);
    const float denom = glm::dot(v, n);
    if (std::fabs(denom) < 1e-20f * std::fabs(v.z)) return -1.0f;
    const float depth = glm::dot(p - origin, n) * -v.z / denom - origin.z;
    return depth > 0.0f && std::isfinite(depth) ? depth : -1.0f;
  }

  // setup.cl surface_depth.
  bool surfaceDepth(float d) const {
    return std::isfinite(d) && d >= nearPlane && d <= farPlane && d < kBackgroundDepth;
  }
  // setup.cl depth_or_none, joins, nearer_beside, inside_surface and edge_colour.
  float depthOrNone(int x, int y) const {
    if (!inFrame(x, y)) return kNoSurface;
    const float d = g.depth.data[size_t(y) * w + x];
    return surfaceDepth(d) ? d : kNoSurface;
  }
  vec3 sanitizedColor(size_t i) const {
    const float* c = &g.color.data[i * g.color.channels];
    return {sanitizeRadiance(c[0]), sanitizeRadiance(c[1]), sanitizeRadiance(c[2])};
  }
  bool inFrame(int x, int y) const { return x >= 0 && y >= 0 && x < w && y < h; }
  bool joins(int x, int y, int dx, int dy, float d) const {
    if (!inFrame(x + dx, y + dy)) return true;
    const float c = depthOrNone(x + dx, y + dy);
    if (!(c < kNoSurface)) return false;
    if (std::fabs(c - d) <= 0.02f * clFmin(c, d)) return true;
    const float a = depthOrNone(x - dx, y - dy), e = depthOrNone(x + 2 * dx, y + 2 * dy);
    if (a < kNoSurface && predicts(a, 1.0f / a, d, 1.0f / d, c, 1.0f / c, 0.01f / c)) return true;
    if (e < kNoSurface && predicts(e, 1.0f / e, c, 1.0f / c, d, 1.0f / d, 0.01f / d)) return true;
    return !(a < kNoSurface) && !(e < kNoSurface);
  }
  bool nearerBeside(int x, int y, float d) const {
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if ((dx != 0 || dy != 0) && depthOrNone(x + dx, y + dy) < d && !joins(x, y, dx, dy, d)) return true;
    return false;
  }
  bool insideSurface(int x, int y) const {
    const float d = depthOrNone(x, y);
    if (!(d < kNoSurface)) return false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx)
        if ((dx != 0 || dy != 0) && !joins(x, y, dx, dy, d)) return false;
    return true;
  }
  vec3 edgeColor(int x, int y, float d, vec3 own) const {
    vec3 lo(INFINITY), hi(-INFINITY);
    for (int ring = 1; ring <= 2 && !(lo.x <= hi.x); ++ring)
      for (int dy = -ring; dy <= ring; ++dy)
        for (int dx = -ring; dx <= ring; dx += (dy == -ring || dy == ring) ? 1 : 2 * ring) {
          const int qx = x + dx, qy = y + dy;
          if (!inFrame(qx, qy) || !joins(x, y, dx, dy, d) || !insideSurface(qx, qy)) continue;
          const vec3 q = sanitizedColor(size_t(qy) * w + qx);
          lo = glm::min(lo, q);
          hi = glm::max(hi, q);
        }
    return lo.x <= hi.x ? glm::min(glm::max(own, lo), hi) : own;
  }

  SSRCL_NATIVE_CLONES void setupRow(int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const float d = g.depth.data[i];
      vec3 v;
      const vec3 origin = pixelLine(vec2(x + 0.5f, y + 0.5f), v);
      const vec3 step = v * (-1.0f / v.z);
      const vec3 viewDir = glm::normalize(step);
      const vec3 p = origin + (d + origin.z) * step;
      const bool surface = surfaceDepth(d) && std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
      const vec3 nw(g.normal.data[3 * i], g.normal.data[3 * i + 1], g.normal.data[3 * i + 2]);
      const float scale = std::max(std::fabs(nw.x), std::max(std::fabs(nw.y), std::fabs(nw.z)));
      bool normalOk = std::isfinite(scale) && scale > 0.0f;
      vec3 nv = normalMatrix * (normalOk ? nw / scale : vec3(0.0f));
      const float len = glm::length(nv);
      normalOk = normalOk && std::isfinite(len) && len > 1e-20f;
      nv = normalOk ? nv / len : vec3(0, 0, 1);
      float r = constantRoughness >= 0.0f ? constantRoughness : g.roughness.data[i];
      r = std::isnan(r) ? 1.0f : std::clamp(r, 0.0f, 1.0f);
      vec3 color = sanitizedColor(i);
      if (surface && edgeColors && nearerBeside(x, y, d)) color = edgeColor(x, y, d, color);
      colors[i] = surface ? vec4(color, r < 0.9f ? 0.0f : 1.0f) : vec4(0.0f);
      float nearest = d;
      if (surface && normalOk)
        for (int corner = 0; corner < 4; ++corner) {
          const float cd = planeDepthAt(vec2(float(x + (corner & 1)), float(y + (corner >> 1))), p, nv);
          if (cd > 0.0f) nearest = std::min(nearest, std::max(cd, 0.5f * d));
        }
      positions[i] = surface ? vec4(p, d) : vec4(0, 0, 0, kNoSurface);
      hzb[i] = surface ? nearest : kNoSurface;
      normals[i] = vec4(nv, r);
      thickness[i] = surface ? thicknessRel * d * std::fabs(glm::dot(viewDir, nv)) : 0.0f;
      planes[i] = surface ? surfacePlane(p, nv, (adaptive ? 1.0f : thicknessRel) * d * std::fabs(glm::dot(viewDir, nv)))
                          : kNoPlane;
      reflects[i] = surface && normalOk && r <= maxRoughness && glm::dot(viewDir, nv) < 0.0f;
    }
  }

  SSRCL_NATIVE_CLONES void reduceRow(int l, int y) {
    reducePyramidRow(levels, l, y, hzb.data(), [](float a, float b, float c, float d, bool, bool) {
      return std::min(std::min(a, b), std::min(c, d));
    });
  }

  double setup(int threads) {
    const auto start = Clock::now();
    parallelRows(h, threads, [this](int y) { setupRow(y); });
    return msSince(start);
  }

  double reduceHzb(int threads) {
    const auto start = Clock::now();
    reduceLevels(levels, threads, [this](int l, int y) { reduceRow(l, y); });
    return msSince(start);
  }

  float hzbFetch(int level, glm::ivec2 cell) const {
    const HzbLevel l = levels[level];
    cell = glm::clamp(cell, glm::ivec2(0), glm::ivec2(l.width - 1, l.height - 1));
    return hzb[l.offset + cell.y * l.width + cell.x];
  }

  // trace.cl cell_exit, of cells of any size (trace.cl steps pixels with it, its Hi-Z integer cells).
  static float cellExit(const ScreenRay& r, float t, float nudge, float cellSize, glm::ivec2& cellOut) {
    const vec2 cell = glm::floor(r.screen(t + nudge) / cellSize);
    cellOut = glm::ivec2(cell);
    const vec2 boundary = (cell + vec2(r.ds.x > 0.0f, r.ds.y > 0.0f)) * cellSize;
    vec2 tb = (boundary - r.s0) / r.ds;
    if (std::fabs(r.ds.x) < 1e-12f) tb.x = INFINITY;
    if (std::fabs(r.ds.y) < 1e-12f) tb.y = INFINITY;
    return std::min(tb.x, tb.y);
  }

  // trace.cl make_screen_ray.
  bool makeScreenRay(vec3 p0, vec3 p1, ScreenRay& r) const {
    const vec4 h0 = proj * vec4(p0, 1.0f), h1 = proj * vec4(p1, 1.0f);
    if (!(h0.w > 0.0f && h1.w > 0.0f)) return false;
    const float k0 = 1.0f / h0.w, k1 = 1.0f / h1.w;
    r.s0 = ndcToPixel(vec2(h0) * k0);
    r.ds = ndcToPixel(vec2(h1) * k1) - r.s0;
    r.q0 = vec4(p0 * k0, k0);
    r.dq = vec4(p1 * k1, k1) - r.q0;
    const vec2 edge(r.ds.x > 0.0f ? float(w) : 0.0f, r.ds.y > 0.0f ? float(h) : 0.0f);
    vec2 te = (edge - r.s0) / r.ds;
    if (std::fabs(r.ds.x) < 1e-12f) te.x = INFINITY;
    if (std::fabs(r.ds.y) < 1e-12f) te.y = INFINITY;
    const float tMax = std::min(1.0f, std::min(te.x, te.y));
    r.ds *= tMax;
    r.dq *= tMax;
    return std::isfinite(r.s0.x) && std::isfinite(r.s0.y) && std::isfinite(r.ds.x) && std::isfinite(r.ds.y);
  }

  // trace.cl hit_pixel.
  float hitPixel(const ScreenRay& ray, vec3 dir, glm::ivec2 cell, float tIn, float tOut, bool& inFront) const {
    cell = glm::clamp(cell, glm::ivec2(0), glm::ivec2(w - 1, h - 1));
    const int idx = cell.y * w + cell.x;
    const vec4 pc = positions[idx];
    inFront = true;
    if (pc.w >= kNoSurface) return -1.0f;
    const vec3 n(normals[idx]);
    const auto side = [&](float t) { const vec4 q = ray.q(t); return glm::dot(vec3(q), n) - q.w * glm::dot(vec3(pc), n); };
    const float gIn = side(tIn), gOut = side(tOut);
    inFront = gOut > 0.0f;
    if (!(glm::dot(n, dir) < 0.0f)) {  // facing away: a hit only where the ray enters through its back
      const vec4 qIn = ray.q(tIn);
      const float hIn = gIn + thickness[idx] * qIn.w, hOut = gOut + thickness[idx] * ray.q(tOut).w;
      const bool entry = hIn < 0.0f && hOut >= 0.0f &&
                         std::fabs(glm::dot(n, vec3(qIn))) >= 0.1f * glm::length(n) * glm::length(vec3(qIn));
      return entry ? tIn + (tOut - tIn) * (hIn / (hIn - hOut)) : -1.0f;
    }
    if (gIn > 0.0f && gOut <= 0.0f) return tIn + (tOut - tIn) * (gIn / (gIn - gOut));
    if (gIn <= 0.0f && -gIn / ray.q(tIn).w <= thickness[idx]) return tIn;
    return -1.0f;
  }

  // Hi-Z as trace.cl traced before it stepped integer cells: min-depth HZB, the cell found from
  // the ray's position, one level a climb. Another traversal than today's trace_hiz with the same
  // hit test, so agreeing hits check the traversal, not a copy of it.
  float traceHiz(const ScreenRay& ray, vec3 dir) const {
    const int levelCount = int(levels.size());
    const float nudge = 0.01f / std::max(std::fabs(ray.ds.x), std::fabs(ray.ds.y));
    const bool deeper = ray.q0.z * ray.dq.w - ray.dq.z * ray.q0.w > 0.0f;
    glm::ivec2 cell;
    float t = cellExit(ray, 0.0f, nudge, 1.0f, cell);
    int mip = 0;
    for (int it = 0; it < maxIterations && t <= 1.0f; ++it) {
      const float tExit = cellExit(ray, t, nudge, float(1 << mip), cell);
      if (mip == 0) {
        bool inFront;
        const float tHit = hitPixel(ray, dir, cell, t, std::min(tExit, 1.0f), inFront);
        if (tHit >= 0.0f) return tHit;
        t = tExit;
        if (inFront) mip = std::min(1, levelCount - 1);
        continue;
      }
      const float dMin = hzbFetch(mip, cell);
      if (ray.depth(t) < dMin) {
        float tCross = INFINITY;
        if (deeper && dMin < kNoSurface) {
          const float denom = ray.dq.z + dMin * ray.dq.w;
          const float root = -(ray.q0.z + dMin * ray.q0.w) / denom;
          tCross = denom != 0.0f && std::isfinite(root) ? root : INFINITY;
        }
        if (tCross <= tExit) {
          t = std::max(t, tCross);
          --mip;
        } else {
          t = tExit;
          mip = std::min(mip + 1, levelCount - 1);
        }
      } else {
        --mip;
      }
    }
    return -1.0f;
  }

  // trace.cl trace_from + the mirror direction of trace_rays: pixel (x, y)'s ray, if it has one.
  bool mirrorRay(int x, int y, ScreenRay& ray, vec3& dir) const {
    const size_t i = size_t(y) * w + x;
    if (!reflects[i]) return false;
    vec3 origin, step;
    viewLine(pixelToNdc(vec2(x + 0.5f, y + 0.5f)), origin, step);
    const vec3 o = -glm::normalize(step), n(normals[i]), p(positions[i]);
    if (glm::dot(o, n) <= 0.0f) return false;
    dir = 2.0f * glm::dot(o, n) * n - o;
    const float lengthMax = 1e6f * -p.z;
    float len = dir.z > 0.0f ? (-nearPlane * 1.001f - p.z) / dir.z
              : dir.z < 0.0f ? (-farPlane - p.z) / dir.z : lengthMax;
    len = std::min(len, lengthMax);
    if (!(len > 0.0f) || !makeScreenRay(p, p + dir * len, ray)) return false;
    return std::max(std::fabs(ray.ds.x), std::fabs(ray.ds.y)) > 0.0f;
  }

  // The view-space distance from pixel i's point to its ray's hit at t.
  float hitDistance(size_t i, const ScreenRay& ray, float t) const {
    const vec4 q = ray.q(t);
    return glm::length(vec3(q) / q.w - vec3(positions[i]));
  }

  SSRCL_NATIVE_CLONES void traceRow(int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      distance[i] = 0.0f;
      ScreenRay ray;
      vec3 dir;
      if (!mirrorRay(x, y, ray, dir)) continue;
      const float t = traceHiz(ray, dir);
      if (t >= 0.0f) distance[i] = hitDistance(i, ray, t);
    }
  }

  // The half-pixel march of pixel (x, y)'s mirror ray: samples every half pixel along the major
  // axis, a quarter pixel off the pixel boundaries there (so that which pixel a sample reads does
  // not hang on rounding), each tested against the depth of the pixel it falls in.
  void marchRow(int y) {
    const float farRatio = 1.0f / (1.0f + thicknessRel);
    for (int x = 0; x < w; ++x) {
      float* out = &linearHits[3 * (size_t(y) * w + x)];
      out[0] = out[1] = out[2] = -1.0f;
      ScreenRay ray;
      vec3 dir;
      if (!mirrorRay(x, y, ray, dir)) continue;
      const float dt = 0.5f / std::max(std::fabs(ray.ds.x), std::fabs(ray.ds.y));
      for (int i = 0; (float(i) + 0.5f) * dt <= 1.0f; ++i) {
        const float t = (float(i) + 0.5f) * dt;
        const vec2 s = ray.screen(t);
        const int px = int(std::floor(s.x)), py = int(std::floor(s.y));
        if ((px == x && py == y) || px < 0 || py < 0 || px >= w || py >= h) continue;
        const float d = positions[size_t(py) * w + px].w;
        if (!(d < kNoSurface)) continue;
        const float u = ray.q0.w + t * ray.dq.w;  // 1/z: q.w = 1 / clip w, the depth (perspective)
        if (u <= 1.0f / d && u >= farRatio / d) {
          out[0] = s.x;
          out[1] = s.y;
          out[2] = u;
          break;
        }
      }
    }
  }

  PacketFrame packetFrame() const {
    PacketFrame f{w, h, &positions[0].x, &normals[0].x, reflects.data(), {}, nearPlane, farPlane, maxIterations};
    std::copy(&proj[0][0], &proj[0][0] + 16, f.projection);
    return f;
  }

  static void requirePacketTrace() {
    if (!packetTraceSupported())
      throw std::runtime_error("native packet trace: needs a CPU with AVX2 (x86-64-v3) or AVX-512");
  }

  // The min-max pyramid from setup's depths, then rows of rays in blocks traced on `threads`.
  double tracePackets(int threads, int samples, float* hits) {
    requirePacketTrace();
    if (proj[2][3] != -1.0f || proj[3][3] != 0.0f)
      throw std::invalid_argument("native packet trace: needs a perspective camera (1/z linear on screen)");
    auto start = Clock::now();
    std::fill(pyramidWords.begin(), pyramidWords.end(), 0u);  // the zero border
    pyramid.texels = pyramidWords.data();
#if defined(SSRCL_PACKET_TRACE)  // else packetTraceSupported() is false: stopped above
    pyramid.farRatio = 1.0f / (1.0f + thicknessRel);
    parallelRows(h, threads, [this](int y) { buildMinMaxLevel0(&positions[0].x, y, y + 1, pyramid); });
    for (int l = 1; l < pyramid.levelCount; ++l)
      parallelRows(pyramid.levels[l].height, threads, [this, l](int y) { buildMinMaxLevel(l, y, y + 1, pyramid); });
#endif
    packetStats = {};
    packetStats.pyramidMs = msSince(start);
    start = Clock::now();
    const PacketFrame frame = packetFrame();
    std::mutex counted;
    constexpr int kRows = 8;  // thousands of rays a call, so that lanes rarely wait for the last ones
    parallelRows((h + kRows - 1) / kRows, threads, [&](int b) {
      PacketCounters c;
      const double cpuStart = threadCpuMs();
#if defined(SSRCL_PACKET_TRACE)
      tracePacketRows(packetIsa, frame, pyramid, samples, 1u, b * kRows, std::min(h, (b + 1) * kRows), hits, c);
#endif
      const double cpu = threadCpuMs() - cpuStart;
      const std::lock_guard<std::mutex> lock(counted);
      packetStats.cpuMs += cpu;
      packetStats.rays += c.rays;
      packetStats.hits += c.hits;
      packetStats.laneSteps += c.laneSteps;
      packetStats.packetSteps += c.packetSteps;
    });
    return msSince(start);
  }

  void setTexels(TexelFormat format) {
    requirePacketTrace();
#if defined(SSRCL_PACKET_TRACE)
    if (!layoutMinMaxPyramid(w, h, format, pyramid)) throw std::invalid_argument("native packet trace: image too large");
    pyramidWords.assign(pyramid.words, 0u);
#endif
  }
};

TraceSettings nativeMirrorSettings() {
  TraceSettings s = qualityPreset("medium");
  s.constantRoughness = 0.0f;
  s.thicknessModel = ThicknessModel::Constant;
  // 1% of the depth, issue 26's rays: thinner than a half-pixel march resolves on steep rays,
  // where the min-max trace's exact overlap test would hit what its linear reference skips.
  s.thicknessRelative = 0.01f;
  return s;
}

HitAgreement compareHitPoints(const std::vector<float>& a, const std::vector<float>& b, float pixels) {
  HitAgreement h;
  for (size_t i = 0; i + 2 < std::min(a.size(), b.size()); i += 3) {
    const bool hitA = a[i] >= 0.0f, hitB = b[i] >= 0.0f;
    if (!hitA && !hitB) continue;
    ++h.hitPixels;
    h.disagreeing += hitA != hitB || std::fabs(a[i] - b[i]) > pixels || std::fabs(a[i + 1] - b[i + 1]) > pixels;
  }
  return h;
}

HitAgreement compareHitDistances(const std::vector<float>& a, const std::vector<float>& b) {
  HitAgreement h;
  for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    if (!(a[i] > 0.0f) && !(b[i] > 0.0f)) continue;
    ++h.hitPixels;
    h.disagreeing += (a[i] > 0.0f) != (b[i] > 0.0f) || std::fabs(a[i] - b[i]) > 0.01f * std::max(a[i], b[i]);
  }
  return h;
}

NativeMirrorTrace::NativeMirrorTrace(const GBuffer& gbuffer, const Camera& camera, const TraceSettings& settings)
    : impl_(nullptr) {
  if (!settings.constantRoughness && gbuffer.roughness.empty())
    throw std::invalid_argument("native mirror trace: no roughness image and no constant roughness");
  impl_ = new Impl(gbuffer, camera, settings);
  if (packetTraceSupported()) impl_->setTexels(TexelFormat::Half);
}
NativeMirrorTrace::~NativeMirrorTrace() { delete impl_; }

NativeStageMs NativeMirrorTrace::run(int threads) {
  Impl& m = *impl_;
  NativeStageMs ms;
  ms.setup = m.setup(threads);
  ms.hzb = m.reduceHzb(threads);
  const auto start = Clock::now();
  parallelRows(m.h, threads, [&m](int y) { m.traceRow(y); });
  ms.trace = msSince(start);
  m.rays = std::count(m.reflects.begin(), m.reflects.end(), 1);
  return ms;
}

FrameStageMs NativeMirrorTrace::runFrame(int threads) {
  Impl& m = *impl_;
  FrameStageMs ms;
  ms.setup = m.setup(threads);
  ms.hzb = m.reduceHzb(threads);
  auto start = Clock::now();
  if (m.adaptive) adaptiveThickness(m.w, m.h, m.positions.data(), m.planes.data(), m.rowRuns.data(), m.thicknessModel, threads);
  ms.thickness = msSince(start);
  start = Clock::now();
  buildRangePyramid(m.levels, m.invProj, m.hzb.data(), m.planes.data(), m.range.data(), threads);
  ms.rangePyramid = msSince(start);
  start = Clock::now();
  reduceColorPyramid(m.levels, m.colors.data(), threads);
  ms.colorPyramid = msSince(start);
  return ms;
}

double NativeMirrorTrace::runPackets(int threads) {
  return impl_->tracePackets(threads, 0, impl_->packetHits.data());
}

double NativeMirrorTrace::runGlossyPackets(int threads, int samplesPerPixel) {
  if (samplesPerPixel < 1) throw std::invalid_argument("native packet trace: samples per pixel must be at least 1");
  return impl_->tracePackets(threads, samplesPerPixel, nullptr);
}

void NativeMirrorTrace::setPacketTexels(TexelFormat format) { impl_->setTexels(format); }
void NativeMirrorTrace::setPacketIsa(PacketIsa isa) { impl_->packetIsa = isa; }
const PacketStats& NativeMirrorTrace::packetStats() const { return impl_->packetStats; }

void NativeMirrorTrace::runLinearMarch(int threads) {
  Impl& m = *impl_;
  parallelRows(m.h, threads, [&m](int y) { m.marchRow(y); });
}

// Compiled for any x86-64: the checks before any code of packet_hiz_trace's -march runs.
PacketIsa packetTraceIsa() {
#if defined(SSRCL_PACKET_TRACE) && defined(__clang__)
  // clang (14, 15) knows no level names, nor f16c, lzcnt or movbe, which every CPU with the rest has.
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512cd") &&
      __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
    return PacketIsa::Avx512;
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
      __builtin_cpu_supports("bmi2"))
    return PacketIsa::Avx2;
#elif defined(SSRCL_PACKET_TRACE)
  if (__builtin_cpu_supports("x86-64-v4")) return PacketIsa::Avx512;
  if (__builtin_cpu_supports("x86-64-v3")) return PacketIsa::Avx2;
#endif
  return PacketIsa::None;
}
bool packetTraceSupported() { return packetTraceIsa() != PacketIsa::None; }
const char* packetIsaName(PacketIsa isa) {
  return isa == PacketIsa::Avx512 ? "AVX-512" : isa == PacketIsa::Avx2 ? "AVX2" : "none";
}
int packetLanes(PacketIsa isa) { return isa == PacketIsa::Avx512 ? 16 : isa == PacketIsa::Avx2 ? 8 : 0; }

#if defined(SSRCL_PACKET_TRACE)
void tracePacketRows(PacketIsa isa, const PacketFrame& frame, const MinMaxPyramid& pyramid, int samples, uint32_t seed,
                     int y0, int y1, float* hitPoints, PacketCounters& counters) {
  if (isa == PacketIsa::Avx512) tracePacketRowsAvx512(frame, pyramid, samples, seed, y0, y1, hitPoints, counters);
  if (isa == PacketIsa::Avx2) tracePacketRowsAvx2(frame, pyramid, samples, seed, y0, y1, hitPoints, counters);
}
#endif

const std::vector<float>& NativeMirrorTrace::distance() const { return impl_->distance; }
const std::vector<float>& NativeMirrorTrace::packetHitPoints() const { return impl_->packetHits; }
const std::vector<float>& NativeMirrorTrace::linearHitPoints() const { return impl_->linearHits; }
long long NativeMirrorTrace::rays() const { return impl_->rays; }
const std::vector<float>& NativeMirrorTrace::hzb() const { return impl_->hzb; }
const std::vector<glm::vec4>& NativeMirrorTrace::planes() const { return impl_->planes; }
const std::vector<glm::vec2>& NativeMirrorTrace::rangePyramid() const { return impl_->range; }
const std::vector<glm::vec4>& NativeMirrorTrace::colorPyramid() const { return impl_->colors; }

}  // namespace ssrcl::bench
