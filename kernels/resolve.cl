// Resolve: turns ray records into the reflection pass, one batch of samples at a time.
//
// With SSRCL_VIEWS, acc_sources holds per pixel the found weight (sum w c) of each ray source
// (the main frame, then each auxiliary view), and out_view the source with the most (0 the main
// frame, k the k-th view, -1 none) and the share of the found weight that came from views.
#ifndef SSRCL_VIEWS
#define SSRCL_VIEWS 0
#endif
// SSRCL_RESOLVE_RAY_STRIDE (host/stage_support.hpp resolveRayStride): of a similar neighbour's
// rays one share in this many (1: all), the pixel's own rays all.

// Glossy pixels use the ratio estimator of Stachowiak ("Stochastic Screen-Space Reflections",
// 2015): the rays of similar neighbours are reused, weighted by this pixel's BRDF * cosine over
// the pdf the ray was drawn with, and
//   rgb = sum(w * c * L) / sum(w),  A = sum(w * c) / sum(w),  distance = sum(w * c * d) / sum(w * c)
// with c the hit's confidence (0 for a miss) - the lobe-weighted integrals TraceSettings
// documents. Mirror pixels take their single ray as it is. The sums accumulate over batches in
// acc_radiance = (sum w c L, sum w c) and acc_weight = (sum w, sum w c d), which the first batch
// starts. Both kernels run over the listed tiles only; the host clears the output elsewhere.

// GGX BRDF * cosine for local view o and light l (normal +Z), without Fresnel.
inline float ggx_brdf_cos(float3 o, float3 l, float alpha) {
  float3 h = o + l;
  float len = length(h);
  if (!(len > 0.0f) || o.z <= 0.0f || l.z <= 0.0f) return 0.0f;
  return ggx_d(h / len, alpha) * ggx_g2(o, l, alpha) / (4.0f * o.z);
}

// Neighbours must be the same surface for their rays to stand for this pixel's: similar depth
// (relative) and normal.
inline bool similar_surface(float depth_p, float3 n_p, float depth_q, float3 n_q) {
  return fabs(depth_q - depth_p) <= 0.05f * depth_p && dot(n_p, n_q) >= 0.9f;
}

