// Ray generation and tracing: one work-item per (listed pixel, sample). Mirror-like pixels get
// one deterministic mirror ray; glossy pixels draw GGX visible-normal samples. Each ray is traced
// through the depth buffer (hierarchical Hi-Z, or fine linear steps) and shaded at its hit.
//
// The ray is followed in screen space: pixel position s(t) = s0 + t * ds, t in [0, 1].
// Q = P / w and k = 1 / w are affine in screen space for any projective camera (perspective or
// orthographic), so the ray's planar depth -Q.z / k at any t is exact, not interpolated.

#ifndef SSRCL_VIEWS
#define SSRCL_VIEWS 0  // 1: auxiliary views follow (kernels/view_trace.cl); ray states are written
#endif
// With a back-face depth pass (1): a ray that passes behind a surface whose back the pass gives,
// beyond that back but within the thickness the model guessed there (thickness.cl known_thickness),
// and then finds nothing, takes that surface as the guess would have: in the renderer it meets
// what is hidden behind the surface, which the screen does not hold, and the surface's colour is
// nearer that than nothing. The exact interval decides first; the guess only fills its misses.
#ifndef SSRCL_BACK_KNOWN
#define SSRCL_BACK_KNOWN 0
#endif
// The Hi-Z trace skips cells the ray crosses wholly behind every hit a pixel there allows (the
// range pyramid, back_pyramid.cl); with views such a skip records the ray's passage behind them
// (SSRCL_RAY_BEHIND), in the frame and in the views alike.
#ifndef SSRCL_TRACE_ROUND
#define SSRCL_TRACE_ROUND 64  // rays made, traced and shaded together (a work-item's, at medium)
#endif
#ifndef SSRCL_REFILL_AT
#define SSRCL_REFILL_AT 2  // a packet's idle lanes take the round's next rays once this many are idle
#endif
#ifndef SSRCL_TRACE_SCALAR
#define SSRCL_TRACE_SCALAR 0  // 1: Hi-Z a ray at a time (trace_hiz), the form the packets' lanes reproduce (tests)
#endif
// 1 on AVX2 CPUs: packets hold the levels' offsets for lane permutes (level_offsets). SSRCL_PORTABLE
// builds what other devices do, for tests/CMakeLists.txt's bit-for-bit check.
#if defined(__AVX2__) && !defined(SSRCL_PORTABLE)
#define SSRCL_LEVEL_PERMUTES 1
#else
#define SSRCL_LEVEL_PERMUTES 0
#endif
#ifndef SSRCL_MATERIAL_HITS
#define SSRCL_MATERIAL_HITS 0  // 1: hits on glossy pixels are shaded with their F0 (f0, albedo)
#endif

typedef struct {
  float2 s0, ds;
  float4 q0, dq;  // xyz = Q, w = k
} ScreenRay;

inline float4 ray_q(const ScreenRay* r, float t) { return r->q0 + t * r->dq; }
inline float3 ray_point(const ScreenRay* r, float t) { float4 q = ray_q(r, t); return q.xyz / q.w; }
inline float2 ray_screen(const ScreenRay* r, float t) { return r->s0 + t * r->ds; }

// Parameter where the ray leaves the pixel it occupies just after t (the reference tracers'
// step). The pixel is looked up slightly ahead of t so a ray sitting on a boundary counts as
// having crossed it.
inline float cell_exit(const ScreenRay* r, float t, float nudge, int2* cell_out) {
  float2 p = ray_screen(r, t + nudge);
  float2 cell = floor(p);
  *cell_out = convert_int2(cell);
  float2 boundary = cell + select((float2)(0.0f), (float2)(1.0f), isgreater(r->ds, (float2)(0.0f)));
  float2 tb = (boundary - r->s0) / r->ds;
  tb = select(tb, (float2)(INFINITY), isless(fabs(r->ds), (float2)(1e-12f)));
  return fmin(tb.x, tb.y);
}

// A row of a projection times (p, 1), rounded as written (no fused multiply-add): the screen ray's
// ends in make_screen_ray and in its lanes (ray_from_lanes) round the same, whatever dot() does.
#pragma OPENCL FP_CONTRACT OFF
inline float project_row(float4 row, float3 p) { return ((row.x * p.x + row.y * p.y) + row.z * p.z) + row.w; }
inline float8 project_lanes(float4 row, Lanes3 p) { return ((row.x * p.x + row.y * p.y) + row.z * p.z) + row.w; }
#pragma OPENCL FP_CONTRACT ON

// Screen ray for a view-space segment p0 -> p1, clipped to the screen so that t in [0, 1] spans
// its on-screen part; false when either end is behind the camera.
inline bool make_screen_ray(float16 proj, int2 size, float3 p0, float3 p1, ScreenRay* r) {
  float4 h0 = (float4)(project_row(proj.s0123, p0), project_row(proj.s4567, p0), 0.0f, project_row(proj.scdef, p0));
  float4 h1 = (float4)(project_row(proj.s0123, p1), project_row(proj.s4567, p1), 0.0f, project_row(proj.scdef, p1));
  if (!(h0.w > 0.0f && h1.w > 0.0f)) return false;
  float k0 = 1.0f / h0.w, k1 = 1.0f / h1.w;
  r->s0 = ndc_to_pixel(h0.xy * k0, size);
  r->ds = ndc_to_pixel(h1.xy * k1, size) - r->s0;
  r->q0 = (float4)(p0 * k0, k0);
  r->dq = (float4)(p1 * k1, k1) - r->q0;
  float2 edge = select((float2)(0.0f), convert_float2(size), isgreater(r->ds, (float2)(0.0f)));
  float2 te = (edge - r->s0) / r->ds;
  te = select(te, (float2)(INFINITY), isless(fabs(r->ds), (float2)(1e-12f)));
  // The far end of a long segment can project millions of pixels away; rescaling keeps t's
  // float resolution well under a pixel.
  float t_max = fmin(1.0f, fmin(te.x, te.y));
  r->ds *= t_max;
  r->dq *= t_max;
  return isfinite(r->s0.x) && isfinite(r->s0.y) && isfinite(r->ds.x) && isfinite(r->ds.y);
}

typedef struct {
  int2 size;
  __global const HzbLevel* levels;
  int level_count;
  __global const float4* planes;   // per pixel, scaled by its thickness (surface_plane.cl)
  __global const float4* normals;  // roughness in w, for the hit's colour lookup
  int max_iterations;
  int iterations;  // work done by this ray, for the counting mode
  int fetches;     // depth-buffer texels read (HZB texels, or a pixel's plane record)
  // SSRCL_VIEWS only: the ray was seen in front of a surface; it then passed behind one it did not
  // hit (a ray that starts hidden, as from a surface a view sees from behind, is not held to it
  // until it comes into view); its hit was found within a surface's thickness.
  int seen, behind, thick;
  __global const float2* range;  // the range pyramid (Hi-Z, back_pyramid.cl): y = farthest hit
  __global const float* guess;   // SSRCL_BACK_KNOWN: the model's thickness in exact ones (0: back unknown)
  // SSRCL_BACK_KNOWN: the first surface the ray passed behind within its guess (past), where.
  int past;
  float past_t;
  int2 past_cell;
  // SSRCL_VIEWS only: the ray was behind a pixel's surface somewhere on its way (facing it or not).
  int hidden;
  // The hit is where the ray entered a surface through its back (hit_pixel).
  int entered;
  // Rays may enter surfaces through their backs: in the frame's own trace. A view (view_trace.cl)
  // is there to find what the frame hides, and its rays go on behind the surfaces it shows
  // (test_multiview's exact hidden and off-screen hits: 0.812 and 0.953; 0.780 and 0.944 with
  // entries in the views).
  int enters;
} TraceScene;

// The ray's signed distance to a pixel's plane (n, dot(p, n)) / thickness, in thicknesses, times
// k = 1 / w (> 0 in front of the camera): affine in t, so its sign and root are exact.
inline float plane_side(const ScreenRay* r, float t, float4 plane) {
  float4 q = ray_q(r, t);
  return dot(q.xyz, plane.xyz) - q.w * plane.w;
}

// Whether a ray may enter a pixel's surface through its back where it stands at view-space point q
// (|n.q|, |n|^2, |q|^2 given): not through a plane seen within SSRCL_ENTRY_MIN_COS of edge-on. Over
// its pixel such a plane runs far from the surface the pixel shows (at a sphere's silhouette, its
// tangent plane): rays that left a sphere entered its silhouette pixels' backs and took their black,
// 2.6% of an analytic mirror frame's exact misses (0.2% with the bound); the real corpus's entries
// (a table top's, a stool's underside) are through planes seen 6 degrees and more from edge-on.
#define SSRCL_ENTRY_MIN_COS 0.1f
inline int entry_facing(float nq, float nn, float qq) { return nq >= SSRCL_ENTRY_MIN_COS * sqrt(nn) * sqrt(qq); }
inline int8 entry_facing8(float8 nq, float8 nn, float8 qq) { return nq >= SSRCL_ENTRY_MIN_COS * sqrt(nn) * sqrt(qq); }

