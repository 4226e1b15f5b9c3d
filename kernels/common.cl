// Shared definitions for every ssrcl kernel: each program lists this file after ssrcl_shared.h.
//
// Conventions: pixel (x, y) covers [x, x+1) x [y, y+1), y = 0 is the top row. Matrices are
// float16 in row-major order (s0123 = first row) and act on column vectors. Depth is planar
// view depth (positive in front of the camera); SSRCL_NO_SURFACE marks sky and invalid pixels.

#define SSRCL_NO_SURFACE FLT_MAX
// Of the depth: a pixel's point this near a neighbour's plane lies on the neighbour's surface.
#define SSRCL_ON_PLANE 0.01f

// Whether point p lies on the plane through q with normal n, within SSRCL_ON_PLANE of `depth`.
inline bool on_plane(float3 p, float3 q, float3 n, float depth) { return fabs(dot(p - q, n)) <= SSRCL_ON_PLANE * depth; }

// Radiance rule: NaN becomes 0, negatives 0, and values clamp at 1e20 so that weighted sums
// in later stages cannot overflow float.
#define SSRCL_MAX_RADIANCE 1e20f

inline float sanitize_radiance(float v) {
  return isnan(v) ? 0.0f : clamp(v, 0.0f, SSRCL_MAX_RADIANCE);
}

inline float3 sanitize_radiance3(float3 v) {
  return (float3)(sanitize_radiance(v.x), sanitize_radiance(v.y), sanitize_radiance(v.z));
}

inline float4 mat_mul(float16 m, float4 v) {
  return (float4)(dot(m.s0123, v), dot(m.s4567, v), dot(m.s89ab, v), dot(m.scdef, v));
}

inline float3 mat3_mul(float16 m, float3 v) {
  return (float3)(dot(m.s012, v), dot(m.s456, v), dot(m.s89a, v));
}

// Camera-space point on the line through NDC (x, y) at NDC depth z.
inline float3 unproject(float16 inv_proj, float2 ndc, float z) {
  float4 h = mat_mul(inv_proj, (float4)(ndc, z, 1.0f));
  return h.xyz / h.w;
}

inline float2 pixel_to_ndc(float2 pixel, int2 size) {
  return (float2)(2.0f * pixel.x / (float)size.x - 1.0f, 1.0f - 2.0f * pixel.y / (float)size.y);
}

inline float2 ndc_to_pixel(float2 ndc, int2 size) {
  return (float2)((ndc.x + 1.0f) * 0.5f * (float)size.x, (1.0f - ndc.y) * 0.5f * (float)size.y);
}

// Where a level's texel lies in a pyramid buffer (the cell clamped to the level).
inline int pyramid_index(__global const HzbLevel* levels, int level, int2 cell) {
  HzbLevel l = levels[level];
  cell = clamp(cell, (int2)(0, 0), (int2)(l.width - 1, l.height - 1));
  return l.offset + cell.y * l.width + cell.x;
}

// The fine texels that the pyramids' reductions (hzb.cl, back_pyramid.cl, color_pyramid.cl)
// combine into texel (x, y) of level dst_level: x0..x1, y0..y1 of the level below, clamped at its
// edge (a coarse level is ceil(fine / 2), so an edge texel may cover one fine column or row).
// False outside.
typedef struct {
  HzbLevel dst, src;
  int x0, y0, x1, y1;
} ReduceCell;

inline bool reduce_cell(__global const HzbLevel* levels, int dst_level, int x, int y, ReduceCell* c) {
  c->dst = levels[dst_level];
  if (x >= c->dst.width || y >= c->dst.height) return false;
  c->src = levels[dst_level - 1];
  c->x0 = 2 * x;
  c->y0 = 2 * y;
  c->x1 = min(c->x0 + 1, c->src.width - 1);
  c->y1 = min(c->y0 + 1, c->src.height - 1);
  return true;
}

