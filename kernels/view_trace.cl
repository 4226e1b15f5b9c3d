// Auxiliary views: a ray the main frame leaves unresolved (a miss, a hit faded at the frame's
// edge, a hit found after passing behind a surface the frame shows, which may hide what the ray
// really meets, or a hit found within a surface's thickness, which may stand in front of it) continues in other G-buffers of the same scene. A ray is a straight line in
// every perspective view, so it is clipped to the view's frustum, projected into the view's
// screen and traced there by the same tracer (trace.cl) against the view's own range pyramid and
// surface planes (back faces included). The hit's colour is the view's.
//
// One pass per (rank, view): a ray takes part in the pass of view k at rank r when k is its r-th
// best view, so every ray tries its views best first and at most SSRCL_VIEWS_PER_RAY of them.
// Views are ranked by where the ray goes: those whose frustum holds the ray's origin first, then
// by how far the ray heads along the view's line of sight (it stays longest in that view). The
// first pass ranks them once for all passes (view_order: a byte per rank).

inline float view_score(__global const ViewCamera* views, int k, float3 p, float3 dir) {
  ViewCamera v = views[k];
  float16 m = vload16(0, v.from_main);
  float3 pk = mat_mul(m, (float4)(p, 1.0f)).xyz;
  float3 dk = mat3_mul(m, dir);
  float4 h = mat_mul(vload16(0, v.proj), (float4)(pk, 1.0f));
  bool inside = h.w > 0.0f && fabs(h.x) <= h.w && fabs(h.y) <= h.w;
  return (inside ? 2.0f : 0.0f) - dk.z / length(dk);
}

// The ray's best SSRCL_VIEWS_PER_RAY views, byte r the view of rank r (0 best; ties go to the
// lower index), 255 past the last view.
inline uint view_order(__global const ViewCamera* views, int view_count, float3 p, float3 dir) {
  float score[SSRCL_MAX_VIEWS];
  for (int k = 0; k < view_count; ++k) score[k] = view_score(views, k, p, dir);
  uint order = 0xffffffffu;
  for (int r = 0; r < min(view_count, SSRCL_VIEWS_PER_RAY); ++r) {
    int best = -1;
    for (int k = 0; k < view_count; ++k)
      if (score[k] > -INFINITY && (best < 0 || score[k] > score[best])) best = k;
    if (best < 0) break;
    order = (order & ~(0xffu << (8 * r))) | ((uint)best << (8 * r));
    score[best] = -INFINITY;
  }
  return order;
}

inline bool has_rank(uint order, int rank, int view) { return ((order >> (8 * rank)) & 0xffu) == (uint)view; }

// Clips the ray p + u dir, u in [0, len], to the view's frustum (Liang-Barsky on its clip-space
// planes, each affine in u). False when no part of it is inside.
inline bool clip_to_frustum(float16 proj, float near_plane, float far_plane, float3 p, float3 dir, float len,
                            float* u0, float* u1) {
  float4 c0 = mat_mul(proj, (float4)(p, 1.0f)), cd = mat_mul(proj, (float4)(dir, 0.0f));
  // Each plane as f(u) = a + b u >= 0: the four sides, then near and far in view depth.
  float a[6] = {c0.w - c0.x, c0.w + c0.x, c0.w - c0.y, c0.w + c0.y, -p.z - near_plane, far_plane + p.z};
  float b[6] = {cd.w - cd.x, cd.w + cd.x, cd.w - cd.y, cd.w + cd.y, -dir.z, dir.z};
  float lo = 0.0f, hi = len;
  for (int k = 0; k < (isfinite(far_plane) ? 6 : 5); ++k) {
    if (b[k] == 0.0f) {
      if (a[k] < 0.0f) return false;
    } else if (b[k] > 0.0f) {
      lo = fmax(lo, -a[k] / b[k]);
    } else {
      hi = fmin(hi, -a[k] / b[k]);
    }
  }
  // Both ends a hair inside, so that they project onto the view's pixels.
  float margin = 1e-4f * (hi - lo);
  *u0 = lo + margin;
  *u1 = hi - margin;
  return hi > lo && isfinite(lo) && isfinite(hi);
}