__kernel void resolve_accumulate(ResolveParams params, __global const int* tile_list,
                                 __global const float4* positions,
                                 __global const float4* normals, __global const int* pixel_rays,
                                 __global const float4* ray_hit,
                                 __global const float4* ray_radiance, __global float4* acc_radiance,
                                 __global float2* acc_weight, __global const uchar* ray_state,
                                 __global float* acc_sources) {
  const int2 size = (int2)(params.width, params.height);
  const float16 inv_proj = vload16(0, params.inv_proj);
  const int batch_size = params.batch_size, first_sample = params.first_sample, reuse_radius = params.reuse_radius;
  const float mirror_roughness = params.mirror_roughness;
  int2 xy = tile_pixel(tile_list, params.tiles_x);
  int x = xy.x, y = xy.y;
  if (x >= size.x || y >= size.y) return;
  int i = y * size.x + x;
  bool first = first_sample == 0;
  float4 radiance = first ? (float4)(0.0f) : acc_radiance[i];
  float2 weight = first ? (float2)(0.0f) : acc_weight[i];
#if SSRCL_VIEWS
  __global float* sources = acc_sources + (size_t)i * (params.view_count + 1);
  if (first)
    for (int k = 0; k <= params.view_count; ++k) sources[k] = 0.0f;
#endif
  if (pixel_rays[i] == 0) {  // sky, or too rough
    acc_radiance[i] = radiance;
    acc_weight[i] = weight;
    return;
  }

  float4 nr = normals[i];
  float3 v;
  float3 p = pixel_view_point(inv_proj, size, (int2)(x, y), positions[i].w, &v);

  if (nr.w <= mirror_roughness) {
    if (first) {  // its one ray is in the first batch
      float4 h = ray_hit[(size_t)i * batch_size];
      bool hit = h.w >= 0.0f;
      radiance = hit ? (float4)(ray_radiance[(size_t)i * batch_size].xyz * h.w, h.w) : (float4)(0.0f);
      weight = (float2)(1.0f, hit ? h.w * length(h.xyz - p) : 0.0f);
#if SSRCL_VIEWS
      if (hit) sources[ray_state[(size_t)i * batch_size] >> SSRCL_RAY_SOURCE_SHIFT] += h.w;
#endif
    }
  } else {
    float3 tx, ty;
    basis_from_normal(nr.xyz, &tx, &ty);
    float3 ol = (float3)(dot(-v, tx), dot(-v, ty), dot(-v, nr.xyz));
    float alpha = fmax(roughness_to_alpha(nr.w, SSRCL_ROUGHNESS_MAPPING), 1e-4f);
    for (int dy = -reuse_radius; dy <= reuse_radius; ++dy) {
      for (int dx = -reuse_radius; dx <= reuse_radius; ++dx) {
        int qx = x + dx, qy = y + dy;
        if (qx < 0 || qy < 0 || qx >= size.x || qy >= size.y) continue;
        int q = qy * size.x + qx;
        int count = min(pixel_rays[q] - first_sample, batch_size);
        if (count <= 0 || (q != i && !similar_surface(positions[i].w, nr.xyz, positions[q].w, normals[q].xyz)))
          continue;
        // Own rays all; of a neighbour's, one of `parts` consecutive shares (consecutive rays
        // share cache lines), picked by a phase that steps by one to the next pixel in x and by
        // two in y, so neighbouring pixels take different shares of q and one pixel's neighbours
        // cover the shares evenly (a rank-1 lattice).
        int parts = q == i ? 1 : min(SSRCL_RESOLVE_RAY_STRIDE, count);
        int part = (x + 2 * y + 3 * qx + qy) % parts;
        for (int s = part * count / parts; s < (part + 1) * count / parts; ++s) {
          size_t r = (size_t)q * batch_size + s;
          float4 rad = ray_radiance[r];
          if (!(rad.w > 0.0f)) continue;  // a mirror ray (delta) or one never traced
          float4 h = ray_hit[r];
          bool hit = h.w >= 0.0f;
          float3 l = hit ? normalize(h.xyz - p) : h.xyz;
          float3 ll = (float3)(dot(l, tx), dot(l, ty), dot(l, nr.xyz));
          float w = ggx_brdf_cos(ol, ll, alpha) / rad.w;
          if (!(w > 0.0f) || !isfinite(w)) continue;
          weight.x += w;
          if (hit) {
            radiance += (float4)(rad.xyz * (w * h.w), w * h.w);
            weight.y += w * h.w * length(h.xyz - p);
#if SSRCL_VIEWS
            sources[ray_state[r] >> SSRCL_RAY_SOURCE_SHIFT] += w * h.w;
#endif
          }
        }
      }
    }
  }
  acc_radiance[i] = radiance;
  acc_weight[i] = weight;
}

__kernel void resolve_finalize(ResolveParams params, __global const int* tile_list,
                               __global const float4* acc_radiance, __global const float2* acc_weight,
                               __global float4* out_rgba, __global float* out_distance,
                               __global const float* acc_sources, __global float2* out_view) {
  const int2 size = (int2)(params.width, params.height);
  int2 xy = tile_pixel(tile_list, params.tiles_x);
  int x = xy.x, y = xy.y;
  if (x >= size.x || y >= size.y) return;
  int i = y * size.x + x;
  float4 r = acc_radiance[i];
  float2 w = acc_weight[i];
  bool any = w.x > 0.0f && r.w > 0.0f;
  float4 rgba = any ? r / w.x : (float4)(0.0f);
  rgba.w = clamp(rgba.w, 0.0f, 1.0f);
  out_rgba[i] = all(isfinite(rgba)) ? rgba : (float4)(0.0f);
  float d = any ? w.y / r.w : 0.0f;
  out_distance[i] = isfinite(d) ? d : 0.0f;
#if SSRCL_VIEWS
  __global const float* sources = acc_sources + (size_t)i * (params.view_count + 1);
  int best = -1;
  float best_weight = 0.0f, total = 0.0f;
  for (int k = 0; k <= params.view_count; ++k) {
    total += sources[k];
    if (sources[k] > best_weight) {
      best = k;
      best_weight = sources[k];
    }
  }
  float share = total > 0.0f ? (total - sources[0]) / total : 0.0f;
  out_view[i] = (float2)((float)best, isfinite(share) ? clamp(share, 0.0f, 1.0f) : 0.0f);
#endif
}
