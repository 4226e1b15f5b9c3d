// Resolve: turns ray records into the reflection pass, one batch of samples at a time.
//
// With SSRCL_VIEWS, acc_sources holds per pixel the found weight (sum w c) of each ray source
// (the main frame, then each auxiliary view), and out_view the source with the most (0 the main
// frame, k the k-th view, -1 none) and the share of the found weight that came from views.
#ifndef SSRCL_VIEWS
#define SSRCL_VIEWS 0
#endif
// SSRCL_RESOLVE_RAY_STRIDE (host/pipeline/stage_support.hpp resolveRayStride): of a similar neighbour's
// rays one share in this many (1: all), the pixel's own rays all.

// Glossy pixels use the ratio estimator of Stachowiak ("Stochastic Screen-Space Reflections",
// 2015): the rays of similar neighbours are reused, weighted by this pixel's BRDF * cosine over
// the pdf the ray was drawn with (at least a quarter of this pixel's own: ggx_reuse_weights), and
//   rgb = sum(w * c * L) / sum(w),  A = sum(w * c) / sum(w),  distance = sum(w * c * d) / sum(w * c)
// with c the hit's confidence (0 for a miss) - the lobe-weighted integrals TraceSettings
// documents. Mirror pixels take their single ray as it is. The sums accumulate over batches in
// acc_radiance = (sum w c L, sum w c) and acc_weight = (sum w, sum w c d), which the first batch
// starts. Both kernels run over the listed tiles only; the host clears the output elsewhere.

// What every tap of one glossy pixel shares: its local view o, alpha^2, 1 + 2 Lambda(o) and the
// constant factor below. Computed once per pixel, so that a tap's BRDF * cosine / pdf costs two
// square roots and one division, four taps to an instruction: a tap's divisions and square roots,
// not its memory reads, are what the resolve costs on PoCL (docs/BENCHMARKS.md "Resolve and filter:
// divisions and transcendentals").
typedef struct {
  float3 o;
  float a2, c, scale;
} GgxLobe;

inline GgxLobe ggx_lobe(float3 o, float alpha) {
  GgxLobe lobe = {o, alpha * alpha, 1.0f + 2.0f * ggx_lambda(o, alpha), alpha * alpha / (2.0f * SSRCL_PI * o.z)};
  return lobe;
}

// GGX BRDF * cosine (without Fresnel) over the pdf each ray was drawn with, for four rays in
// float4 lanes (PoCL keeps OpenCL vectors packed: one vdivps or vsqrtps serves four taps; its
// work-item loop is not vectorised). l = (lx, ly, lz) local, of length len (not normalised: no
// division). D(h) G2(o, l) / (4 o.z pdf) (ggx_d, ggx_lambda in ggx.cl; G2 height-correlated)
// with the half vector left unnormalised too, H = o len + l, both factors of degree 0 in H and l:
//   D = a2 |H|^4 / (pi K^2),  K = a2 Hz^2 + Hx^2 + Hy^2
//   G2 = 1 / (1 + Lambda(o) + Lambda(l)) = 2 lz / (c lz + sqrt(lz^2 + a2 (lx^2 + ly^2)))
// so the weight is scale |H|^4 lz / (K^2 (c lz + s) pdf), 0 below the surface (G2 = 0 there; H
// vanishes only there, l = -o).
//
// The pdf taken is at least a quarter of the one this pixel's own sampling gives the direction (a
// max heuristic): a neighbour's ray weighs at most four of the pixel's own rays there, whose
// weight is BRDF * cosine / own pdf = G2 / G1(o) = (1 + c) lz / (c lz + s). A neighbour's lobe
// turned away by a normal map draws this lobe's directions in its tail, with a pdf far below this
// pixel's: one such ray outweighed all the pixel's own, and the block of neighbours it served showed
// its colour. Medium, corpus: 23.03 -> 23.32 dB, added mean signed error 0.0005 a scene; a polished
// normal-mapped wooden floor (roughness 0.15-0.19) 25.69 -> 26.19 dB. A bound of one own ray gained
// more (23.38 dB, the floor 26.64) but darkened the analytic glossy floor by 2% (the lobe's core,
// which neighbours draw less often than the pixel would, counts less than its tails); this one adds
// -0.0012 to its A. The pixel's own rays are unchanged (their pdf is that own pdf).
inline float4 ggx_reuse_weights(GgxLobe lobe, float4 lx, float4 ly, float4 lz, float4 len, float4 pdf) {
  float4 hx = lobe.o.x * len + lx, hy = lobe.o.y * len + ly, hz = lobe.o.z * len + lz;
  float4 h2 = hx * hx + hy * hy + hz * hz;
  float4 k = lobe.a2 * hz * hz + (hx * hx + hy * hy);
  float4 s = sqrt(lz * lz + lobe.a2 * (lx * lx + ly * ly));
  float4 w = lz / (lobe.c * lz + s) * fmin(lobe.scale * (h2 * h2) / (k * k * pdf), 4.0f * (1.0f + lobe.c));
  return select((float4)(0.0f), w, lz > 0.0f);
}