// The exact test against one pixel's surface (the plane through its point with its normal) for
// the ray's stretch [t_in, t_out] over that pixel: a hit where the ray crosses the plane from its
// front, or where it is already behind by less than the thickness (surfaces are assumed that
// thick). Surfaces facing away from the ray cannot be reached from their front, only through their
// back. Returns the hit's t or -1;
// *in_front tells whether the ray leaves the stretch in front of the surface.
inline float hit_pixel(TraceScene* sc, const ScreenRay* ray, float3 dir, int2 cell, float t_in, float t_out,
                       bool* in_front) {
  cell = clamp(cell, (int2)(0, 0), sc->size - 1);
  ++sc->fetches;
  float4 plane = sc->planes[cell.y * sc->size.x + cell.x];
  *in_front = true;
  if (plane.w == -INFINITY) {  // SSRCL_NO_PLANE
#if SSRCL_VIEWS
    sc->seen = 1;  // over the sky
#endif
    return -1.0f;
  }
  float g_in = plane_side(ray, t_in, plane), g_out = plane_side(ray, t_out, plane);
  *in_front = g_out > 0.0f;
#if SSRCL_VIEWS
  if (g_in <= 0.0f || g_out <= 0.0f) sc->hidden = 1;
#endif
  if (!(dot(plane.xyz, dir) < 0.0f)) {
    // A surface facing away is still solid, as thick as its record says (the back-face pass's exact
    // back where it gives one, the thickness model's guess elsewhere): a ray that enters it through
    // its back (from behind the back to within the thickness: h = g + k goes from < 0 to >= 0) stops
    // there, on a face the screen does not show (shaded black: trace_rays), as a ray from a floor
    // meets a table top's underside. docs/BENCHMARKS.md "Rays that enter a surface's back".
    const float4 q_in = ray_q(ray, t_in);
    const float h_in = g_in + q_in.w, h_out = g_out + ray_q(ray, t_out).w;
    if (sc->enters && h_in < 0.0f && h_out >= 0.0f &&
        entry_facing(fabs(dot(plane.xyz, q_in.xyz)), dot(plane.xyz, plane.xyz), dot(q_in.xyz, q_in.xyz))) {
      sc->entered = 1;
#if SSRCL_VIEWS
      sc->thick = 1;  // a face no pass shows: a view that sees the ray's whole way may replace it
#endif
      return t_in + (t_out - t_in) * (h_in / (h_in - h_out));
    }
    return -1.0f;
  }
  if (g_in > 0.0f && g_out <= 0.0f) return t_in + (t_out - t_in) * (g_in / (g_in - g_out));
  // Behind by at most one thickness: -g_in / k <= 1, k > 0.
  if (g_in <= 0.0f && -g_in <= ray_q(ray, t_in).w) {
#if SSRCL_VIEWS
    sc->thick = 1;
#endif
    return t_in;
  }
#if SSRCL_VIEWS
  if (*in_front) sc->seen = 1;
  else if (sc->seen) sc->behind = 1;
#endif
#if SSRCL_BACK_KNOWN
  if (!*in_front && !sc->past && -g_in <= sc->guess[cell.y * sc->size.x + cell.x] * ray_q(ray, t_in).w) {
    sc->past = 1;
    sc->past_t = t_in;
    sc->past_cell = cell;
  }
#endif
  return -1.0f;
}

// The depths at which a ray over cell `cell` of level `level` may hit: from the nearest surface
// there (x) to the farthest a hit allows (y): the range pyramid's texel.
inline float2 cell_range(const TraceScene* sc, int level, int2 cell) {
  return sc->range[pyramid_index(sc->levels, level, cell)];
}

#if SSRCL_VIEWS
// What hit_pixel records of a cell the ray does not meet, for the views: wholly beyond every hit
// its pixels allow, the ray passed behind their surfaces (hidden there); wholly in front of a
// pixel's surface, it was seen.
inline void passed_cell(TraceScene* sc, int level, bool beyond, bool before) {
  if (beyond) {
    sc->hidden = 1;
    if (sc->seen) sc->behind = 1;
  } else if (before && level == 0) {
    sc->seen = 1;
  }
}
#endif

// A cell's side as a float: 2^level from the exponent bits.
inline float cell_size(int level) { return as_float((level + 127) << 23); }

// Hierarchical traversal (FidelityFX SSSR style), stepped as a native packet tracer steps: cells are
// integers, their boundaries found from the ray's reciprocal screen direction (t at x = (x - s0.x) * ix),
// and at every level one test, whether the ray's depth over its stretch of the cell meets the cell's
// range. A coarse cell it meets is entered a level finer where the ray reaches the range's near end;
// a pixel it meets is decided by hit_pixel; a cell it misses is left for the next one along, up as
// many levels (at most two) as that step leaves parents. A pixel whose surface the ray passed
// behind within reach keeps it fine. With views every pixel is tested (hit_pixel records the ray's
// passage behind surfaces).
// Returns the hit's t, or a negative value on a miss.
inline float trace_hiz(TraceScene* sc, const ScreenRay* ray, float3 dir, int2* hit_cell) {
  const int top = sc->level_count - 1;
  // A still axis never reaches a boundary: its boundary t are huge (ix > 0: the one ahead is above).
  const float ix = fabs(ray->ds.x) < 1e-12f ? 1e30f : 1.0f / ray->ds.x;
  const float iy = fabs(ray->ds.y) < 1e-12f ? 1e30f : 1.0f / ray->ds.y;
  const int px = ix > 0.0f, py = iy > 0.0f;  // 1 where the ray goes to +x, +y
  const bool deeper = ray->q0.z * ray->dq.w - ray->dq.z * ray->q0.w > 0.0f;  // depth grows with t
  // Leave the origin pixel first.
  int2 c = convert_int2(floor(ray->s0));
  float tx = ((float)(c.x + px) - ray->s0.x) * ix, ty = ((float)(c.y + py) - ray->s0.y) * iy;
  c = tx <= ty ? (int2)(c.x + 2 * px - 1, c.y) : (int2)(c.x, c.y + 2 * py - 1);
  float t = fmin(tx, ty);
  float d_t = -(ray->q0.z + t * ray->dq.z) / (ray->q0.w + t * ray->dq.w);
  int level = 0;
  for (; sc->iterations < sc->max_iterations && t <= 1.0f; ++sc->iterations) {
    const float size = cell_size(level);
    tx = ((float)(c.x + px) * size - ray->s0.x) * ix;
    ty = ((float)(c.y + py) * size - ray->s0.y) * iy;
    const float t_exit = fmin(tx, ty), t_end = fmin(t_exit, 1.0f);
    const float d_end = -(ray->q0.z + t_end * ray->dq.z) / (ray->q0.w + t_end * ray->dq.w);
    ++sc->fetches;
    const float2 range = cell_range(sc, level, c);
    const bool meets = fmax(d_t, d_end) >= range.x && fmin(d_t, d_end) <= range.y;
#if SSRCL_VIEWS
    passed_cell(sc, level, fmin(d_t, d_end) > range.y, fmax(d_t, d_end) < range.x);
#endif
    bool stay = false;
    if (level == 0 && meets) {
      bool in_front;
      float t_hit = hit_pixel(sc, ray, dir, c, t, t_end, &in_front);
      if (t_hit >= 0.0f) {
        *hit_cell = c;
        return t_hit;
      }
      stay = !in_front && d_end <= range.y;
    } else if (level > 0 && meets) {
      const float t_cross = -(ray->q0.z + range.x * ray->q0.w) / (ray->dq.z + range.x * ray->dq.w);
      if (d_t < range.x && deeper && isfinite(t_cross)) {
        t = fmax(t, fmin(t_cross, t_end));
        d_t = range.x;
      }
      // The child holding the ray at t: past the cell's middle along the ray, the one ahead.
      const float half_size = 0.5f * size;
      const float mid_x = ((float)(2 * c.x + 1) * half_size - ray->s0.x) * ix;
      const float mid_y = ((float)(2 * c.y + 1) * half_size - ray->s0.y) * iy;
      c = (int2)(2 * c.x + (t >= mid_x ? px : px ^ 1), 2 * c.y + (t >= mid_y ? py : py ^ 1));
      --level;
      continue;
    }
    const int2 next = tx <= ty ? (int2)(c.x + 2 * px - 1, c.y) : (int2)(c.x, c.y + 2 * py - 1);
    const int up = stay ? 0 : min(min(31 - (int)clz((next.x ^ c.x) | (next.y ^ c.y)), 2), top - level);
    c = next >> up;
    level += up;
    t = t_exit;
    d_t = d_end;
  }
  return -1.0f;
}

