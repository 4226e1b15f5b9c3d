// Hierarchical Hi-Z trace of one mirror ray per listed pixel (FidelityFX SSSR style traversal).
//
// The ray is followed in screen space: pixel position s(t) = s0 + t * ds, t in [0, 1].
// Q = P / w and k = 1 / w are affine in screen space for any projective camera (perspective or
// orthographic), so the ray's planar depth -Q.z / k at any t is exact, not interpolated.

typedef struct {
  float2 s0, ds;
  float4 q0, dq;  // xyz = Q, w = k
} ScreenRay;

inline float4 ray_q(const ScreenRay* r, float t) { return r->q0 + t * r->dq; }
inline float ray_depth(const ScreenRay* r, float t) { float4 q = ray_q(r, t); return -q.z / q.w; }
inline float3 ray_point(const ScreenRay* r, float t) { float4 q = ray_q(r, t); return q.xyz / q.w; }

// t where the ray's depth equals d (a Moebius function of t, so one closed-form root).
inline float ray_t_at_depth(const ScreenRay* r, float d) {
  float denom = r->dq.z + d * r->dq.w;
  float t = -(r->q0.z + d * r->q0.w) / denom;
  return (denom != 0.0f && isfinite(t)) ? t : INFINITY;
}

// Parameter where the ray leaves the cell of `cell_size` pixels it occupies just after t. The
// cell is looked up slightly ahead of t so a ray sitting on a boundary counts as having crossed it.
inline float cell_exit(const ScreenRay* r, float t, float nudge, float cell_size, int2* cell_out) {
  float2 p = r->s0 + (t + nudge) * r->ds;
  float2 cell = floor(p / cell_size);
  *cell_out = convert_int2(cell);
  float2 boundary = (cell + select((float2)(0.0f), (float2)(1.0f), isgreater(r->ds, (float2)(0.0f)))) * cell_size;
  float2 tb = (boundary - r->s0) / r->ds;
  tb = select(tb, (float2)(INFINITY), isless(fabs(r->ds), (float2)(1e-12f)));
  return fmin(tb.x, tb.y);
}

// Screen ray for a view-space segment p0 -> p1, clipped to the screen so that t in [0, 1] spans
// its on-screen part; false when either end is behind the camera.
inline bool make_screen_ray(float16 proj, int2 size, float3 p0, float3 p1, ScreenRay* r) {
  float4 h0 = mat_mul(proj, (float4)(p0, 1.0f));
  float4 h1 = mat_mul(proj, (float4)(p1, 1.0f));
  if (!(h0.w > 0.0f && h1.w > 0.0f)) return false;
  float k0 = 1.0f / h0.w, k1 = 1.0f / h1.w;
  r->s0 = ndc_to_pixel(h0.xy * k0, size);
  r->ds = ndc_to_pixel(h1.xy * k1, size) - r->s0;
  r->q0 = (float4)(p0 * k0, k0);
  r->dq = (float4)(p1 * k1, k1) - r->q0;
  // Clip to the screen rectangle.
  float2 edge = select((float2)(0.0f), convert_float2(size), isgreater(r->ds, (float2)(0.0f)));
  float2 te = (edge - r->s0) / r->ds;
  te = select(te, (float2)(INFINITY), isless(fabs(r->ds), (float2)(1e-12f)));
  // The far end of a long segment can project millions of pixels away; rescaling keeps t's
  // float resolution well under a pixel.
  float t_max = fmin(1.0f, fmin(te.x, te.y));
  r->ds *= t_max;
  r->dq *= t_max;
  return isfinite(r->s0.x) && isfinite(r->s0.y) && isfinite(r->ds.x) && isfinite(r->ds.y);
}

// A hit on a surface that faces away from the ray is a surface the ray cannot have reached.
inline bool faces_ray(__global const float4* normals, int2 size, int2 cell, float3 dir) {
  cell = clamp(cell, (int2)(0, 0), size - 1);
  return dot(normals[cell.y * size.x + cell.x].xyz, dir) < 0.0f;
}

