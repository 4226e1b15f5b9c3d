// The range pyramid: per texel the nearest depth (x) and the farthest planar depth (y) at which a
// ray over its pixels can hit a surface (trace.cl hit_pixel), in the HZB's layout. The Hi-Z trace
// tests a ray's stretch over a cell against both: it skips a cell the ray crosses wholly in front
// of x or behind y, where the min-depth HZB alone makes it descend and step pixel by pixel until
// it comes out in front, and tests a pixel's plane only where its range meets the ray. Both ends
// of a texel in one record: a step's one read.
//
// hit_pixel hits a pixel's surface where the ray crosses its plane or lies behind it by at most
// one thickness: every hit point is in the slab between the plane and its copy one thickness
// behind (the plane records are in thickness units, surface_plane.cl), over the pixel. Each
// viewing line meets the slab in a segment; over the pixel's footprint the segments' ends are
// nearest and farthest at corners, unless a viewing line there runs along the plane (unbounded).
// At level 0 x is that near end (no farther than the pixel's depth); coarser levels keep the
// HZB's (range_reduce).
// The corners are widened by SSRCL_BACK_MARGIN pixels: a ray's stretch over a pixel starts where
// the last one left off, on the boundary within rounding.
#define SSRCL_BACK_MARGIN 0.05f

// Eight pixels of a row to a work-item, one to a float8 lane: PoCL's work-group vectoriser does
// not run on this kernel (its loop vectoriser refuses the float3 arithmetic, "instruction return
// type cannot be vectorized"; written on scalars, the work-item loop is still left scalar), and a
// work-item at a time the twenty divisions of a pixel's four corners were most of the stage.
// The lanes round as the per-pixel form did, bit for bit: the same operations in the same order,
// dot products as PoCL's dot() rounds them (dot_lanes, dot4_lanes: no fused multiply-add).
#define SSRCL_BACK_LANES 8

// dot(m row, (ndc_x, ndc_y, 0, 1)) of each lane, as common.cl mat_mul's dot of two float4 rounds it.
inline float8 dot4_lanes(float4 row, float8 ndc_x, float8 ndc_y) {
#pragma OPENCL FP_CONTRACT OFF
  float8 x = row.x * ndc_x, y = row.y * ndc_y, z = (float8)(row.z * 0.0f), w = (float8)(row.w * 1.0f);
  return ((x + y) + z) + w;
}

// The far end of the slab dot(x, n) in [c - 1, c] on the viewing line through each lane's pixel
// position (px, py) (common.cl view_line), its near end in *near; *sign gets 1 or 2 as the line
// runs with or against n, 3 along it.
inline float8 slab_ends(float16 inv_proj, int2 size, float8 px, float8 py, float8 nx, float8 ny, float8 nz, float8 c,
                        int8* sign, float8* near) {
  const float8 ndc_x = 2.0f * px / (float)size.x - 1.0f, ndc_y = 1.0f - 2.0f * py / (float)size.y;
  const float8 ax = dot4_lanes(inv_proj.s0123, ndc_x, ndc_y), ay = dot4_lanes(inv_proj.s4567, ndc_x, ndc_y);
  const float8 az = dot4_lanes(inv_proj.s89ab, ndc_x, ndc_y), aw = dot4_lanes(inv_proj.scdef, ndc_x, ndc_y);
  const float4 e = (float4)(inv_proj.s2, inv_proj.s6, inv_proj.sa, inv_proj.se);
  const float8 vx = ax * e.w - e.x * aw, vy = ay * e.w - e.y * aw, vz = az * e.w - e.z * aw;
  const float8 sx = vx / -vz, sy = vy / -vz, sz = vz / -vz;
  float8 ox, oy, oz;
  if (e.w != 0.0f) {
    ox = (float8)(e.x / e.w);
    oy = (float8)(e.y / e.w);
    oz = (float8)(e.z / e.w);
  } else {
    ox = ax / aw;
    oy = ay / aw;
    oz = az / aw;
  }
  const float8 along = dot_lanes(sx, sy, sz, nx, ny, nz), from = dot_lanes(ox, oy, oz, nx, ny, nz);
  *sign |= select(select((int8)(3), (int8)(2), along < 0.0f), (int8)(1), along > 0.0f);
  const float8 a = (c - from) / along, b = (c - 1.0f - from) / along;
  *near = fmin(a, b) - oz;
  return fmax(a, b) - oz;  // planar depth (view_line)
}