// trace_hiz for eight rays at once, one per float8 lane. PoCL runs each
// work-item's loop as scalar code (its loop exits per ray, so its vectoriser cannot run it across
// work-items); lanes bring the vector units in by hand. Each lane evaluates trace_hiz's and
// hit_pixel's expressions in the same form and order, so it rounds as the scalar code does and
// finds the same hits. A lane's finished ray idles until all eight are done.
typedef struct {
  float8 s0x, s0y, dsx, dsy, q0x, q0y, q0z, q0w, dqx, dqy, dqz, dqw;
} ScreenRays8;

// Eight float2 records as two float8s, a gather each (scattered_record_lanes).
inline float8 gather8_xy(__global const float2* a, int8 i, float8* y) {
  __global const float* f = (__global const float*)a;
  *y = gather8(f, 2 * i + 1);
  return gather8(f, 2 * i);
}

// plane_side per lane.
inline float8 plane_side8(const ScreenRays8* r, float8 t, float8 px, float8 py, float8 pz, float8 pw) {
  float8 qx = r->q0x + t * r->dqx, qy = r->q0y + t * r->dqy, qz = r->q0z + t * r->dqz, qw = r->q0w + t * r->dqw;
  return dot_lanes(qx, qy, qz, px, py, pz) - qw * pw;
}

// hit_pixel per lane, for the lanes in `lanes` (the others' results are not used). Inlined into the
// packet step, as scattered_record_lanes is (PoCL's inliner left both calls).
__attribute__((always_inline)) inline float8 hit_pixel8(const TraceScene* sc, const ScreenRays8* r, float8 dx,
                                                       float8 dy, float8 dz, int8 cx, int8 cy, float8 t_in,
                                                       float8 t_out, int8 lanes, int8* in_front, int8* seen,
                                                       int8* behind, int8* thick, int8* hidden, int8* past,
                                                       float8* g_past, int8* entered, float8* guess) {
  int8 q = clamp(cy, 0, sc->size.y - 1) * sc->size.x + clamp(cx, 0, sc->size.x - 1);
  const RecordLanes plane = scattered_record_lanes(sc->planes, q);
  const float8 px = plane.x, py = plane.y, pz = plane.z, pw = plane.w;
  int8 sky = pw == -INFINITY;  // SSRCL_NO_PLANE
  float8 g_in = plane_side8(r, t_in, px, py, pz, pw), g_out = plane_side8(r, t_out, px, py, pz, pw);
  *in_front = sky | (g_out > 0.0f);
  int8 facing = ~sky & (dot_lanes(px, py, pz, dx, dy, dz) < 0.0f);
  float8 k_in = r->q0w + t_in * r->dqw;  // 1 / w where the stretch starts: a thickness there
  int8 crossing = facing & (g_in > 0.0f) & (g_out <= 0.0f);
  int8 within = facing & ~crossing & (g_in <= 0.0f) & (-g_in <= k_in);
  int8 passed = lanes & facing & ~crossing & ~within;
  *behind |= passed & ~*in_front & *seen;
  *seen |= (lanes & sky) | (passed & *in_front);
  *thick |= lanes & within;
  *hidden |= lanes & ~sky & ((g_in <= 0.0f) | (g_out <= 0.0f));
  *past = passed & ~*in_front;  // behind by more than its thickness
  *g_past = g_in;
  float8 t_hit = select((float8)(-1.0f), t_in, within);
#if SSRCL_BACK_KNOWN
  *guess = gather8(sc->guess, q);
#endif
  {  // hit_pixel's entry through a surface's back
    float8 h_in = g_in + k_in, h_out = g_out + (r->q0w + t_out * r->dqw);
    int8 entry = sc->enters ? lanes & ~sky & ~facing & (h_in < 0.0f) & (h_out >= 0.0f) : (int8)(0);
    if (any_lane(entry)) {  // rare: the plane's angle only then
      const float8 qx = r->q0x + t_in * r->dqx, qy = r->q0y + t_in * r->dqy, qz = r->q0z + t_in * r->dqz;
      entry &= entry_facing8(fabs(dot_lanes(px, py, pz, qx, qy, qz)), dot_lanes(px, py, pz, px, py, pz),
                            dot_lanes(qx, qy, qz, qx, qy, qz));
    }
    *entered = entry;
    *thick |= entry;  // as hit_pixel's
    t_hit = select(t_hit, t_in + (t_out - t_in) * (h_in / (h_in - h_out)), entry);
  }
  return select(t_hit, t_in + (t_out - t_in) * (g_in / (g_in - g_out)), crossing);
}

// hit_pixel's record of the first surface a ray passed behind within its guess, per lane: the lanes
// `now` passing behind their pixel's surface (by g, hit_pixel8's g_in; guess, its pixel's guess)
// that have none yet.
inline void note_past_back8(const ScreenRays8* r, int8 now, float8 g, float8 guess, int8 cx, int8 cy, float8 t,
                            int8* past, float8* past_t, int8* past_x, int8* past_y) {
  now &= ~*past;
  now &= -g <= guess * (r->q0w + t * r->dqw);
  *past |= now;
  *past_t = select(*past_t, t, now);
  *past_x = select(*past_x, cx, now);
  *past_y = select(*past_y, cy, now);
}

// A packet: eight rays in float8 lanes and where each stands (trace_hiz's variables per lane).
typedef struct {
  ScreenRays8 r;
  float8 dx, dy, dz, ix, iy, t, d_t, t_hit;
  int8 px, py, cx, cy, level, deeper, active, iterations, fetches, hit_x, hit_y, seen, behind, thick, hidden, entered;
  int8 past, past_x, past_y;  // SSRCL_BACK_KNOWN: TraceScene's past, per lane
  float8 past_t;
  int8 slot;  // the round's ray in each lane, -1 for none
#if SSRCL_LEVEL_PERMUTES
  int8 offsets_low, offsets_high;  // the levels' offsets 0-7 and 8-15 (level_offsets)
#endif
} Packet8;

// Where each lane's level starts in the pyramids. On AVX2, from the levels' offsets held in two
// vectors by two lane permutes (vpermd): the read of `levels` that stands in for them elsewhere is
// eight scalar loads there (LLVM forms no gathers for it), at the head of each step's chain of
// dependent reads. Other devices read `levels` (and keep their registers).
inline int8 level_offsets(const Packet8* p, const TraceScene* sc) {
#if SSRCL_LEVEL_PERMUTES
  if (sc->level_count <= 16)
    return select(__builtin_ia32_permvarsi256(p->offsets_low, p->level),
                  __builtin_ia32_permvarsi256(p->offsets_high, p->level), p->level > 7);
#endif
  return as_int8(gather8((__global const float*)sc->levels, p->level * (int)(sizeof(HzbLevel) / sizeof(int))));
}

// The lanes of `m` start the rays packet_fill put in them: where each leaves its pixel, and its
// records cleared.
inline void packet_derive(Packet8* p, int8 m) {
  const ScreenRays8 r = p->r;
  const float8 ix = select(1.0f / r.dsx, (float8)(1e30f), fabs(r.dsx) < 1e-12f);
  const float8 iy = select(1.0f / r.dsy, (float8)(1e30f), fabs(r.dsy) < 1e-12f);
  const int8 px = select((int8)(0), (int8)(1), ix > 0.0f), py = select((int8)(0), (int8)(1), iy > 0.0f);
  const int8 x = convert_int8(floor(r.s0x)), y = convert_int8(floor(r.s0y));
  const float8 tx = (convert_float8(x + px) - r.s0x) * ix, ty = (convert_float8(y + py) - r.s0y) * iy;
  const int8 step_x = tx <= ty;
  const float8 t = fmin(tx, ty);
  p->ix = select(p->ix, ix, m);
  p->iy = select(p->iy, iy, m);
  p->px = select(p->px, px, m);
  p->py = select(p->py, py, m);
  p->deeper = select(p->deeper, r.q0z * r.dqw - r.dqz * r.q0w > 0.0f, m);
  p->cx = select(p->cx, select(x, x + 2 * px - 1, step_x), m);
  p->cy = select(p->cy, select(y + 2 * py - 1, y, step_x), m);
  p->t = select(p->t, t, m);
  p->d_t = select(p->d_t, -(r.q0z + t * r.dqz) / (r.q0w + t * r.dqw), m);
  p->fetches = select(p->fetches, 0, m);
  p->behind = select(p->behind, 0, m);
  p->thick = select(p->thick, 0, m);
  p->hidden = select(p->hidden, 0, m);
  p->entered = select(p->entered, 0, m);
  p->past = select(p->past, 0, m);
  p->past_x = select(p->past_x, 0, m);
  p->past_y = select(p->past_y, 0, m);
  p->past_t = select(p->past_t, -1.0f, m);
  p->level = select(p->level, 0, m);
  p->hit_x = select(p->hit_x, 0, m);
  p->hit_y = select(p->hit_y, 0, m);
  p->t_hit = select(p->t_hit, -1.0f, m);
  p->active |= m;
}

