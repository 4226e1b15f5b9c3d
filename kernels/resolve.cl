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

// A work-item resolves one row of a tile, SSRCL_TILE pixels, one pixel to a float8 lane: each
// tap's divisions and square roots then serve eight pixels. Each lane runs the sequence of
// operations its pixel alone would (the same taps in the same order, each group of up to four
// consecutive rays of one share summed as (r0 + r1) + (r2 + r3) before it is added), so the
// output does not depend on the lanes. Four of a pixel's rays to a float4 did the same work per
// neighbour whether the neighbour's share was one ray (medium, draft) or four: 25 groups of four
// for medium's 28 rays, where eight pixels now take 28 of eight.
#if SSRCL_TILE != 8
#error "resolve_accumulate puts a tile row in float8 lanes"
#endif

// What every tap of one glossy pixel shares: its local view o, alpha^2, 1 + 2 Lambda(o) and the
// constant factor below, computed once per pixel, so that a tap's BRDF * cosine / pdf costs two
// square roots and one division.
typedef struct {
  float3 o;
  float a2, c, scale;
} GgxLobe;

inline GgxLobe ggx_lobe(float3 o, float alpha) {
  GgxLobe lobe = {o, alpha * alpha, 1.0f + 2.0f * ggx_lambda(o, alpha), alpha * alpha / (2.0f * SSRCL_PI * o.z)};
  return lobe;
}

// Eight pixels' lobes, one to a lane.
typedef struct {
  float8 ox, oy, oz, a2, c, scale;
} GgxLobes;

// GGX BRDF * cosine (without Fresnel) over the pdf each ray was drawn with, one ray per lane.
// l = (lx, ly, lz) local, of length len (not normalised: no division). D(h) G2(o, l) / (4 o.z
// pdf) (ggx_d, ggx_lambda in ggx.cl; G2 height-correlated) with the half vector left
// unnormalised too, H = o len + l, both factors of degree 0 in H and l:
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
inline float8 ggx_reuse_weights(GgxLobes lobe, float8 lx, float8 ly, float8 lz, float8 len, float8 pdf) {
  float8 hx = lobe.ox * len + lx, hy = lobe.oy * len + ly, hz = lobe.oz * len + lz;
  float8 h2 = hx * hx + hy * hy + hz * hz;
  float8 k = lobe.a2 * hz * hz + (hx * hx + hy * hy);
  float8 s = sqrt(lz * lz + lobe.a2 * (lx * lx + ly * ly));
  float8 w = lz / (lobe.c * lz + s) * fmin(lobe.scale * (h2 * h2) / (k * k * pdf), 4.0f * (1.0f + lobe.c));
  return select((float8)(0.0f), w, lz > 0.0f);
}

// What a glossy pixel's taps share besides its lobe: its point, normal and tangents, depth.
typedef struct {
  float3 p, n, tx, ty;
  float depth, inv_depth;
} TapFrame;

// Eight pixels' TapFrames, one to a lane.
typedef struct {
  float8 px, py, pz, nx, ny, nz, txx, txy, txz, tyx, tyy, tyz, depth, inv_depth;
} TapFrames;

// One tap's terms of the sums, or a group's: w, w c L (rgb), w c, w c d.
typedef struct {
  float8 w, r, g, b, wc, wcd;
} TapSums;

inline TapSums tap_add(TapSums a, TapSums b) {
  TapSums s = {a.w + b.w, a.r + b.r, a.g + b.g, a.b + b.b, a.wc + b.wc, a.wcd + b.wcd};
  return s;
}