// With `guessed`, a pixel whose back is known also catches rays within the thickness model's guess
// (`guess`, in units of its exact thickness, trace.cl SSRCL_BACK_KNOWN): its slab is the larger one.
__kernel void back_level0(FrameConstants frame, __global const float* hzb, __global const float4* planes,
                          __global const float* guess, int guessed, __global float2* range) {
  const int2 size = (int2)(frame.width, frame.height);
  const int x0 = SSRCL_BACK_LANES * (int)get_global_id(0), y = get_global_id(1);
  if (x0 >= size.x || y >= size.y) return;
  const float16 inv_proj = vload16(0, frame.inv_proj);
  const int8 lane = (int8)(0, 1, 2, 3, 4, 5, 6, 7);
  // Lanes past the row's end repeat its last pixel (level 0 at offset 0, rows of the frame's width).
  const int8 slot = y * size.x + min(x0 + lane, size.x - 1);
  RecordLanes plane = record_lanes(planes, slot);
  if (guessed) {  // records are over the thickness
    const float8 g = fmax(gather8(guess, slot), 1.0f);
    plane.x /= g;
    plane.y /= g;
    plane.z /= g;
    plane.w /= g;
  }
  const float8 px = convert_float8(x0 + lane), py = (float8)((float)y);
  int8 sign = 0;
  const float lo = -SSRCL_BACK_MARGIN, hi = 1.0f + SSRCL_BACK_MARGIN;
  float8 n0, n1, n2, n3;
  float8 far_end =
      fmax(fmax(slab_ends(inv_proj, size, px + lo, py + lo, plane.x, plane.y, plane.z, plane.w, &sign, &n0),
                slab_ends(inv_proj, size, px + hi, py + lo, plane.x, plane.y, plane.z, plane.w, &sign, &n1)),
           fmax(slab_ends(inv_proj, size, px + lo, py + hi, plane.x, plane.y, plane.z, plane.w, &sign, &n2),
                slab_ends(inv_proj, size, px + hi, py + hi, plane.x, plane.y, plane.z, plane.w, &sign, &n3)));
  float8 near_end = fmin(fmin(n0, n1), fmin(n2, n3));
  // A thousandth more: the trace compares its own rounded depths with these.
  const int8 bounded = (sign == 1 || sign == 2) && isfinite(far_end) && isfinite(near_end);
  far_end = select((float8)(INFINITY), far_end + 1e-3f * fabs(far_end), bounded);
  near_end = select((float8)(-INFINITY), near_end - 1e-3f * fabs(near_end), bounded);
  // The near end no farther than the pixel's own depth, which the coarse levels' nearest reduce.
  const int i = y * size.x + x0;
  const float8 depth = x0 + SSRCL_BACK_LANES <= size.x ? vload8(0, hzb + i) : gather8(hzb, slot);
  near_end = fmin(near_end, depth);
  const int8 sky = plane.w == -INFINITY;  // SSRCL_NO_PLANE: nothing to hit
  far_end = select(far_end, (float8)(-INFINITY), sky);
  near_end = select(near_end, (float8)(INFINITY), sky);
  if (x0 + SSRCL_BACK_LANES <= size.x) {
    vstore16((float16)(near_end, far_end).s08192a3b4c5d6e7f, 0, (__global float*)(range + i));
    return;
  }
  float nears[SSRCL_BACK_LANES], fars[SSRCL_BACK_LANES];
  vstore8(near_end, 0, nears);
  vstore8(far_end, 0, fars);
  for (int k = 0; k < size.x - x0; ++k) range[i + k] = (float2)(nears[k], fars[k]);
}

// One reduction step of the range pyramid: x the HZB's texel (the nearest pixel depth: a coarse
// cell the ray crosses in front of every pixel's depth is skipped, as the HZB alone would; the near
// ends of level 0 would make rays descend a fifth more often), y the farthest of the four.
__kernel void range_reduce(__global float2* pyramid, __global const HzbLevel* levels, int dst_level,
                           __global const float* hzb) {
  int x = get_global_id(0), y = get_global_id(1);
  ReduceCell c;
  if (!reduce_cell(levels, dst_level, x, y, &c)) return;
  int4 i = cell_texel_indices(&c);
  const int dst = c.dst.offset + y * c.dst.width + x;
  float2 a = pyramid[i.x], b = pyramid[i.y], d = pyramid[i.z], e = pyramid[i.w];
  pyramid[dst] = (float2)(hzb[dst], fmax(fmax(a.y, b.y), fmax(d.y, e.y)));
}