// A view rendered at another moment (a neighbouring frame) shows the scene as it was then. Its hit
// texel counts only where the frame cannot tell that it moved: its surface point, reprojected
// into the frame, lies outside it or behind what the frame shows there (hidden from the frame).
// In front of the nearest surface the frame shows around that pixel (3x3: a silhouette a pixel
// off is no disagreement) by more than 2% of its depth, the frame would see it, and what it shows
// instead says the hit has moved (or left) since.
inline bool moved_since(float16 main_proj, int2 size, __global const float4* main_positions, float3 hit) {
  float4 h = mat_mul(main_proj, (float4)(hit, 1.0f));
  if (!(h.w > 0.0f) || fabs(h.x) >= h.w || fabs(h.y) >= h.w) return false;
  int2 c = clamp(convert_int2(ndc_to_pixel(h.xy / h.w, size)), (int2)(0, 0), size - 1);
  float nearest = INFINITY;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int2 q = clamp(c + (int2)(dx, dy), (int2)(0, 0), size - 1);
      nearest = fmin(nearest, main_positions[q.y * size.x + q.x].w);
    }
  return -hit.z < 0.98f * nearest;
}

// One ray of a round in the view: the frame's record of it, and where it stands in the view.
typedef struct {
  size_t record;
  int pixel;
  float4 h, rad;
  uchar state;
  float3 p;  // its origin in the frame
  float main_distance;
} ViewRay;