// Where the four source texels under a reduction cell lie in its pyramid (one buffer, levels at
// their offsets).
inline int4 cell_texel_indices(const ReduceCell* c) {
  int s = c->src.offset, w = c->src.width;
  return (int4)(s + c->y0 * w + c->x0, s + c->y0 * w + c->x1, s + c->y1 * w + c->x0, s + c->y1 * w + c->x1);
}

// The viewing line through NDC (x, y) as a point on it and a step along it (eye -> scene) that
// grows planar depth by exactly 1: the point at depth D is origin + (D + origin.z) * step.
// Built from two homogeneous points, inv_proj * (x, y, 0, 1) and the centre of projection
// inv_proj * (0, 0, 1, 0) (a direction at infinity for orthographic cameras), which are finite for
// every depth layout; NDC z = -1 or 0 themselves can lie at infinity with reversed Z or an
// infinite far plane. The origin is the eye for perspective cameras, so points keep their
// relative precision at any depth.
inline void view_line(float16 inv_proj, float2 ndc, float3* origin, float3* step) {
  float4 a = mat_mul(inv_proj, (float4)(ndc, 0.0f, 1.0f));
  float4 e = (float4)(inv_proj.s2, inv_proj.s6, inv_proj.sa, inv_proj.se);
  float3 v = a.xyz * e.w - e.xyz * a.w;
  *step = v / -v.z;
  *origin = e.w != 0.0f ? e.xyz / e.w : a.xyz / a.w;
}

// View-space surface point of pixel `pix` at planar depth `depth`, and the unit viewing direction
// (eye -> point); valid for perspective and orthographic cameras alike.
inline float3 pixel_view_point(float16 inv_proj, int2 size, int2 pix, float depth, float3* view_dir) {
  float3 origin, step;
  view_line(inv_proj, pixel_to_ndc(convert_float2(pix) + 0.5f, size), &origin, &step);
  *view_dir = normalize(step);
  return origin + (depth + origin.z) * step;
}

// Confidence of a hit at screen position s: fades to 0 over `edge_fade` of the smaller screen side.
inline float edge_confidence(float2 s, int2 size, float edge_fade) {
  if (!(edge_fade > 0.0f)) return 1.0f;
  float border = fmin(fmin(s.x, (float)size.x - s.x), fmin(s.y, (float)size.y - s.y));
  return clamp(border / (edge_fade * (float)min(size.x, size.y)), 0.0f, 1.0f);
}

// Work is classified in tiles of SSRCL_TILE^2 pixels (the 2D work-group size): kernels that run
// per tile take a list of tile indices and a 1D range of work-groups, group g covering tile
// tile_list[g].

inline int2 tile_pixel(__global const int* tile_list, int tiles_x) {
  int tile = tile_list[get_group_id(0)];
  return (int2)((tile % tiles_x) * SSRCL_TILE + (int)get_local_id(0),
                (tile / tiles_x) * SSRCL_TILE + (int)get_local_id(1));
}

// Field `field` of the eight elements of array a, one to a lane.
#define SSRCL_LANES(a, field) \
  (float8)(a[0].field, a[1].field, a[2].field, a[3].field, a[4].field, a[5].field, a[6].field, a[7].field)

// Along a plane 1 / depth (perspective) or depth (orthographic) is affine in screen space, so on
// one surface a pixel's depth d2 is predicted, within 1%, by two pixels before it (d0, d1) on a
// line through it, as far apart as it is from d1.
inline bool predicts(float d0, float d1, float d2) {
  float tol = 0.01f;
  return fabs(1.0f / d2 - (2.0f / d1 - 1.0f / d0)) <= tol / d2 || fabs(d2 - (2.0f * d1 - d0)) <= tol * d2;
}

// a[i.sN] in lane N. LLVM makes one hardware gather (vgatherdps) of it.
inline float8 gather8(__global const float* a, int8 i) {
  return (float8)(a[i.s0], a[i.s1], a[i.s2], a[i.s3], a[i.s4], a[i.s5], a[i.s6], a[i.s7]);
}