// hits[pixel] = (hit x, hit y in pixels, view-space distance, 1) or stays 0 on a miss.
__kernel void trace_mirror(int2 size, float16 proj, float16 inv_proj, float near_plane, float far_plane,
                           __global const float* hzb, __global const HzbLevel* levels, int level_count,
                           __global const float4* normals, __global const int* ray_list, int ray_count,
                           float thickness_rel, int max_iterations, __global float4* hits) {
  int gid = get_global_id(0);
  if (gid >= ray_count) return;
  int i = ray_list[gid];
  int2 pix = (int2)(i % size.x, i / size.x);

  float d0 = hzb[i];
  float3 n = normals[i].xyz;
  float2 ndc = pixel_to_ndc(convert_float2(pix) + 0.5f, size);
  // The pixel's viewing line, valid for perspective and orthographic cameras alike.
  float3 a = unproject(inv_proj, ndc, -1.0f), b = unproject(inv_proj, ndc, 0.0f);
  float3 v = normalize(b - a);
  float3 p = a + (b - a) * ((-d0 - a.z) / (b.z - a.z));
  if (dot(v, n) >= 0.0f) return;  // normal faces away from the viewer: no defined reflection
  float3 dir = v - 2.0f * dot(v, n) * n;

  // Segment end: at the near plane for rays toward the camera, at the far plane otherwise,
  // capped so an infinite far plane still gives a finite end point.
  float length_max = 1e6f * d0;
  float len = dir.z > 0.0f ? (-near_plane * 1.001f - p.z) / dir.z
            : dir.z < 0.0f ? (-far_plane - p.z) / dir.z : length_max;
  len = fmin(len, length_max);
  if (!(len > 0.0f)) return;

  ScreenRay ray;
  if (!make_screen_ray(proj, size, p, p + dir * len, &ray)) return;
  float major = fmax(fabs(ray.ds.x), fabs(ray.ds.y));
  if (!(major > 0.0f)) return;
  float nudge = 0.01f / major;  // a hundredth of a pixel along the major axis
  bool deeper = ray.q0.z * ray.dq.w - ray.dq.z * ray.q0.w > 0.0f;  // depth grows with t

  int2 cell;
  float t = cell_exit(&ray, 0.0f, nudge, 1.0f, &cell);  // leave the origin pixel first
  int mip = 0;
  for (int iter = 0; iter < max_iterations && t <= 1.0f; ++iter) {
    float t_exit = cell_exit(&ray, t, nudge, (float)(1 << mip), &cell);
    float d_min = hzb_fetch(hzb, levels, mip, cell);
    float d_now = ray_depth(&ray, t);
    if (d_now < d_min) {
      // In front of everything in this cell: does the ray reach the cell's nearest depth inside it?
      float t_cross = (deeper && d_min < SSRCL_NO_SURFACE) ? ray_t_at_depth(&ray, d_min) : INFINITY;
      if (t_cross <= t_exit) {
        if (mip > 0) {
          t = fmax(t, t_cross);
          --mip;
          continue;
        }
        if (t_cross <= 1.0f && faces_ray(normals, size, cell, dir)) {
          t = fmax(t, t_cross);
          float2 s = ray.s0 + t * ray.ds;
          hits[i] = (float4)(s, length(ray_point(&ray, t) - p), 1.0f);
          return;
        }
        t = t_exit;
      } else {
        t = t_exit;
        mip = min(mip + 1, level_count - 1);
      }
    } else if (mip > 0) {
      --mip;  // possibly behind something in this cell: look closer
    } else if (d_min < SSRCL_NO_SURFACE && d_now - d_min <= thickness_rel * d_min &&
               faces_ray(normals, size, cell, dir)) {
      float2 s = ray.s0 + t * ray.ds;
      hits[i] = (float4)(s, length(ray_point(&ray, t) - p), 1.0f);
      return;
    } else {
      t = t_exit;  // behind the surface by more than its thickness: the ray passes behind it
    }
  }
}