// The results of the lanes in `m`, each to its round slot: t_hit[i] the hit's t or -1,
// hit_cell[i] the pixel hit, and sc[i] counts the ray's work and its views flags.
inline void packet_end(const Packet8* p, TraceScene* sc, int8 m, float* t_hit_out, int2* hit_cell) {
  float t_lane[8], past_t[8];
  int lanes[8], slot[8], x[8], y[8], iterations[8], fetches[8], seen[8], behind[8], thick[8], hidden[8],
      entered[8], past[8], past_x[8], past_y[8];
  vstore8(m, 0, lanes);
  vstore8(p->slot, 0, slot);
  vstore8(p->t_hit, 0, t_lane);
  vstore8(p->hit_x, 0, x);
  vstore8(p->hit_y, 0, y);
  vstore8(p->iterations, 0, iterations);
  vstore8(p->fetches, 0, fetches);
  vstore8(p->entered, 0, entered);
#if SSRCL_BACK_KNOWN
  vstore8(p->past, 0, past);
  vstore8(p->past_x, 0, past_x);
  vstore8(p->past_y, 0, past_y);
  vstore8(p->past_t, 0, past_t);
#endif
#if SSRCL_VIEWS
  vstore8(p->seen, 0, seen);
  vstore8(p->behind, 0, behind);
  vstore8(p->thick, 0, thick);
  vstore8(p->hidden, 0, hidden);
#endif
  for (int j = 0; j < 8; ++j) {
    if (!lanes[j]) continue;
    const int i = slot[j];
    t_hit_out[i] = t_lane[j];
    hit_cell[i] = (int2)(x[j], y[j]);
    sc[i].iterations = iterations[j];
    sc[i].entered = entered[j] != 0;
    sc[i].fetches += fetches[j];
#if SSRCL_BACK_KNOWN
    sc[i].past = past[j] != 0;
    sc[i].past_t = past_t[j];
    sc[i].past_cell = (int2)(past_x[j], past_y[j]);
#endif
#if SSRCL_VIEWS
    sc[i].seen = seen[j] != 0;
    sc[i].behind |= behind[j] != 0;
    sc[i].thick |= thick[j] != 0;
    sc[i].hidden |= hidden[j] != 0;
#endif
  }
}

// The packet's idle lanes: the results of the rays they finished written, then the round's next
// live rays from `next` on started in them, a lane at a time by selects. Returns the next ray not
// started.
inline int packet_fill(Packet8* p, TraceScene* sc, const ScreenRay* rays, const float3* dirs, const int* live,
                       int next, float* t_hit_out, int2* hit_cell) {
  const int8 idle = p->active == 0;
  packet_end(p, sc, idle & (p->slot >= 0), t_hit_out, hit_cell);
  p->slot = select(p->slot, -1, idle);
  int idle_lane[8];
  vstore8(idle, 0, idle_lane);
  int8 started = 0;
  for (int j = 0; j < 8; ++j) {
    if (!idle_lane[j]) continue;
    while (next < SSRCL_TRACE_ROUND && !live[next]) ++next;
    if (next == SSRCL_TRACE_ROUND) break;
    const int i = next++;
    const ScreenRay r = rays[i];
    const float3 d = dirs[i];
    const int8 at = (int8)(0, 1, 2, 3, 4, 5, 6, 7) == j;
    p->r.s0x = select(p->r.s0x, (float8)(r.s0.x), at), p->r.s0y = select(p->r.s0y, (float8)(r.s0.y), at);
    p->r.dsx = select(p->r.dsx, (float8)(r.ds.x), at), p->r.dsy = select(p->r.dsy, (float8)(r.ds.y), at);
    p->r.q0x = select(p->r.q0x, (float8)(r.q0.x), at), p->r.q0y = select(p->r.q0y, (float8)(r.q0.y), at);
    p->r.q0z = select(p->r.q0z, (float8)(r.q0.z), at), p->r.q0w = select(p->r.q0w, (float8)(r.q0.w), at);
    p->r.dqx = select(p->r.dqx, (float8)(r.dq.x), at), p->r.dqy = select(p->r.dqy, (float8)(r.dq.y), at);
    p->r.dqz = select(p->r.dqz, (float8)(r.dq.z), at), p->r.dqw = select(p->r.dqw, (float8)(r.dq.w), at);
    p->dx = select(p->dx, (float8)(d.x), at), p->dy = select(p->dy, (float8)(d.y), at);
    p->dz = select(p->dz, (float8)(d.z), at);
    p->iterations = select(p->iterations, (int8)(sc[i].iterations), at);
    p->seen = select(p->seen, (int8)(sc[i].seen ? -1 : 0), at);
    p->slot = select(p->slot, (int8)(i), at);
    started |= at;
  }
  packet_derive(p, started);
  return next;
}

// One step of the packet's live lanes; false once none is left. Inlined into trace_hiz_packets's
// loop of steps, which calls nothing else, so the compiler keeps the packet's state in registers
// across steps where a call made it store and reload it each step (docs/BENCHMARKS.md).
__attribute__((always_inline)) inline bool packet_step(Packet8* p, const TraceScene* sc) {
  const int top = sc->level_count - 1;
  p->active &= (p->iterations < sc->max_iterations) & (p->t <= 1.0f);
  if (!any_lane(p->active)) return false;
  const float8 size = as_float8((p->level + 127) << 23);  // cell_size
  const float8 tx = (convert_float8(p->cx + p->px) * size - p->r.s0x) * p->ix;
  const float8 ty = (convert_float8(p->cy + p->py) * size - p->r.s0y) * p->iy;
  const float8 t_exit = fmin(tx, ty), t_end = fmin(t_exit, 1.0f);
  const float8 d_end = -(p->r.q0z + t_end * p->r.dqz) / (p->r.q0w + t_end * p->r.dqw);
  // cell_range: a level is ceil(fine / 2) of the one below (stage_support.cpp), its size by shifts,
  // its offset by level_offsets.
  const int8 width = ((int8)(sc->size.x) + ((int8)(1) << p->level) - 1) >> p->level;
  const int8 height = ((int8)(sc->size.y) + ((int8)(1) << p->level) - 1) >> p->level;
  const int8 texel = level_offsets(p, sc) + clamp(p->cy, 0, height - 1) * width + clamp(p->cx, 0, width - 1);
  float8 hi;
  const float8 lo = gather8_xy(sc->range, texel, &hi);
  if (SSRCL_COUNT_WORK) p->fetches -= p->active;  // counted only where they are read
  const int8 meets = p->active & (fmax(p->d_t, d_end) >= lo) & (fmin(p->d_t, d_end) <= hi);
  const int8 fine = p->level == 0;
#if SSRCL_VIEWS
  {  // passed_cell per lane
    const int8 beyond = p->active & (fmin(p->d_t, d_end) > hi);
    p->hidden |= beyond;
    p->behind |= beyond & p->seen;
    p->seen |= p->active & fine & ~beyond & (fmax(p->d_t, d_end) < lo);
  }
#endif
  int8 hit = 0, stay = 0;
  // On whether any lane is fine, known before the range texel arrives: a branch on the texel
  // would wait for it (5% of the trace).
  if (any_lane(fine & p->active)) {
    const int8 test = fine & meets;
    int8 in_front, past_now, entered_now = 0;
    float8 g_past, guess;
    // The views' records, kept in the packet only where views read them (else left for dead here).
    int8 seen = p->seen, behind = p->behind, thick = p->thick, hidden = p->hidden;
    float8 t_pixel = hit_pixel8(sc, &p->r, p->dx, p->dy, p->dz, p->cx, p->cy, p->t, t_end, test, &in_front, &seen,
                                &behind, &thick, &hidden, &past_now, &g_past, &entered_now, &guess);
#if SSRCL_VIEWS
    p->seen = seen;
    p->behind = behind;
    p->thick = thick;
    p->hidden = hidden;
#endif
#if SSRCL_BACK_KNOWN
    note_past_back8(&p->r, past_now, g_past, guess, p->cx, p->cy, p->t, &p->past, &p->past_t, &p->past_x, &p->past_y);
#endif
    if (SSRCL_COUNT_WORK) p->fetches -= test;
    hit = test & (t_pixel >= 0.0f);
    stay = test & ~in_front & (d_end <= hi);
    p->entered |= hit & entered_now;
    p->t_hit = select(p->t_hit, t_pixel, hit);
    p->hit_x = select(p->hit_x, p->cx, hit);
    p->hit_y = select(p->hit_y, p->cy, hit);
  }
  // A coarse cell the ray meets: its child at t, or where the ray reaches the near end.
  const int8 descend = meets & ~fine;
  const float8 t_cross = -(p->r.q0z + lo * p->r.q0w) / (p->r.dqz + lo * p->r.dqw);
  const int8 crossing = (p->d_t < lo) & p->deeper & isfinite(t_cross);
  const float8 t_down = select(p->t, fmax(p->t, fmin(t_cross, t_end)), crossing);
  const float8 half_size = 0.5f * size;
  const int8 cx2 = p->cx + p->cx, cy2 = p->cy + p->cy;
  const float8 mid_x = (convert_float8(cx2 + 1) * half_size - p->r.s0x) * p->ix;
  const float8 mid_y = (convert_float8(cy2 + 1) * half_size - p->r.s0y) * p->iy;
  const int8 child_x = cx2 + select(p->px ^ 1, p->px, t_down >= mid_x);
  const int8 child_y = cy2 + select(p->py ^ 1, p->py, t_down >= mid_y);
  // Any other live lane: the next cell along, up as many levels as it leaves parents.
  const int8 move = p->active & ~hit & ~descend;
  const int8 step_x = tx <= ty;
  int8 next_x = select(p->cx, p->cx + 2 * p->px - 1, step_x), next_y = select(p->cy + 2 * p->py - 1, p->cy, step_x);
  // trace_hiz's min(31 - clz(d), 2) for the bits d in which the next cell differs (d != 0) by two
  // unsigned compares: AVX2 has no vector clz, and PoCL built one from ~70 instructions a step.
  const uint8 d = as_uint8((next_x ^ p->cx) | (next_y ^ p->cy));
  int8 up = min(-(d > 1u) - (d > 3u), top - p->level);
  up = select(up, 0, stay);
  p->cx = select(select(p->cx, child_x, descend), next_x >> up, move);
  p->cy = select(select(p->cy, child_y, descend), next_y >> up, move);
  p->level = select(select(p->level, p->level - 1, descend), p->level + up, move);
  p->d_t = select(select(p->d_t, select(p->d_t, lo, crossing), descend), d_end, move);
  p->t = select(select(p->t, t_down, descend), t_exit, move);
  p->active &= ~hit;
  p->iterations -= p->active;
  return true;
}

