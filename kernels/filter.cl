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
  int radius = clamp((int)(nr.w * 6.0f + 0.5f), 1, 4);
  float sigma2 = 0.5f * (float)(radius * radius);
  float d = positions[i].w;
  float4 sum = (float4)(0.0f);
  float weights = 0.0f, dist_sum = 0.0f, dist_weights = 0.0f;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      int qx = x + dx, qy = y + dy;
      if (qx < 0 || qy < 0 || qx >= size.x || qy >= size.y) continue;
      int q = qy * size.x + qx;
      float4 nq = normals[q];
      if (pixel_rays[q] == 0 || nq.w <= mirror_roughness) continue;
      // The Gaussian, same surface depth-wise, similar lobe width: one exp of their exponents' sum;
      // same orientation: cos^64 by six squarings (PoCL's exp and pow are library calls, which took
      // 86% of the filter's time: docs/BENCHMARKS.md "Resolve and filter").
      float w = exp(-(float)(dx * dx + dy * dy) / (2.0f * sigma2) - fabs(positions[q].w - d) / (0.01f * d) -
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
