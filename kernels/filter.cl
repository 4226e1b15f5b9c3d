// Optional edge-aware spatial filter of the resolved glossy pass: a Gaussian whose radius grows
// with roughness (rougher lobes vary slowly), stopped where a neighbour leaves the pixel's plane or
// its normal turns, so reflections do not bleed across objects. Mirror-like and untraced pixels pass through unchanged. Runs over
// the listed tiles: pixels that reflect lie in them, and it reads no others.
// Over the square of taps (params.axes 3), or separably: a pass along y, then one along x over
// its output (2r + 1 taps a pass where the square takes (2r + 1)^2), each tap weighed as in the
// square; host/pipeline/filter_stage.hpp.
//
// A work-item filters one row of a tile, one pixel to a float8 lane (as resolve_accumulate does):
// PoCL does not vectorise work-items whose loops differ in length, and each pixel's radius is its
// own. The lanes take the taps of the widest radius among them, each lane only those within its
// own, in its own order, so that every pixel's sums are those its per-pixel form made.
#if SSRCL_TILE != 8
#error "denoise puts a tile row in float8 lanes"
#endif

// Component w of records[slot.sN] in lane N.
inline float8 record_w_lanes(__global const float4* records, int8 slot) {
  return (float8)(records[slot.s0].w, records[slot.s1].w, records[slot.s2].w, records[slot.s3].w,
                  records[slot.s4].w, records[slot.s5].w, records[slot.s6].w, records[slot.s7].w);
}