// Traces the round's live rays in a packet of eight lanes. A lane whose ray is done idles until
// SSRCL_REFILL_AT of the packet's lanes are, then they take the round's next rays: with the eight
// lanes held until all were done, half the lanes stepped idle (docs/BENCHMARKS.md, "Lanes that take
// the next ray").
inline void trace_hiz_packets(TraceScene* sc, const ScreenRay* rays, const float3* dirs, const int* live,
                              float* t_hit_out, int2* hit_cell) {
  Packet8 packet = {0};  // idle lanes step too: their cells and levels must be in range
#if SSRCL_LEVEL_PERMUTES
  int offsets[16];
  for (int l = 0; l < 16; ++l) offsets[l] = l < sc->level_count ? sc->levels[l].offset : 0;
  packet.offsets_low = vload8(0, offsets);
  packet.offsets_high = vload8(1, offsets);
#endif
  packet.slot = -1;
  int next = packet_fill(&packet, sc, rays, dirs, live, 0, t_hit_out, hit_cell);
  // Steps until the idle lanes are to be refilled or none is live (its steps or its screen run out).
  for (;;) {
    while (!(next < SSRCL_TRACE_ROUND && count_lanes(packet.active == 0) >= SSRCL_REFILL_AT) &&
           packet_step(&packet, sc)) {
    }
    if (next == SSRCL_TRACE_ROUND) break;
    next = packet_fill(&packet, sc, rays, dirs, live, next, t_hit_out, hit_cell);
  }
  packet_end(&packet, sc, packet.slot >= 0, t_hit_out, hit_cell);
}

// Fixed steps of `step_pixels` along the major screen axis, each tested with hit_pixel against
// the pixel it lands in: no hierarchy that could skip a thin feature, the reference tracer.
inline float trace_linear(TraceScene* sc, const ScreenRay* ray, float3 dir, float step_pixels, int2* hit_cell) {
  float major = fmax(fabs(ray->ds.x), fabs(ray->ds.y));
  int2 cell;
  float t_prev = cell_exit(ray, 0.0f, 0.01f / major, &cell);  // leave the origin pixel first
  float dt = step_pixels / major;
  int steps = min((int)ceil((1.0f - t_prev) / dt), sc->max_iterations);
  for (int k = 1; k <= steps; ++k, ++sc->iterations) {
    float t = fmin(t_prev + dt, 1.0f);
    cell = convert_int2(floor(ray_screen(ray, t)));
    bool in_front;
    float t_hit = hit_pixel(sc, ray, dir, cell, t_prev, t, &in_front);
    if (t_hit >= 0.0f) {
      *hit_cell = cell;
      return t_hit;
    }
    t_prev = t;
  }
  return -1.0f;
}

// Perspective-correct DDA (McGuire and Mara 2014): visits every pixel the ray's screen line
// crosses, in order, each tested with hit_pixel. Exhaustive at full resolution like the linear
// march, with one test per pixel instead of one per step.
inline float trace_dda(TraceScene* sc, const ScreenRay* ray, float3 dir, int2* hit_cell) {
  float nudge = 0.01f / fmax(fabs(ray->ds.x), fabs(ray->ds.y));
  int2 cell;
  float t = cell_exit(ray, 0.0f, nudge, &cell);  // leave the origin pixel first
  for (; sc->iterations < sc->max_iterations && t <= 1.0f; ++sc->iterations) {
    float t_exit = cell_exit(ray, t, nudge, &cell);
    bool in_front;
    float t_hit = hit_pixel(sc, ray, dir, cell, t, fmin(t_exit, 1.0f), &in_front);
    if (t_hit >= 0.0f) {
      *hit_cell = cell;
      return t_hit;
    }
    t = t_exit;
  }
  return -1.0f;
}

// The screen ray of the view-space segment p0 -> p1 (both in front of the camera); false where
// it has no on-screen length to trace.
inline bool segment_ray(float16 proj, int2 size, float3 p0, float3 p1, ScreenRay* ray) {
  return make_screen_ray(proj, size, p0, p1, ray) && fmax(fabs(ray->ds.x), fabs(ray->ds.y)) > 0.0f;
}

// Traces a screen ray with direction dir by the program's tracer.
inline float trace_ray(TraceScene* sc, float linear_step, const ScreenRay* ray, float3 dir, int2* cell) {
#if SSRCL_TRACER == SSRCL_TRACER_LINEAR
  return trace_linear(sc, ray, dir, linear_step, cell);
#elif SSRCL_TRACER == SSRCL_TRACER_DDA
  return trace_dda(sc, ray, dir, cell);
#else
  return trace_hiz(sc, ray, dir, cell);
#endif
}

// The screen ray from view-space point p along unit direction dir: the segment ends at the near
// plane for rays toward the camera, at the far plane otherwise, capped so an infinite far plane
// still gives a finite end. False where there is nothing on screen to trace.
inline bool ray_from(float16 proj, int2 size, float near_plane, float far_plane, float3 p, float3 dir,
                     ScreenRay* ray) {
  float length_max = 1e6f * -p.z;
  float len = dir.z > 0.0f ? (-near_plane * 1.001f - p.z) / dir.z
            : dir.z < 0.0f ? (-far_plane - p.z) / dir.z : length_max;
  len = fmin(len, length_max);
  return len > 0.0f && segment_ray(proj, size, p, p + dir * len, ray);
}