// Record slot.sN of each lane N, transposed: one float8 per component. Eight record loads and a
// transpose, for lanes whose records lie side by side (neighbouring pixels).
typedef struct {
  float8 x, y, z, w;
} RecordLanes;

inline RecordLanes record_lanes(__global const float4* records, int8 slot) {
  float16 a = (float16)(records[slot.s0], records[slot.s1], records[slot.s2], records[slot.s3]).s048c159d26ae37bf;
  float16 b = (float16)(records[slot.s4], records[slot.s5], records[slot.s6], records[slot.s7]).s048c159d26ae37bf;
  RecordLanes r = {(float8)(a.s0123, b.s0123), (float8)(a.s4567, b.s4567), (float8)(a.s89ab, b.s89ab),
                   (float8)(a.scdef, b.scdef)};
  return r;
}

// The same for the eight records from `first` on, side by side (a row of neighbouring pixels):
// two vector loads, where the eight loads of record_lanes do not know they are neighbours.
inline RecordLanes row_record_lanes(__global const float4* records, int first) {
  __global const float* f = (__global const float*)(records + first);
  float16 a = vload16(0, f).s048c159d26ae37bf, b = vload16(1, f).s048c159d26ae37bf;
  RecordLanes r = {(float8)(a.s0123, b.s0123), (float8)(a.s4567, b.s4567), (float8)(a.s89ab, b.s89ab),
                   (float8)(a.scdef, b.scdef)};
  return r;
}

// The same for lanes whose records lie apart (the trace's rays): a hardware gather a component.
// There eight loads' addresses leave the vector registers a pair at a time (the trace's CPU -8%);
// on neighbouring records the gathers are slower (the resolve 1.15x, the filter 1.5x).
// Always inlined: called, the trace's packet step saved and restored 20 vectors around it.
__attribute__((always_inline)) inline RecordLanes scattered_record_lanes(__global const float4* records, int8 slot) {
  __global const float* f = (__global const float*)records;
  const int8 i = 4 * slot;
  RecordLanes r = {gather8(f, i), gather8(f, i + 1), gather8(f, i + 2), gather8(f, i + 3)};
  return r;
}

// dot(n_p, n_q) of each lane, rounded as PoCL's dot() of two float3 rounds it (the three products,
// then (x + y) + z, no fused multiply-add), so that kernels with a pixel to a lane compare normals
// as their per-pixel forms did, bit for bit.
inline float8 dot_lanes(float8 ax, float8 ay, float8 az, float8 bx, float8 by, float8 bz) {
#pragma OPENCL FP_CONTRACT OFF
  float8 x = ax * bx, y = ay * by, z = az * bz;
  return (x + y) + z;
}

// any() of a lane mask (each lane 0 or -1): PoCL's any(int8) tests the lanes' sign bits a pair at
// a time, a branch each. On AVX CPUs one vptest; elsewhere one OR tree and one test (the form
// SSRCL_PORTABLE builds, for tests).
inline bool any_lane(int8 mask) {
#if defined(__AVX__) && !defined(SSRCL_PORTABLE)
  return !__builtin_ia32_ptestz256(as_long4(mask), as_long4(mask));
#else
  int4 a = mask.lo | mask.hi;
  int2 b = a.lo | a.hi;
  return (b.x | b.y) != 0;
#endif
}

// How many lanes of a mask (each lane 0 or -1) are set: on AVX CPUs by vmovmskps and popcnt, where
// the sum took eight extractions (the packet loop asks every step).
inline int count_lanes(int8 mask) {
#if defined(__AVX__) && !defined(SSRCL_PORTABLE)
  return popcount(__builtin_ia32_movmskps256(as_float8(mask)));
#else
  return -(mask.s0 + mask.s1 + mask.s2 + mask.s3 + mask.s4 + mask.s5 + mask.s6 + mask.s7);
#endif
}

inline int max_lane(int8 v) {
  int4 m = max(v.lo, v.hi);
  return max(max(m.x, m.y), max(m.z, m.w));
}