__kernel void trace_views(ViewTraceParams params, __global const ViewCamera* views,
                          __global const float4* main_positions, __global const float4* main_normals,
                          __global const int* ray_list, __global const int* pixel_rays,
                          __global const float2* range, __global const HzbLevel* levels,
                          __global const float4* positions, __global const float4* normals,
                          __global const float4* planes, __global const float4* color_pyramid,
                          __global float4* ray_hit, __global float4* ray_radiance, __global uchar* ray_state,
                          __global uint* ray_view_order) {
  const int2 main_size = (int2)(params.frame.width, params.frame.height);
  const int batch_size = params.batch_size;
  const ViewCamera cam = views[params.view];
  const float16 from_main = vload16(0, cam.from_main), proj = vload16(0, cam.proj);
  const int2 size = (int2)(cam.width, cam.height);
  // The rays of SSRCL_TRACE_PIXELS listed pixels per work-item, in rounds of the ones that go on
  // in this view, traced together (trace.cl trace_round) and then taken or left one by one.
  const TraceScene view_scene = {size, levels, params.level_count, planes, normals, params.max_iterations,
                                  0,    0,      0,                  0,      0,       range};
  int next;
  const int end = work_item_rays(params.listed, batch_size, &next);
  while (next < end) {
    ViewRay lane[SSRCL_TRACE_ROUND];
    TraceScene scene[SSRCL_TRACE_ROUND];
    Round round;
    round_begin(&round, scene, &view_scene);
    int count = 0;
    while (count < SSRCL_TRACE_ROUND && next < end) {
      const int gid = next++;
      const int i = ray_list[gid / batch_size];
      const int slot = gid % batch_size;
      if (params.first_sample + slot >= pixel_rays[i]) continue;
      const size_t record = (size_t)i * batch_size + slot;
      const float4 h = ray_hit[record];
      const uchar state = ray_state[record];
      const bool hit = h.w >= 0.0f, thick = (state & SSRCL_RAY_THICK) != 0;
      if (hit && h.w >= 1.0f && !(state & SSRCL_RAY_BEHIND) && !thick) continue;  // resolved in full
      if (!hit && !(dot(h.xyz, h.xyz) > 0.0f)) continue;  // no ray (facing away, below the surface)
      if (!params.rank_views && !has_rank(ray_view_order[record], params.rank, params.view)) continue;

      float3 v;
      const float3 p = pixel_view_point(vload16(0, params.frame.inv_proj), main_size,
                                        (int2)(i % main_size.x, i / main_size.x), main_positions[i].w, &v);
      const float3 dir = hit ? normalize(h.xyz - p) : h.xyz;
      const float main_distance = hit ? length(h.xyz - p) : INFINITY;
      if (params.rank_views) {
        const uint order = view_order(views, params.view_count, p, dir);
        ray_view_order[record] = order;
        if (!has_rank(order, params.rank, params.view)) continue;
      }

      const float3 pk = mat_mul(from_main, (float4)(p, 1.0f)).xyz;
      const float3 dk = normalize(mat3_mul(from_main, dir));
      // A hit the main frame found by crossing a surface is looked for up to just past it: the view
      // may see it whole, or a surface in front of it that the frame hid.
      const float len = hit && !thick ? 1.02f * main_distance : 1e6f * fmax(length(pk), cam.near_plane);
      float u0, u1;
      if (!clip_to_frustum(proj, cam.near_plane, cam.far_plane, pk, dk, len, &u0, &u1)) continue;
      // A neighbouring frame takes a clear miss up where it leaves the frame's frustum (2% before,
      // so that a surface at the frame's edge is not stepped over): on the stretch before, the
      // frame shows nothing on the ray's way, and what the neighbour shows there has moved since
      // (moved_since); a view of the same moment traces it whole. p and pk are the same point, dir
      // and dk the same unit direction: distances along the ray are the same in both.
      float f0, f1;
      if (cam.other_time && !hit && (state & SSRCL_RAY_CLEAR) &&
          clip_to_frustum(vload16(0, params.frame.proj), params.frame.near_plane, params.frame.far_plane, p, dir,
                          len, &f0, &f1)) {
        u0 = fmax(u0, 0.98f * f1);
        if (!(u0 < u1)) continue;
      }

      const int k = count++;
      const ViewRay made = {record, i, h, ray_radiance[record], state, p, main_distance};
      lane[k] = made;
      // Where the view shows the ray's origin, the ray is seen from its start: passing behind
      // anything on its way puts its hit in doubt (a contact point the view does not see either).
      // Where the origin is hidden (a surface seen from behind) or outside, only after it comes
      // into view.
      const float4 ho = mat_mul(proj, (float4)(pk, 1.0f));
      if (ho.w > 0.0f && fabs(ho.x) < ho.w && fabs(ho.y) < ho.w) {
        const int2 o = clamp(convert_int2(ndc_to_pixel(ho.xy / ho.w, size)), (int2)(0, 0), size - 1);
        const float shown = positions[o.y * size.x + o.x].w;
        scene[k].seen = fabs(shown + pk.z) <= 0.02f * -pk.z;
      }
      round.dir[k] = dk;
      round.live[k] = segment_ray(proj, size, pk + dk * u0, pk + dk * u1, &round.ray[k]);
    }
    trace_round(scene, params.linear_step, &round);

    for (int k = 0; k < count; ++k) {
      const float t = round.t[k];
      if (t < 0.0f) continue;
      const ViewRay r = lane[k];
      const ScreenRay ray = round.ray[k];
      const int2 cell = clamp(round.cell[k], (int2)(0, 0), size - 1);
      const float3 hit_k = ray_point(&ray, t);
      const float3 hit_main = mat_mul(vload16(0, cam.to_main), (float4)(hit_k, 1.0f)).xyz;
      // The texel hit: its surface point, not the ray's (which may pass within its thickness).
      if (cam.other_time) {
        const float3 texel =
            mat_mul(vload16(0, cam.to_main), (float4)(positions[cell.y * size.x + cell.x].xyz, 1.0f)).xyz;
        if (moved_since(vload16(0, params.frame.proj), main_size, main_positions, texel)) continue;
      }
      const bool hit = r.h.w >= 0.0f, behind = (r.state & SSRCL_RAY_BEHIND) != 0,
                 thick = (r.state & SSRCL_RAY_THICK) != 0;
      const float distance = length(hit_main - r.p);
      const float confidence = edge_confidence(ray_screen(&ray, t), size, params.edge_fade);
      // Taken when the view sees more of the hit than the frame did; or, where the frame's hit is in
      // doubt, when the view sees the ray's whole way to its hit (it did not pass behind anything: a
      // contact point hidden from the view too stays the frame's), nearer than a frame hit found
      // behind a surface, or anywhere for one found only within a thickness.
      const bool clear = !scene[k].behind && confidence > 0.0f;
      const bool nearer = behind && clear && distance < 0.98f * r.main_distance;
      const bool crossing = thick && clear;
      if (!(confidence > fmax(r.h.w, 0.0f) || nearer || crossing)) continue;

      // The frame's own hit, confirmed: it keeps the frame's colour (its own render, at its own
      // resolution) and the confidence the view adds.
      if (hit && fabs(distance - r.main_distance) <= 0.02f * r.main_distance) {
        ray_hit[r.record] = (float4)(r.h.xyz, fmax(r.h.w, confidence));
        ray_state[r.record] = (uchar)(r.state & ~(SSRCL_RAY_BEHIND | SSRCL_RAY_THICK));
        continue;
      }
      const float nr_w = main_normals[r.pixel].w;
      const float alpha = nr_w <= params.frame.mirror_roughness
                              ? 0.0f
                              : fmax(roughness_to_alpha(nr_w, SSRCL_ROUGHNESS_MAPPING), 1e-4f);
      float3 color = sanitize_radiance3(
          hit_color(&scene[k], color_pyramid, proj, &ray, t, cell, distance, alpha, params.cone_scale).xyz);
      const float mean = (color.x + color.y + color.z) / 3.0f;
      if (mean > params.radiance_limit) color *= params.radiance_limit / mean;
      ray_hit[r.record] = (float4)(hit_main, confidence);
      ray_radiance[r.record] = (float4)(color, r.rad.w);
      ray_state[r.record] = (uchar)((1 + params.view) << SSRCL_RAY_SOURCE_SHIFT);
    }
  }
}