// ray_from for eight rays, one per lane, in the same expressions and order (ray_from,
// segment_ray, make_screen_ray): the lanes whose screen ray is live, and their rays.
inline int8 ray_from_lanes(float16 proj, int2 size, float near_plane, float far_plane, Lanes3 p, Lanes3 dir,
                           ScreenRays8* r) {
  float8 length_max = 1e6f * -p.z;
  float8 len = select(select(length_max, (-far_plane - p.z) / dir.z, dir.z < 0.0f),
                      fma((float8)(-near_plane), (float8)(1.001f), -p.z) / dir.z, dir.z > 0.0f);
  len = fmin(len, length_max);
  Lanes3 p1 = lanes3(p.x + dir.x * len, p.y + dir.y * len, p.z + dir.z * len);
  float8 w0 = project_lanes(proj.scdef, p), w1 = project_lanes(proj.scdef, p1);
  float8 k0 = 1.0f / w0, k1 = 1.0f / w1;
  float8 n0x = project_lanes(proj.s0123, p) * k0, n0y = project_lanes(proj.s4567, p) * k0;
  float8 n1x = project_lanes(proj.s0123, p1) * k1, n1y = project_lanes(proj.s4567, p1) * k1;
  // ndc_to_pixel, each end in its own statement (no fused multiply-add across them).
  r->s0x = (n0x + 1.0f) * 0.5f * (float)size.x;
  r->s0y = (1.0f - n0y) * 0.5f * (float)size.y;
  float8 s1x = (n1x + 1.0f) * 0.5f * (float)size.x;
  float8 s1y = (1.0f - n1y) * 0.5f * (float)size.y;
  r->dsx = s1x - r->s0x;
  r->dsy = s1y - r->s0y;
  r->q0x = p.x * k0, r->q0y = p.y * k0, r->q0z = p.z * k0, r->q0w = k0;
  float8 e1x = p1.x * k1, e1y = p1.y * k1, e1z = p1.z * k1;
  r->dqx = e1x - r->q0x, r->dqy = e1y - r->q0y, r->dqz = e1z - r->q0z, r->dqw = k1 - r->q0w;
  float8 tex = (select((float8)(0.0f), (float8)(size.x), r->dsx > 0.0f) - r->s0x) / r->dsx;
  float8 tey = (select((float8)(0.0f), (float8)(size.y), r->dsy > 0.0f) - r->s0y) / r->dsy;
  tex = select(tex, (float8)(INFINITY), fabs(r->dsx) < 1e-12f);
  tey = select(tey, (float8)(INFINITY), fabs(r->dsy) < 1e-12f);
  float8 t_max = fmin(1.0f, fmin(tex, tey));
  r->dsx *= t_max, r->dsy *= t_max;
  r->dqx *= t_max, r->dqy *= t_max, r->dqz *= t_max, r->dqw *= t_max;
  return (len > 0.0f) & (w0 > 0.0f) & (w1 > 0.0f) & isfinite(r->s0x) & isfinite(r->s0y) & isfinite(r->dsx) &
         isfinite(r->dsy) & (fmax(fabs(r->dsx), fabs(r->dsy)) > 0.0f);
}

// The direction a surface with normal n and GGX alpha reflects toward o (unit, away from it): the
// exact mirror direction (pdf 0: a delta), or a visible-normal sample of its lobe drawn with u and
// its pdf. Zero where the sample points below the surface (zero BRDF weight, nothing to trace).
inline float3 sample_reflection(float3 o, float3 n, bool mirror, float alpha, float2 u, float* pdf) {
  *pdf = 0.0f;
  if (mirror) return 2.0f * dot(o, n) * n - o;
  float3 tx, ty;
  basis_from_normal(n, &tx, &ty);
  float3 ol = (float3)(dot(o, tx), dot(o, ty), dot(o, n));
  float3 h = ggx_sample_vndf(ol, alpha, u);
  float3 ll = 2.0f * dot(ol, h) * h - ol;
  if (ll.z <= 0.0f) return (float3)(0.0f);
  *pdf = ggx_vndf_pdf_from_half(ol, h, alpha);
  return normalize(ll.x * tx + ll.y * ty + ll.z * n);
}

// The colour pyramid's level whose texels match the footprint of this ray's share of the lobe (a
// cone of tangent alpha * cone_scale) at the hit distance.
inline float hit_mip_level(const TraceScene* sc, float16 proj, const ScreenRay* ray, float t, float distance,
                           float alpha, float cone_scale) {
  float px_per_unit = 0.5f * (float)sc->size.y * fabs(proj.s5) * ray_q(ray, t).w;
  return log2(fmax(2.0f * distance * alpha * cone_scale * px_per_unit, 1.0f));
}

// Whether a hit on pixel q reads the colour pyramid over its footprint: prefiltering on
// (cone_scale > 0), a rough ray (alpha > 0: not a mirror ray) and a pixel the pyramid holds
// (specular pixels it leaves out read their own colour, setup.cl).
inline bool prefiltered_hit(const TraceScene* sc, int q, float alpha, float cone_scale) {
  return cone_scale > 0.0f && alpha > 0.0f && !specular_pixel(sc->normals[q].w);
}

// The colour at a ray's hit on pixel `cell` at `distance` from its origin, looked up at once (the
// views' hits: their pyramids keep coverage weights, not hit counts).
inline float4 hit_color(const TraceScene* sc, __global const float4* color_pyramid, float16 proj,
                        const ScreenRay* ray, float t, int2 cell, float distance, float alpha, float cone_scale) {
  int q = cell.y * sc->size.x + cell.x;
  if (!prefiltered_hit(sc, q, alpha, cone_scale)) return color_pyramid[q];
  return pyramid_sample(color_pyramid, sc->levels, sc->level_count, ray_screen(ray, t),
                        hit_mip_level(sc, proj, ray, t, distance, alpha, cone_scale));
}

// E's (scale, bias) at GGX alpha and cos(theta_o), bilinear in the host's table (SSRCL_ALBEDO_STEPS).
// NaN reads as 0 (fmax), as the host's table reads a NaN cosine as grazing.
inline float2 specular_albedo(__global const float2* table, float alpha, float cos_o) {
  const int row = SSRCL_ALBEDO_STEPS + 1;
  float2 uv = sqrt(fmin(fmax((float2)(alpha, cos_o), 0.0f), 1.0f)) * (float)SSRCL_ALBEDO_STEPS;
  int2 k = min(convert_int2(uv), SSRCL_ALBEDO_STEPS - 1);
  float2 f = uv - convert_float2(k);
  __global const float2* t = table + k.x * row + k.y;
  return mix(mix(t[0], t[1], f.y), mix(t[row], t[row + 1], f.y), f.x);
}

// One more ray from a hit on pixel `cell` (normal and roughness nq, GGX alpha_q) at view-space `hit`,
// for the light it reflects back along the arriving ray `dir`: whether there is one to trace, and
// its screen ray and direction.
inline bool bounce_ray(float16 proj, int2 size, float near_plane, float far_plane, float mirror_roughness, float3 hit,
                       float3 dir, float4 nq, float alpha_q, int2 cell, int sample, uint seed, ScreenRay* ray2,
                       float3* dir2) {
  float pdf2;
  const float2 u = sample_2d(cell.x, cell.y, sample, seed + 1u);
  *dir2 = sample_reflection(-dir, nq.xyz, nq.w <= mirror_roughness, alpha_q, u, &pdf2);
  return dot(*dir2, *dir2) > 0.0f && ray_from(proj, size, near_plane, far_plane, hit, *dir2, ray2);
}

// What that ray finds at t2 (negative: nothing) on pixel cell2: the screen colour in xyz and the
// hit's edge confidence in w, or w = -1.
inline float4 bounce_found(__global const float4* color_pyramid, int2 size, float edge_fade, const ScreenRay* ray2,
                           float t2, int2 cell2) {
  if (t2 < 0.0f) return (float4)(0.0f, 0.0f, 0.0f, -1.0f);
  cell2 = clamp(cell2, (int2)(0, 0), size - 1);
  return (float4)(color_pyramid[cell2.y * size.x + cell2.x].xyz,
                  edge_confidence(ray_screen(ray2, t2), size, edge_fade));
}

// A round of rays as the tracers take them: each ray's screen ray and direction, whether it has
// one (live: those without one are not traced), and what it finds (t, or negative on a miss, and
// the pixel).
typedef struct {
  ScreenRay ray[SSRCL_TRACE_ROUND];
  float3 dir[SSRCL_TRACE_ROUND];
  int live[SSRCL_TRACE_ROUND];
  float t[SSRCL_TRACE_ROUND];
  int2 cell[SSRCL_TRACE_ROUND];
} Round;

// Only `live` and `t` are read before a ray is put in its slot: the tracers start live slots only,
// and a slot's ray is read only where its t is a hit (clearing the rays cost the mirror trace 5%).
inline void round_clear(Round* r) {
  for (int k = 0; k < SSRCL_TRACE_ROUND; ++k) {
    r->live[k] = 0;
    r->t[k] = -1.0f;
  }
}

// A new round: every lane to trace in `frame` from its start (the packets read the frame from
// lane 0's; each lane counts its own steps), none with a ray yet.
inline void round_begin(Round* r, TraceScene* scene, const TraceScene* frame) {
  for (int k = 0; k < SSRCL_TRACE_ROUND; ++k) scene[k] = *frame;
  round_clear(r);
}