// The taps of the records in slot (live lanes only), each weighed by its lane's lobe.
inline TapSums resolve_taps(__global const float4* ray_hit, __global const float4* ray_radiance, TapFrames f,
                            GgxLobes lobe, int8 slot, int8 live) {
  RecordLanes hit_rec = record_lanes(ray_hit, slot), rad = record_lanes(ray_radiance, slot);
  float8 pdf = rad.w, confidence = hit_rec.w;
  int8 hit = confidence >= 0.0f;
  float8 dx = hit_rec.x - f.px, dy = hit_rec.y - f.py, dz = hit_rec.z - f.pz;
  float8 distance = sqrt(dx * dx + dy * dy + dz * dz);
  // Toward the hit in units of this pixel's depth (the weight is of degree 5 in it: near 1
  // whatever the scene's unit, far from float's range), or a miss's direction as recorded.
  float8 lx = select(hit_rec.x, dx * f.inv_depth, hit), ly = select(hit_rec.y, dy * f.inv_depth, hit),
         lz = select(hit_rec.z, dz * f.inv_depth, hit), len = select((float8)(1.0f), distance * f.inv_depth, hit);
  float8 w = ggx_reuse_weights(lobe, lx * f.txx + ly * f.txy + lz * f.txz, lx * f.tyx + ly * f.tyy + lz * f.tyz,
                               lx * f.nx + ly * f.ny + lz * f.nz, len, pdf);
  // pdf 0: a mirror ray (delta) or one never traced; their records' colours may be anything.
  int8 take = live && pdf > 0.0f && w > 0.0f && isfinite(w), found = take && hit;
  w = select((float8)(0.0f), w, take);
  float8 wc = select((float8)(0.0f), w * confidence, found);
  TapSums t = {w,
               select((float8)(0.0f), rad.x * wc, found),
               select((float8)(0.0f), rad.y * wc, found),
               select((float8)(0.0f), rad.z * wc, found),
               wc,
               select((float8)(0.0f), wc * distance, found)};
  return t;
}

// n / d for 0 <= n < 2^22 and d in 1..4, without integer division (x86 has none in vectors):
// n times the float reciprocal of d, which is exact or (1/3) rounded up, truncated (checked for
// every such n and d). One reciprocal serves a neighbour's three quotients.
#if SSRCL_RESOLVE_RAY_STRIDE > 4 || (SSRCL_RESOLVE_RAY_STRIDE & (SSRCL_RESOLVE_RAY_STRIDE - 1))
#error "resolve_accumulate's quotient() divides by at most 4, its one-ray shares by a power of two"
#endif
inline int8 quotient(int8 n, float8 inv_d) { return convert_int8(convert_float8(n) * inv_d); }

