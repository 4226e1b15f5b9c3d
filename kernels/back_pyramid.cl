// The range pyramid: per texel the HZB's nearest depth (x) and the farthest planar depth at which
// a ray over its pixels can hit a surface (y, trace.cl hit_pixel), in the HZB's layout. The Hi-Z
// trace skips a cell the ray crosses wholly behind y, where the min-depth HZB alone makes it
// descend and step pixel by pixel until it comes out in front. Both ends of a texel in one
// record: a step's one read (the ends apart, a step read two cache lines).
//
// hit_pixel hits a pixel's surface where the ray crosses its plane or lies behind it by at most
// one thickness: every hit point is in the slab between the plane and its copy one thickness
// behind (the plane records are in thickness units, surface_plane.cl), over the pixel. Each
// viewing line meets the slab in a segment; over the pixel's footprint the segments' far ends are
// farthest at a corner, unless a viewing line there runs along the plane (unbounded: +infinity).
// The corners are widened by SSRCL_BACK_MARGIN pixels: a ray's stretch over a pixel starts where
// the last one left off, on the boundary within rounding.
#define SSRCL_BACK_MARGIN 0.05f

// The far end of the slab dot(x, n) in [c - 1, c] on the viewing line through pixel position
// `corner`; *sign gets 1 or 2 as the line runs with or against n, 3 along it.
inline float slab_far_end(float16 inv_proj, int2 size, float2 corner, float3 n, float c, int* sign) {
  float3 origin, step;
  view_line(inv_proj, pixel_to_ndc(corner, size), &origin, &step);
  float along = dot(step, n), from = dot(origin, n);
  *sign |= along > 0.0f ? 1 : along < 0.0f ? 2 : 3;
  return fmax((c - from) / along, (c - 1.0f - from) / along) - origin.z;  // planar depth (view_line)
}

// With `guessed`, a pixel whose back is known also catches rays within the thickness model's guess
// (`guess`, in units of its exact thickness, trace.cl SSRCL_BACK_KNOWN): its slab is the larger one.
__kernel void back_level0(FrameConstants frame, __global const float* hzb, __global const float4* planes,
                          __global const float* guess, int guessed, __global float2* range) {
  const int2 size = (int2)(frame.width, frame.height);
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= size.x || y >= size.y) return;
  const float16 inv_proj = vload16(0, frame.inv_proj);
  float4 plane = planes[y * size.x + x];
  if (guessed) plane /= fmax(guess[y * size.x + x], 1.0f);  // records are over the thickness
  float far_end = -INFINITY;  // SSRCL_NO_PLANE: nothing to hit
  if (plane.w != -INFINITY) {
    int sign = 0;
    const float lo = -SSRCL_BACK_MARGIN, hi = 1.0f + SSRCL_BACK_MARGIN;
    far_end = fmax(fmax(slab_far_end(inv_proj, size, (float2)(x + lo, y + lo), plane.xyz, plane.w, &sign),
                        slab_far_end(inv_proj, size, (float2)(x + hi, y + lo), plane.xyz, plane.w, &sign)),
                   fmax(slab_far_end(inv_proj, size, (float2)(x + lo, y + hi), plane.xyz, plane.w, &sign),
                        slab_far_end(inv_proj, size, (float2)(x + hi, y + hi), plane.xyz, plane.w, &sign)));
    // A thousandth more: the trace compares its own rounded depths with these.
    far_end = (sign == 1 || sign == 2) && isfinite(far_end) ? far_end + 1e-3f * fabs(far_end) : INFINITY;
  }
  const int i = y * size.x + x;  // level 0 at offset 0, rows of the frame's width
  range[i] = (float2)(hzb[i], far_end);
}

// One reduction step of the range pyramid: x as the HZB's (depth_reduce, so equal to it), y the
// farthest of the four.
__kernel void range_reduce(__global float2* pyramid, __global const HzbLevel* levels, int dst_level) {
  int x = get_global_id(0), y = get_global_id(1);
  ReduceCell c;
  if (!reduce_cell(levels, dst_level, x, y, &c)) return;
  int4 i = cell_texel_indices(&c);
  float2 a = pyramid[i.x], b = pyramid[i.y], d = pyramid[i.z], e = pyramid[i.w];
  pyramid[c.dst.offset + y * c.dst.width + x] =
      (float2)(fmin(fmin(a.x, b.x), fmin(d.x, e.x)), fmax(fmax(a.y, b.y), fmax(d.y, e.y)));
}