// Traces a round's live rays, lane k in frame sc[k] (its steps counted on from there): Hi-Z in
// packets, or the reference tracers a ray at a time.
inline void trace_round(TraceScene* sc, float linear_step, Round* r) {
#if SSRCL_TRACER == SSRCL_TRACER_HIZ && !SSRCL_TRACE_SCALAR
  trace_hiz_packets(sc, r->ray, r->dir, r->live, r->t, r->cell);
#else
  for (int k = 0; k < SSRCL_TRACE_ROUND; ++k)
    if (r->live[k]) r->t[k] = trace_ray(&sc[k], linear_step, &r->ray[k], r->dir[k], &r->cell[k]);
#endif
}

// The ray slots [*next, returned) of this work-item: those of its SSRCL_TRACE_PIXELS listed pixels.
inline int work_item_rays(int listed, int batch_size, int* next) {
  *next = (int)get_global_id(0) * SSRCL_TRACE_PIXELS * batch_size;
  return min(((int)get_global_id(0) + 1) * SSRCL_TRACE_PIXELS, listed) * batch_size;
}

// Counting mode (SSRCL_COUNT_WORK): texel reads and the iteration histogram (ssrcl_shared.h).
inline void count_work(__global int* counters, int gid, const TraceScene* sc) {
  atomic_add(&counters[gid % SSRCL_FETCH_SLOTS], sc->fetches);
  atomic_inc(&counters[SSRCL_FETCH_SLOTS + (32 - clz(sc->iterations))]);
}

// A primary ray between its making and its shading (trace_rays).
typedef struct {
  int gid, sample;
  size_t record;
  float3 p;  // its origin, view space
  float pdf, alpha;
  int mirror;
  int traced;  // its records are written: it is shaded (a miss where its screen ray is not live)
} PixelRay;