#if SSRCL_VIEWS
inline void add_source(__global float* sources, __global const uchar* ray_state, size_t r, float found) {
  if (found > 0.0f) sources[ray_state[r] >> SSRCL_RAY_SOURCE_SHIFT] += found;
}
#endif

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
  const int2 row = tile_pixel(tile_list, params.frame.tiles_x);  // work-groups (1, SSRCL_TILE): a row's first pixel
  const int x0 = row.x, y = row.y;
  if (y >= size.y) return;
  const bool first = first_sample == 0;

  // Each pixel's sums as they stand, and what its glossy taps need (tapping: it takes some).
  float4 radiance[8];
  float2 weight[8];
  int tapping[8];
  TapFrame frame[8];
  GgxLobe lobes[8];
  bool any_taps = false;
  for (int l = 0; l < 8; ++l) {
    int x = x0 + l, i = y * size.x + x;
    tapping[l] = 0;
    frame[l].p = frame[l].n = frame[l].tx = frame[l].ty = (float3)(0.0f);
    frame[l].depth = frame[l].inv_depth = 0.0f;
    lobes[l].o = (float3)(0.0f);
    lobes[l].a2 = lobes[l].c = lobes[l].scale = 0.0f;
    radiance[l] = (float4)(0.0f);
    weight[l] = (float2)(0.0f);
    if (x >= size.x) continue;
    if (!first) {
      radiance[l] = acc_radiance[i];
      weight[l] = acc_weight[i];
    }
#if SSRCL_VIEWS
    __global float* sources = acc_sources + (size_t)i * (params.view_count + 1);
    if (first)
      for (int k = 0; k <= params.view_count; ++k) sources[k] = 0.0f;
#endif
    if (pixel_rays[i] == 0) continue;  // sky, or too rough
    float4 nr = normals[i];
    float3 v;
    float3 p = pixel_view_point(inv_proj, size, (int2)(x, y), positions[i].w, &v);
    if (nr.w <= mirror_roughness) {
      if (first) {  // its one ray is in the first batch
        float4 h = ray_hit[(size_t)i * batch_size];
        bool hit = h.w >= 0.0f;
        radiance[l] = hit ? (float4)(ray_radiance[(size_t)i * batch_size].xyz * h.w, h.w) : (float4)(0.0f);
        weight[l] = (float2)(1.0f, hit ? h.w * length(h.xyz - p) : 0.0f);
#if SSRCL_VIEWS
        if (hit) sources[ray_state[(size_t)i * batch_size] >> SSRCL_RAY_SOURCE_SHIFT] += h.w;
#endif
      }
      continue;
    }
    float3 tx, ty;
    basis_from_normal(nr.xyz, &tx, &ty);
    float3 ol = (float3)(dot(-v, tx), dot(-v, ty), dot(-v, nr.xyz));
    // Seen from below the lobe weighs no ray (G2 = 0): nothing accumulates.
    if (!(ol.z > 0.0f)) continue;
    lobes[l] = ggx_lobe(ol, fmax(roughness_to_alpha(nr.w, SSRCL_ROUGHNESS_MAPPING), 1e-4f));
    frame[l].p = p;
    frame[l].n = nr.xyz;
    frame[l].tx = tx;
    frame[l].ty = ty;
    frame[l].depth = positions[i].w;
    frame[l].inv_depth = 1.0f / positions[i].w;
    tapping[l] = -1;
    any_taps = true;
  }

  if (any_taps) {
    const TapFrames f = {SSRCL_LANES(frame, p.x),  SSRCL_LANES(frame, p.y),  SSRCL_LANES(frame, p.z),
                         SSRCL_LANES(frame, n.x),  SSRCL_LANES(frame, n.y),  SSRCL_LANES(frame, n.z),
                         SSRCL_LANES(frame, tx.x), SSRCL_LANES(frame, tx.y), SSRCL_LANES(frame, tx.z),
                         SSRCL_LANES(frame, ty.x), SSRCL_LANES(frame, ty.y), SSRCL_LANES(frame, ty.z),
                         SSRCL_LANES(frame, depth), SSRCL_LANES(frame, inv_depth)};
    const GgxLobes lobe = {SSRCL_LANES(lobes, o.x), SSRCL_LANES(lobes, o.y), SSRCL_LANES(lobes, o.z),
                           SSRCL_LANES(lobes, a2),  SSRCL_LANES(lobes, c),   SSRCL_LANES(lobes, scale)};
    TapSums sum = {SSRCL_LANES(weight, x), SSRCL_LANES(radiance, x), SSRCL_LANES(radiance, y),
                   SSRCL_LANES(radiance, z), SSRCL_LANES(radiance, w), SSRCL_LANES(weight, y)};
    const int8 x = x0 + (int8)(0, 1, 2, 3, 4, 5, 6, 7), taps = vload8(0, tapping);
    for (int dy = -reuse_radius; dy <= reuse_radius; ++dy) {
      const int qy = y + dy;
      if (qy < 0 || qy >= size.y) continue;
      for (int dx = -reuse_radius; dx <= reuse_radius; ++dx) {
        const bool own = dx == 0 && dy == 0;
        const int8 qx = x + dx, q = qy * size.x + clamp(qx, 0, size.x - 1);
        // All eight neighbours in the frame lie side by side: vector loads (as the filter's taps).
        const int first_q = qy * size.x + x0 + dx;
        const bool inside = x0 + dx >= 0 && x0 + dx + 7 < size.x;
        const int8 rays_q = inside ? vload8(0, pixel_rays + first_q)
                                   : (int8)(pixel_rays[q.s0], pixel_rays[q.s1], pixel_rays[q.s2], pixel_rays[q.s3],
                                            pixel_rays[q.s4], pixel_rays[q.s5], pixel_rays[q.s6], pixel_rays[q.s7]);
        const int8 count = min(rays_q - first_sample, batch_size);
        int8 similar = (int8)(-1);
        // Neighbours must be the same surface for their rays to stand for this pixel's: similar
        // depth (relative) and normal.
        if (!own) {
          RecordLanes n_q = inside ? row_record_lanes(normals, first_q) : record_lanes(normals, q);
          float8 depth_q = inside ? row_record_lanes(positions, first_q).w : record_lanes(positions, q).w;
          similar = fabs(depth_q - f.depth) <= 0.05f * f.depth
                    && dot_lanes(f.nx, f.ny, f.nz, n_q.x, n_q.y, n_q.z) >= 0.9f;
        }
        const int8 valid = taps && qx >= 0 && qx < size.x && count > 0 && similar;
        if (!any_lane(valid)) continue;
        // Own rays all; of a neighbour's, one of `parts` consecutive shares (consecutive rays
        // share cache lines), picked by a phase that steps by one to the next pixel in x and by
        // two in y, so neighbouring pixels take different shares of q and one pixel's neighbours
        // cover the shares evenly (a rank-1 lattice).
        const int8 phase = x + 2 * y + 3 * qx + qy, base = q * batch_size;
        int8 start, end;
        if (!own && count_lanes(valid && count == SSRCL_RESOLVE_RAY_STRIDE) == count_lanes(valid)) {
          // Each valid lane's share is one ray, `phase mod stride`: what the quotients below give,
          // without their chain of conversions (a third of the resolve's time at medium).
          start = select((int8)(0), phase & (SSRCL_RESOLVE_RAY_STRIDE - 1), valid);
          end = select((int8)(0), start + 1, valid);
        } else {
          const int8 parts = own ? (int8)(1) : select((int8)(1), min(count, SSRCL_RESOLVE_RAY_STRIDE), valid);
          const float8 inv_parts = 1.0f / convert_float8(parts);
          const int8 part = phase - parts * quotient(phase, inv_parts);
          start = select((int8)(0), quotient(part * count, inv_parts), valid);
          end = select((int8)(0), quotient((part + 1) * count, inv_parts), valid);
        }
        const int longest = max_lane(end - start);
        // Groups of four consecutive rays of each share, as a pixel's own taps were taken: a
        // group's sum is (t0 + t1) + (t2 + t3), a missing tap adding nothing.
        for (int c = 0; c < longest; c += 4) {
          TapSums group[4];
          const int n = min(4, longest - c);
          for (int k = 0; k < n; ++k) {
            const int8 s = start + (c + k), live = s < end, slot = select((int8)(0), base + s, live);
            group[k] = resolve_taps(ray_hit, ray_radiance, f, lobe, slot, live);
#if SSRCL_VIEWS
            float found[8];
            int slots[8];
            vstore8(group[k].wc, 0, found);
            vstore8(slot, 0, slots);
            for (int l = 0; l < 8; ++l)
              add_source(acc_sources + (size_t)(y * size.x + x0 + l) * (params.view_count + 1), ray_state, slots[l],
                         found[l]);
#endif
          }
          TapSums t = group[0];
          if (n > 1) t = tap_add(t, group[1]);
          if (n > 2) t = tap_add(t, n > 3 ? tap_add(group[2], group[3]) : group[2]);
          sum = tap_add(sum, t);
        }
      }
    }
    float r[8], g[8], b[8], wc[8], w[8], wcd[8];
    vstore8(sum.w, 0, w);
    vstore8(sum.r, 0, r);
    vstore8(sum.g, 0, g);
    vstore8(sum.b, 0, b);
    vstore8(sum.wc, 0, wc);
    vstore8(sum.wcd, 0, wcd);
    for (int l = 0; l < 8; ++l) {
      if (!tapping[l]) continue;
      radiance[l] = (float4)(r[l], g[l], b[l], wc[l]);
      weight[l] = (float2)(w[l], wcd[l]);
    }
  }
  for (int l = 0; l < 8; ++l) {
    int x = x0 + l, i = y * size.x + x;
    if (x >= size.x) continue;
    acc_radiance[i] = radiance[l];
    acc_weight[i] = weight[l];
  }
}

// out_rgba may be acc_radiance itself (the filter's input, host/pipeline/resolve_stage.cpp): each
// pixel reads its sums before it writes its result.
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