// Records base + slot.s0 .. s3, transposed: .s0123 their x, .s4567 y, .s89ab z, .scdef w.
inline float16 record_lanes(__global const float4* records, size_t base, int4 slot) {
  return (float16)(records[base + slot.s0], records[base + slot.s1], records[base + slot.s2], records[base + slot.s3])
      .s048c159d26ae37bf;
}

inline float lane_sum(float4 v) { return (v.s0 + v.s1) + (v.s2 + v.s3); }

#if SSRCL_VIEWS
inline void add_source(__global float* sources, __global const uchar* ray_state, size_t r, float found) {
  if (found > 0.0f) sources[ray_state[r] >> SSRCL_RAY_SOURCE_SHIFT] += found;
}
#endif

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
  const int2 size = (int2)(params.frame.width, params.frame.height);
  const float16 inv_proj = vload16(0, params.frame.inv_proj);
  const int batch_size = params.batch_size, first_sample = params.first_sample, reuse_radius = params.reuse_radius;
  const float mirror_roughness = params.frame.mirror_roughness;
  int2 xy = tile_pixel(tile_list, params.frame.tiles_x);
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
    GgxLobe lobe = ggx_lobe(ol, fmax(roughness_to_alpha(nr.w, SSRCL_ROUGHNESS_MAPPING), 1e-4f));
    // Seen from below the lobe weighs no ray (G2 = 0): nothing accumulates.
    const int radius = ol.z > 0.0f ? reuse_radius : -1;
    const float inv_depth = 1.0f / positions[i].w;
    for (int dy = -radius; dy <= radius; ++dy) {
      for (int dx = -radius; dx <= radius; ++dx) {
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
        // Four rays at a time; lanes past the share's end repeat its last ray and take no weight.
        const int end = (part + 1) * count / parts;
        const size_t base = (size_t)q * batch_size;
        for (int s = part * count / parts; s < end; s += 4) {
          int4 lane = (int4)(s) + (int4)(0, 1, 2, 3), slot = min(lane, end - 1);
          float16 hit_rec = record_lanes(ray_hit, base, slot), rad = record_lanes(ray_radiance, base, slot);
          float4 pdf = rad.scdef, confidence = hit_rec.scdef;
          int4 hit = confidence >= 0.0f;
          float4 dx = hit_rec.s0123 - p.x, dy = hit_rec.s4567 - p.y, dz = hit_rec.s89ab - p.z;
          float4 distance = sqrt(dx * dx + dy * dy + dz * dz);
          // Toward the hit in units of this pixel's depth (the weight is of degree 5 in it: near 1
          // whatever the scene's unit, far from float's range), or a miss's direction as recorded.
          float4 lx = select(hit_rec.s0123, dx * inv_depth, hit), ly = select(hit_rec.s4567, dy * inv_depth, hit),
                 lz = select(hit_rec.s89ab, dz * inv_depth, hit), len = select((float4)(1.0f), distance * inv_depth, hit);
          float4 w = ggx_reuse_weights(lobe, lx * tx.x + ly * tx.y + lz * tx.z, lx * ty.x + ly * ty.y + lz * ty.z,
                                       lx * nr.x + ly * nr.y + lz * nr.z, len, pdf);
          // pdf 0: a mirror ray (delta) or one never traced; their records' colours may be anything.
          int4 take = lane < end && pdf > 0.0f && w > 0.0f && isfinite(w), found = take && hit;
          w = select((float4)(0.0f), w, take);
          float4 wc = select((float4)(0.0f), w * confidence, found);
          weight.x += lane_sum(w);
          radiance += (float4)(lane_sum(select((float4)(0.0f), rad.s0123 * wc, found)),
                               lane_sum(select((float4)(0.0f), rad.s4567 * wc, found)),
                               lane_sum(select((float4)(0.0f), rad.s89ab * wc, found)), lane_sum(wc));
          weight.y += lane_sum(select((float4)(0.0f), wc * distance, found));
#if SSRCL_VIEWS
          add_source(sources, ray_state, base + slot.s0, wc.s0);
          add_source(sources, ray_state, base + slot.s1, wc.s1);
          add_source(sources, ray_state, base + slot.s2, wc.s2);
          add_source(sources, ray_state, base + slot.s3, wc.s3);
#endif
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
  const int2 size = (int2)(params.frame.width, params.frame.height);
  int2 xy = tile_pixel(tile_list, params.frame.tiles_x);
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