// Ray records, per (pixel, sample slot of this batch):
//   ray_hit      hit: (view-space hit point, confidence >= 0); miss: (direction, -1)
//   ray_radiance (rgb at the hit, pdf of the direction); pdf 0 marks a ray that is a delta
//                (mirror) or was not traced, which neighbours must not reuse.
__kernel void trace_rays(TraceParams params, __global const float2* range, __global const HzbLevel* levels,
                         __global const float4* positions, __global const float4* normals,
                         __global const int* ray_list, __global const int* pixel_rays,
                         __global const float4* planes, __global const float* guess, __global int* work_counters,
                         __global const float4* color_pyramid, __global const float* base, __global const float* specular,
                         __global const float* f0, __global const float2* albedo, __global float4* ray_hit,
                         __global float4* ray_radiance, __global uchar* ray_state) {
  const int2 size = (int2)(params.frame.width, params.frame.height);
  const float16 proj = vload16(0, params.frame.proj), inv_proj = vload16(0, params.frame.inv_proj);
  const float near_plane = params.frame.near_plane, far_plane = params.frame.far_plane, linear_step = params.linear_step;
  const float mirror_roughness = params.frame.mirror_roughness, edge_fade = params.edge_fade;
  const int batch_size = params.batch_size, level_count = params.level_count;
  const uint seed = params.seed;
  // The rays of SSRCL_TRACE_PIXELS listed pixels per work-item, in rounds of up to SSRCL_TRACE_ROUND:
  // made one by one (skipping the slots a pixel has no ray in, so lanes stay full where pixels have
  // one ray, as mirror pixels do), traced together in lanes (Hi-Z), then shaded one by one.
  const TraceScene frame_scene = {size, levels, level_count, planes, normals, params.max_iterations, 0, 0, 0, 0, 0,
                                   range, guess, 0, -1.0f, (int2)(0), 0, 0, 1};
  int next;
  const int end = work_item_rays(params.listed, batch_size, &next);
  while (next < end) {
    PixelRay lane[SSRCL_TRACE_ROUND];
    TraceScene scene[SSRCL_TRACE_ROUND];
    Round first;
    round_begin(&first, scene, &frame_scene);
    for (int k = 0; k < SSRCL_TRACE_ROUND; ++k) lane[k].traced = 0;
    // The round's rays up to their directions, one by one; their directions eight at a time
    // (sample_reflection_lanes); then their screen rays, one by one. A ray whose sample points
    // below its surface leaves its lane to the next.
    PixelRay drawn[SSRCL_TRACE_ROUND];
    float o_x[SSRCL_TRACE_ROUND], o_y[SSRCL_TRACE_ROUND], o_z[SSRCL_TRACE_ROUND], n_x[SSRCL_TRACE_ROUND],
        n_y[SSRCL_TRACE_ROUND], n_z[SSRCL_TRACE_ROUND], u_x[SSRCL_TRACE_ROUND], u_y[SSRCL_TRACE_ROUND],
        a_k[SSRCL_TRACE_ROUND], p_x[SSRCL_TRACE_ROUND], p_y[SSRCL_TRACE_ROUND], p_z[SSRCL_TRACE_ROUND];
    int m_k[SSRCL_TRACE_ROUND];
    int drawn_count = 0;
    while (drawn_count < SSRCL_TRACE_ROUND && next < end) {
      int gid = next++;
      int i = ray_list[gid / batch_size];
      int slot = gid % batch_size;
      int sample = params.first_sample + slot;
      if (sample >= pixel_rays[i]) continue;
      size_t record = (size_t)i * batch_size + slot;
      ray_hit[record] = (float4)(0.0f, 0.0f, 0.0f, -1.0f);
      ray_radiance[record] = (float4)(0.0f);
#if SSRCL_VIEWS
      ray_state[record] = 0;
#endif

      float4 nr = normals[i];
      float3 n = nr.xyz;
      float3 v;
      const int2 pixel = (int2)(i % size.x, i / size.x);
      float3 p = pixel_view_point(inv_proj, size, pixel, positions[i].w, &v);
      float3 o = -v;
      if (dot(o, n) <= 0.0f) continue;  // normal faces away from the viewer: no defined reflection

      // Mirror-like pixels have one ray, the exact mirror direction.
      const int k = drawn_count++;
      m_k[k] = nr.w <= mirror_roughness ? -1 : 0;
      a_k[k] = fmax(roughness_to_alpha(nr.w, SSRCL_ROUGHNESS_MAPPING), 1e-4f);
      float2 u = sample_2d(pixel.x, pixel.y, sample, seed);
      p_x[k] = p.x, p_y[k] = p.y, p_z[k] = p.z;
      o_x[k] = o.x, o_y[k] = o.y, o_z[k] = o.z, n_x[k] = n.x, n_y[k] = n.y, n_z[k] = n.z, u_x[k] = u.x, u_y[k] = u.y;
      PixelRay made = {gid, sample, record, p, 0.0f, a_k[k], m_k[k] != 0, 1};
      drawn[k] = made;
    }
    float d_x[SSRCL_TRACE_ROUND], d_y[SSRCL_TRACE_ROUND], d_z[SSRCL_TRACE_ROUND], pdf_k[SSRCL_TRACE_ROUND];
    ScreenRay drawn_ray[SSRCL_TRACE_ROUND];
    int drawn_live[SSRCL_TRACE_ROUND];
    for (int k = 0; k < drawn_count; k += 8) {
      float8 pdf;
      Lanes3 d = sample_reflection_lanes(lanes3(vload8(0, o_x + k), vload8(0, o_y + k), vload8(0, o_z + k)),
                                         lanes3(vload8(0, n_x + k), vload8(0, n_y + k), vload8(0, n_z + k)),
                                         vload8(0, m_k + k), vload8(0, a_k + k), vload8(0, u_x + k), vload8(0, u_y + k),
                                         &pdf);
      vstore8(d.x, 0, d_x + k);
      vstore8(d.y, 0, d_y + k);
      vstore8(d.z, 0, d_z + k);
      vstore8(pdf, 0, pdf_k + k);
      ScreenRays8 r;
      vstore8(ray_from_lanes(proj, size, near_plane, far_plane,
                             lanes3(vload8(0, p_x + k), vload8(0, p_y + k), vload8(0, p_z + k)), d, &r),
              0, drawn_live + k);
      float f[12][8];
      vstore8(r.s0x, 0, f[0]), vstore8(r.s0y, 0, f[1]), vstore8(r.dsx, 0, f[2]), vstore8(r.dsy, 0, f[3]);
      vstore8(r.q0x, 0, f[4]), vstore8(r.q0y, 0, f[5]), vstore8(r.q0z, 0, f[6]), vstore8(r.q0w, 0, f[7]);
      vstore8(r.dqx, 0, f[8]), vstore8(r.dqy, 0, f[9]), vstore8(r.dqz, 0, f[10]), vstore8(r.dqw, 0, f[11]);
      for (int j = 0; j < 8; ++j) {
        const ScreenRay one = {(float2)(f[0][j], f[1][j]), (float2)(f[2][j], f[3][j]),
                               (float4)(f[4][j], f[5][j], f[6][j], f[7][j]),
                               (float4)(f[8][j], f[9][j], f[10][j], f[11][j])};
        drawn_ray[k + j] = one;
      }
    }
    for (int j = 0, k = 0; j < drawn_count; ++j) {
      float3 dir = (float3)(d_x[j], d_y[j], d_z[j]);
      if (!(dot(dir, dir) > 0.0f)) continue;
      PixelRay made = drawn[j];
      made.pdf = pdf_k[j];
      ray_hit[made.record] = (float4)(dir, -1.0f);
      ray_radiance[made.record] = (float4)(0.0f, 0.0f, 0.0f, made.pdf);
      lane[k] = made;
      first.dir[k] = dir;
      first.live[k] = drawn_live[j] != 0;
      first.ray[k] = drawn_ray[j];
      ++k;
    }
    trace_round(scene, linear_step, &first);

    // Shading, in two passes around the second rays of hits on glossy pixels, which are traced
    // together as the first were: what each hit needs of its pixel, then what the second finds.
    float4 hit_radiance[SSRCL_TRACE_ROUND];
    float3 hit_point[SSRCL_TRACE_ROUND];
    float2 hit_screen[SSRCL_TRACE_ROUND];
    int hit_glossy[SSRCL_TRACE_ROUND];  // the hit is on a glossy pixel whose base is known
    Round second;
    round_clear(&second);
    for (int k = 0; k < SSRCL_TRACE_ROUND; ++k) {
      hit_glossy[k] = 0;
      if (!lane[k].traced) continue;
      const int sample = lane[k].sample;
      const float3 p = lane[k].p, dir = first.dir[k];
      const float alpha = lane[k].alpha;
      const bool mirror = lane[k].mirror;
      const TraceScene* sc = &scene[k];
      const ScreenRay ray = first.ray[k];
      int2 cell = first.cell[k];  // the pixel whose surface the ray hit; its colour is the hit's colour
      float t = first.t[k];
#if SSRCL_BACK_KNOWN
      if (t < 0.0f && sc->past) {
        t = sc->past_t;
        cell = sc->past_cell;
      }
#endif
#if SSRCL_VIEWS
      // Only the primary ray's passage counts: the glossy hit's second ray below only shades the hit.
      ray_state[lane[k].record] =
          (sc->behind ? SSRCL_RAY_BEHIND : 0) | (t >= 0.0f && sc->thick ? SSRCL_RAY_THICK : 0) |
          (t < 0.0f && !sc->hidden && first.live[k] && sc->iterations < sc->max_iterations ? SSRCL_RAY_CLEAR : 0);
#endif
      first.t[k] = t;
      if (t < 0.0f) continue;

      float2 s = ray_screen(&ray, t);
      float3 hit = ray_point(&ray, t);
      cell = clamp(cell, (int2)(0, 0), size - 1);
      first.cell[k] = cell;
      int q = cell.y * size.x + cell.x;
      // A prefiltered hit is looked up once the batch's hits are counted (hit_prefilter.cl): recorded
      // as the screen position and the mip of its footprint.
      // A hit through a surface's back (hit_pixel) is on a face the screen does not show, which its
      // light seldom reaches (the underside of a seat, a table top, a plank): black, neither looked up
      // nor bounced. Measured against the model's guess and against leaving the ray a miss:
      // docs/BENCHMARKS.md "Rays that enter a surface's back".
      const bool black = sc->entered;
      bool prefiltered = !black && prefiltered_hit(sc, q, mirror ? 0.0f : alpha, params.cone_scale);
      hit_radiance[k] =
          black ? (float4)(0.0f)
          : prefiltered
              ? (float4)(s, -1.0f - hit_mip_level(sc, proj, &ray, t, length(hit - p), alpha, params.cone_scale), 0.0f)
              : color_pyramid[q];
      hit_point[k] = hit;
      hit_screen[k] = s;
      // A hit on a glossy pixel: its screen colour is what it reflects toward the camera, not toward
      // this pixel. With its non-reflected radiance known (`base`), the hit's radiance is that plus
      // its specular part, what one more ray, reflected at the hit, finds, times its specular colour.
      // A pixel wrongly marked glossy (a material that writes no roughness reads 0) has specular
      // colour 0 and keeps its base: its screen colour. A mirror ray is one sample nothing averages:
      // it bounces only where the second ray is deterministic too (a mirror-like hit); a rough hit's
      // one second ray shows there as noise (mirror sample: floor within 25% of Cycles 0.90 -> 0.74).
      float4 nq = normals[q];
      bool bounce = !mirror || nq.w <= mirror_roughness;
      // `|`, not `||`: `&& (1 || bounce)` is constant, which the compiler warned of at every build.
      hit_glossy[k] = !black && !prefiltered && params.has_base && nq.w < params.glossy_hit_roughness &&
                      (SSRCL_MATERIAL_HITS | bounce);
      if (hit_glossy[k] && bounce)
        second.live[k] = bounce_ray(proj, size, near_plane, far_plane, mirror_roughness, hit, dir, nq,
                                    fmax(roughness_to_alpha(nq.w, SSRCL_ROUGHNESS_MAPPING), 1e-4f), cell, sample, seed,
                                    &second.ray[k], &second.dir[k]);
    }
    // A second ray's budget of steps is what its first left (scene[k].iterations).
    trace_round(scene, linear_step, &second);

    for (int k = 0; k < SSRCL_TRACE_ROUND; ++k) {
      if (!lane[k].traced) continue;
      if (SSRCL_COUNT_WORK) count_work(work_counters, lane[k].gid, &scene[k]);
      if (first.t[k] < 0.0f) continue;
      const int2 cell = first.cell[k];
      const int q = cell.y * size.x + cell.x;
      const float3 dir = first.dir[k];
      float4 radiance = hit_radiance[k];
      if (hit_glossy[k]) {
        const float4 nq = normals[q];
        const float alpha_q = fmax(roughness_to_alpha(nq.w, SSRCL_ROUGHNESS_MAPPING), 1e-4f);
        const float4 found = bounce_found(color_pyramid, size, edge_fade, &second.ray[k], second.t[k], second.cell[k]);
#if SSRCL_MATERIAL_HITS
        // The specular colour times E(the hit's F0, its roughness, toward this pixel) times what the
        // ray finds: Cycles' GlossCol is ~1 on dielectrics and metals alike, the Fresnel and a metal's
        // tint live in Glossy Direct/Indirect, so with the colour alone a dielectric's specular part
        // came out 10-25x too bright (1 against E 0.04-0.1 off grazing). Where the ray finds nothing
        // (c2 < 1), or none is traced (a mirror ray on a rough hit), the guess is the glossy light
        // the camera sees there times E(toward this pixel) / E(toward the camera), at most 1: raised,
        // the camera's highlight comes back as the blob (where the floor shows props, issue 24's
        // corpus and tests/data/glazed_props: capped it ties the screen colour within 0.01 dB on all
        // six scenes, uncapped it loses up to 0.16 dB).
        float3 f0_q = vload3(q, f0), base_q = vload3(q, base);
        float2 e = specular_albedo(albedo, alpha_q, dot(nq.xyz, -dir));
        float3 e_out = f0_q * e.x + e.y;
        float3 v_q;
        pixel_view_point(inv_proj, size, cell, positions[q].w, &v_q);
        float2 e_cam = specular_albedo(albedo, alpha_q, dot(nq.xyz, -v_q));
        float3 shaded = base_q + fmin(e_out / fmax(f0_q * e_cam.x + e_cam.y, 1e-4f), 1.0f) * (radiance.xyz - base_q);
        if (found.w >= 0.0f) shaded = mix(shaded, base_q + vload3(q, specular) * e_out * found.xyz, found.w);
        radiance.xyz = sanitize_radiance3(shaded);
#else
        // Where the ray finds nothing on screen (confidence c2 < 1) the screen colour stays the best
        // guess for that share.
        if (found.w >= 0.0f) {
          float3 bounced = vload3(q, base) + vload3(q, specular) * found.xyz;
          radiance.xyz = sanitize_radiance3(mix(radiance.xyz, bounced, found.w));
        }
#endif
      }
      ray_hit[lane[k].record] = (float4)(hit_point[k], edge_confidence(hit_screen[k], size, edge_fade));
      ray_radiance[lane[k].record] = (float4)(radiance.xyz, lane[k].pdf);
    }
  }
}
