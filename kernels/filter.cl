// Optional edge-aware spatial filter of the resolved glossy pass: a Gaussian whose radius grows
// with roughness (rougher lobes vary slowly), stopped at depth and normal edges so reflections
// do not bleed across objects. Mirror-like and untraced pixels pass through unchanged. Runs over
// the listed tiles: pixels that reflect lie in them, and it reads no others.
__kernel void denoise(FilterParams params, __global const int* tile_list, __global const float4* positions, __global const float4* normals, __global const int* pixel_rays,
                      __global const float4* in_rgba, __global const float* in_distance,
                      __global float4* out_rgba, __global float* out_distance) {
  const int2 size = (int2)(params.frame.width, params.frame.height);
  const float mirror_roughness = params.frame.mirror_roughness;
  int2 xy = tile_pixel(tile_list, params.frame.tiles_x);
  int x = xy.x, y = xy.y;
  if (x >= size.x || y >= size.y) return;
  int i = y * size.x + x;
  float4 nr = normals[i];
  if (pixel_rays[i] == 0 || nr.w <= mirror_roughness) {
    out_rgba[i] = in_rgba[i];
    out_distance[i] = in_distance[i];
    return;
  }
  // Wider for rougher lobes, narrower the more rays the pixel has: its noise falls as 1/sqrt(rays),
  // and a wide kernel over a well-sampled pixel only blurs (12 x roughness at 4 rays). A pixel
  // resolved from its neighbours' rays alone (-1, strided tracing) counts as one.
  int radius = clamp((int)(nr.w * 24.0f * rsqrt((float)max(pixel_rays[i], 1)) + 0.5f), 1, 6);
  float sigma2 = 0.5f * (float)(radius * radius);
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
  float4 sum = (float4)(0.0f);
  float weights = 0.0f, dist_sum = 0.0f, dist_weights = 0.0f;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      int qx = x + dx, qy = y + dy;
      if (qx < 0 || qy < 0 || qx >= size.x || qy >= size.y) continue;
      int q = qy * size.x + qx;
      float4 nq = normals[q];
      if (pixel_rays[q] == 0 || nq.w <= mirror_roughness) continue;
      // The Gaussian, on the same plane, similar lobe width: one exp of their exponents' sum;
      // same orientation: cos^64 by six squarings (PoCL's exp and pow are library calls, which took
      // 86% of the filter's time: docs/BENCHMARKS.md "Resolve and filter").
      float w = exp(-(float)(dx * dx + dy * dy) / (2.0f * sigma2) - fabs(positions[q].w * (inv_d + dx * g.x + dy * g.y) - 1.0f) / 0.01f -
                    fabs(nq.w - nr.w) * 10.0f);
      float cosine = fmax(dot(nr.xyz, nq.xyz), 0.0f);
      for (int k = 0; k < 6; ++k) cosine *= cosine;
      w *= cosine;
      float4 c = in_rgba[q];
      sum += w * c;
      weights += w;
      dist_sum += w * c.w * in_distance[q];
      dist_weights += w * c.w;
    }
  }
  float4 filtered = sum / weights;  // weights >= 1: the centre pixel always counts
  // Where nothing was found the pass is 0: colour whose weights outlived A's underflow is not kept.
  out_rgba[i] = filtered.w > 0.0f ? filtered : (float4)(0.0f);
  out_distance[i] = dist_weights > 0.0f ? dist_sum / dist_weights : 0.0f;
}