__kernel void denoise(FilterParams params, __global const int* tile_list, __global const float4* positions, __global const float4* normals, __global const int* pixel_rays,
                      __global const float4* in_rgba, __global const float* in_distance,
                      __global float4* out_rgba, __global float* out_distance) {
  const int2 size = (int2)(params.frame.width, params.frame.height);
  const float mirror_roughness = params.frame.mirror_roughness;
  const int2 row = tile_pixel(tile_list, params.frame.tiles_x);  // work-groups (1, SSRCL_TILE): a row's first pixel
  const int x0 = row.x, y = row.y;
  if (y >= size.y) return;
  // Each lane's pixel: its radius (-1: it takes no taps), 2 sigma^2, normal, inverse depth and the
  // gradient of inverse depth.
  int radius[8];
  float two_sigma2[8], inv_depth[8], grad_x[8], grad_y[8];
  float4 normal[8];
  for (int l = 0; l < 8; ++l) {
    int x = x0 + l, i = y * size.x + x;
    radius[l] = -1;
    two_sigma2[l] = inv_depth[l] = grad_x[l] = grad_y[l] = 1.0f;
    normal[l] = (float4)(0.0f);
    if (x >= size.x) continue;
    float4 nr = normals[i];
    if (pixel_rays[i] == 0 || nr.w <= mirror_roughness) {
      out_rgba[i] = in_rgba[i];
      out_distance[i] = in_distance[i];
      continue;
    }
    // Wider for rougher lobes, narrower the more rays the pixel has: its noise falls as 1/sqrt(rays),
    // and a wide kernel over a well-sampled pixel only blurs (12 x roughness at 4 rays). A pixel
    // resolved from its neighbours' rays alone (-1, strided tracing) counts as one.
    int r = clamp((int)(nr.w * 24.0f * rsqrt((float)max(pixel_rays[i], 1)) + 0.5f), 1, 6);
    float sigma2 = 0.5f * (float)(r * r);
    float d = positions[i].w;
    // Neighbours are compared with the plane through this pixel, not its depth: inverse depth is affine
    // in screen space over a plane. The gradient per axis is the smaller one-sided difference, so an edge
    // on one side does not tilt the plane.
    float inv_d = 1.0f / d;
    float gx0 = x > 0 ? inv_d - 1.0f / positions[i - 1].w : INFINITY;
    float gx1 = x + 1 < size.x ? 1.0f / positions[i + 1].w - inv_d : INFINITY;
    float gy0 = y > 0 ? inv_d - 1.0f / positions[i - size.x].w : INFINITY;
    float gy1 = y + 1 < size.y ? 1.0f / positions[i + size.x].w - inv_d : INFINITY;
    float2 g = (float2)(fabs(gx0) < fabs(gx1) ? gx0 : gx1, fabs(gy0) < fabs(gy1) ? gy0 : gy1);
    if (!isfinite(g.x)) g.x = 0.0f;
    if (!isfinite(g.y)) g.y = 0.0f;
    radius[l] = r;
    two_sigma2[l] = 2.0f * sigma2;
    inv_depth[l] = inv_d;
    grad_x[l] = g.x;
    grad_y[l] = g.y;
    normal[l] = nr;
  }
  const int8 lane_radius = vload8(0, radius);
  const int widest = max_lane(lane_radius);
  if (widest < 0) return;
  const float8 lane_two_sigma2 = vload8(0, two_sigma2), inv_d = vload8(0, inv_depth), gx = vload8(0, grad_x),
               gy = vload8(0, grad_y);
  const float8 nx = SSRCL_LANES(normal, x), ny = SSRCL_LANES(normal, y), nz = SSRCL_LANES(normal, z),
               nw = SSRCL_LANES(normal, w);
  const int8 x = x0 + (int8)(0, 1, 2, 3, 4, 5, 6, 7);
  const float8 zero = (float8)(0.0f);
  float8 sum_r = zero, sum_g = zero, sum_b = zero, sum_a = zero, weights = zero, dist_sum = zero, dist_weights = zero;
  const int reach_x = params.axes & 1 ? widest : 0, reach_y = params.axes & 2 ? widest : 0;
  for (int dy = -reach_y; dy <= reach_y; ++dy) {
    const int qy = y + dy;
    if (qy < 0 || qy >= size.y) continue;
    for (int dx = -reach_x; dx <= reach_x; ++dx) {
      const int8 qx = x + dx, q = qy * size.x + clamp(qx, 0, size.x - 1);
      int8 take = lane_radius >= (int)max(abs(dx), abs(dy)) && qx >= 0 && qx < size.x;
      if (!any_lane(take)) continue;
      // All eight taps in the frame: they lie side by side, a vector load a record (0.7x the
      // filter's CPU time at 1920x1080); at the frame's edges each lane loads its own clamped tap.
      const int first = qy * size.x + x0 + dx;
      const bool inside = x0 + dx >= 0 && x0 + dx + 7 < size.x;
      const RecordLanes nq = inside ? row_record_lanes(normals, first) : record_lanes(normals, q);
      const int8 rays_q = inside ? vload8(0, pixel_rays + first)
                                 : (int8)(pixel_rays[q.s0], pixel_rays[q.s1], pixel_rays[q.s2], pixel_rays[q.s3],
                                          pixel_rays[q.s4], pixel_rays[q.s5], pixel_rays[q.s6], pixel_rays[q.s7]);
      take = take && rays_q != 0 && nq.w > mirror_roughness;
      if (!any_lane(take)) continue;
      // The Gaussian, on the same plane, similar lobe width: one exp of their exponents' sum;
      // same orientation: cos^64 by six squarings (PoCL's exp and pow are library calls, which took
      // 86% of the filter's time: docs/BENCHMARKS.md "Resolve and filter").
      const float8 e = -(float)(dx * dx + dy * dy) / lane_two_sigma2 -
                       fabs((inside ? row_record_lanes(positions, first).w : record_w_lanes(positions, q)) *
                                (inv_d + dx * gx + dy * gy) - 1.0f) / 0.01f -
                       fabs(nq.w - nw) * 10.0f;
      // exp lane by lane: PoCL's float8 exp rounds otherwise than its scalar exp (the pass changed),
      // and it was not faster.
      float8 w = (float8)(exp(e.s0), exp(e.s1), exp(e.s2), exp(e.s3), exp(e.s4), exp(e.s5), exp(e.s6), exp(e.s7));
      float8 cosine = fmax(dot_lanes(nx, ny, nz, nq.x, nq.y, nq.z), 0.0f);
      for (int k = 0; k < 6; ++k) cosine *= cosine;
      w *= cosine;
      const RecordLanes c = inside ? row_record_lanes(in_rgba, first) : record_lanes(in_rgba, q);
      const float8 distance = inside ? vload8(0, in_distance + first) : gather8(in_distance, q);
      sum_r = select(sum_r, sum_r + w * c.x, take);
      sum_g = select(sum_g, sum_g + w * c.y, take);
      sum_b = select(sum_b, sum_b + w * c.z, take);
      sum_a = select(sum_a, sum_a + w * c.w, take);
      weights = select(weights, weights + w, take);
      dist_sum = select(dist_sum, dist_sum + w * c.w * distance, take);
      dist_weights = select(dist_weights, dist_weights + w * c.w, take);
    }
  }
  float r[8], g[8], b[8], a[8], w[8], ds[8], dw[8];
  vstore8(sum_r, 0, r);
  vstore8(sum_g, 0, g);
  vstore8(sum_b, 0, b);
  vstore8(sum_a, 0, a);
  vstore8(weights, 0, w);
  vstore8(dist_sum, 0, ds);
  vstore8(dist_weights, 0, dw);
  for (int l = 0; l < 8; ++l) {
    if (radius[l] < 0) continue;
    int i = y * size.x + x0 + l;
    float4 filtered = (float4)(r[l], g[l], b[l], a[l]) / w[l];  // weights >= 1: the centre pixel always counts
    // Where nothing was found the pass is 0: colour whose weights outlived A's underflow is not kept.
    out_rgba[i] = filtered.w > 0.0f ? filtered : (float4)(0.0f);
    out_distance[i] = dw[l] > 0.0f ? ds[l] / dw[l] : 0.0f;
  }
}
