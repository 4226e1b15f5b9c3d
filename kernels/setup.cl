// Setup: turn the renderer's passes into what tracing needs, and list the pixels worth a ray.
// Writes each pixel's view-space surface point with its planar depth in w (SSRCL_NO_SURFACE for
// sky/invalid), its surface plane for the trace (surface_plane.cl), HZB level 0, view-space
// normals with roughness in w, sanitized color (colour pyramid level 0), each pixel's ray count
// (0 for sky and pixels above max_roughness, 1 for mirror-like ones), and lists the work: traced
// pixels in ray_list, and in tile_list the 8x8 tiles (this kernel's work-groups) holding a pixel
// that reflects. With `classify` 0 every pixel and tile is listed instead (the unclassified
// baseline: the others' work-items exit at once).
//
// A pixel's surface is the plane through its point with its normal. HZB level 0 is the nearest
// depth of that plane over the pixel's square (its centre depth for invalid normals), so the
// pyramid bounds the surface everywhere in the pixel, not only at its centre: a grazing floor
// is 10% nearer at a pixel's near edge than at its centre.

// Depth at and beyond which a pixel is background whatever the far plane (Cycles writes 1e10).
#define SSRCL_BACKGROUND_DEPTH 1e10f

// Glossy pixels' ray count: samples_per_pixel, or with full_rays_roughness > 0 a share of it in
// proportion to roughness up to that roughness (at least one ray): narrow lobes see a small part of
// the scene, and their neighbours' reused rays cover it.
inline int glossy_rays(float roughness, int samples_per_pixel, float full_rays_roughness) {
  if (!(full_rays_roughness > 0.0f) || roughness >= full_rays_roughness) return samples_per_pixel;
  return clamp((int)ceil((float)samples_per_pixel * roughness / full_rays_roughness), 1, samples_per_pixel);
}

// The viewing lines of view_line (common.cl) as an affine map of pixel coordinates, built once per
// work-item: view_line's homogeneous point inv_proj * (ndc, 0, 1) is affine in the pixel, so a line
// costs a few multiply-adds instead of a matrix product and six divisions (five lines per pixel,
// centre and corners, were most of setup's time). eye is the centre of projection scaled to w = 1
// (lines' directions only change scale, which steps and depths divide out), w = 0 for orthographic
// cameras.
typedef struct {
  float4 at_origin, per_x, per_y, eye;
} PixelLines;

inline PixelLines pixel_lines(float16 inv_proj, int2 size) {
  float4 col_x = inv_proj.s048c, col_y = inv_proj.s159d, col_w = inv_proj.s37bf;
  float4 per_x = col_x * (2.0f / (float)size.x), per_y = col_y * (-2.0f / (float)size.y);
  float4 eye = inv_proj.s26ae;
  return (PixelLines){col_w - col_x + col_y, per_x, per_y, eye.w != 0.0f ? eye / eye.w : eye};
}

// The line through screen point `pixel`: its origin (the eye for perspective cameras) and an
// unnormalised direction v; the step view_line returns is v / -v.z.
inline float3 pixel_line(const PixelLines* lines, float2 pixel, float3* v) {
  float4 a = lines->at_origin + pixel.x * lines->per_x + pixel.y * lines->per_y;
  float4 e = lines->eye;
  *v = a.xyz * e.w - e.xyz * a.w;
  return e.w != 0.0f ? e.xyz : a.xyz / a.w;
}

// Planar depth where the line through screen point `pixel` meets the plane through p with normal n,
// or a negative value where it runs parallel to it or meets it behind the eye.
inline float plane_depth_at(const PixelLines* lines, float2 pixel, float3 p, float3 n) {
  float3 v;
  float3 origin = pixel_line(lines, pixel, &v);
  float denom = dot(v, n);  // dot(step, n) * -v.z
  if (fabs(denom) < 1e-20f * fabs(v.z)) return -1.0f;
  float depth = dot(p - origin, n) * -v.z / denom - origin.z;
  return depth > 0.0f && isfinite(depth) ? depth : -1.0f;
}

// Normals need not be unit length: they are scaled to their largest component first, so that
// neither huge (length overflows) nor denormal ones (length underflows) are lost. 0 for zero or
// non-finite normals.
inline float normal_scale(float3 n) {
  float scale = fmax(fabs(n.x), fmax(fabs(n.y), fabs(n.z)));
  return isfinite(scale) && scale > 0.0f ? scale : 0.0f;
}

// The view-space unit normal of a normal as written. Zero or non-finite normals leave the pixel
// without a reflection (*ok false: it still occludes, facing the camera).
inline float3 view_normal(float16 normal_matrix, float3 nw, bool* ok) {
  float scale = normal_scale(nw);
  bool normal_ok = scale > 0.0f;
  float3 nv = mat3_mul(normal_matrix, normal_ok ? nw / scale : (float3)(0.0f));
  float len = length(nv);
  *ok = normal_ok && isfinite(len) && len > 1e-20f;
  return *ok ? nv / len : (float3)(0.0f, 0.0f, 1.0f);
}

// Length of a normal as written (0 for unusable ones).
inline float written_length(float3 n) {
  float scale = normal_scale(n);
  return scale > 0.0f ? scale * length(n / scale) : 0.0f;
}

inline float pixel_roughness(float constant_roughness, __global const float* roughness_in, int i) {
  float r = constant_roughness >= 0.0f ? constant_roughness : roughness_in[i];
  return isnan(r) ? 1.0f : clamp(r, 0.0f, 1.0f);
}

// Cycles' background depth (1e10) means no surface even under an infinite far plane.
inline bool surface_depth(float d, float near_plane, float far_plane) {
  return isfinite(d) && d >= near_plane && d <= far_plane && d < SSRCL_BACKGROUND_DEPTH;
}

// Edge colours. Depth comes from one sample of a pixel, colour from all of them: a pixel beside a
// nearer object's edge has the depth of the surface behind and the colour of both. A ray that hits
// it reached that surface behind the object, so the colour it reads is held within the light of the
// pixels wholly on that surface (per channel, their minimum to maximum). Beside a street lamp of 20
// the wall's edge pixels held 1-7 against its 0.46, and rays passing behind the lamp to the wall
// took that (puddles, docs/BENCHMARKS.md "Edge colours"). The nearer object's own edge pixels keep
// their mix: a ray reaching one may as well have passed just beside it.

inline bool in_frame(int2 p, int2 size) { return all(p >= 0) && all(p < size); }

// The depth of pixel (x, y), or SSRCL_NO_SURFACE where it shows none or lies outside the frame.
inline float depth_or_none(__global const float* depth_in, int2 size, int x, int y, float near_plane,
                           float far_plane) {
  if (!in_frame((int2)(x, y), size)) return SSRCL_NO_SURFACE;
  float d = depth_in[y * size.x + x];
  return surface_depth(d, near_plane, far_plane) ? d : SSRCL_NO_SURFACE;
}

// Whether pixel p + o shows the surface of pixel p (depth d), as thickness.cl joins runs: its depth
// within 2% of d, or on the line through p - o and p, or d on the line through p + 2o and p + o (a
// surface's own slope, seen from its outline). Past the frame's border the same surface goes on;
// where neither line has a surface in the frame to go through, nothing tells them apart either.
inline bool joins(__global const float* depth_in, int2 size, int2 p, int2 o, float d, float near_plane,
                  float far_plane) {
  if (!in_frame(p + o, size)) return true;
  const float c = depth_or_none(depth_in, size, p.x + o.x, p.y + o.y, near_plane, far_plane);
  if (!(c < SSRCL_NO_SURFACE)) return false;
  if (fabs(c - d) <= 0.02f * fmin(c, d)) return true;
  const float a = depth_or_none(depth_in, size, p.x - o.x, p.y - o.y, near_plane, far_plane);
  const float e = depth_or_none(depth_in, size, p.x + 2 * o.x, p.y + 2 * o.y, near_plane, far_plane);
  if (a < SSRCL_NO_SURFACE && predicts(a, d, c)) return true;
  if (e < SSRCL_NO_SURFACE && predicts(e, c, d)) return true;
  return !(a < SSRCL_NO_SURFACE) && !(e < SSRCL_NO_SURFACE);
}

// Whether a surface nearer than pixel p's (depth d) lies among its eight neighbours.
inline bool nearer_beside(__global const float* depth_in, int2 size, int2 p, float d, float near_plane,
                          float far_plane) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if ((dx != 0 || dy != 0) &&
          depth_or_none(depth_in, size, p.x + dx, p.y + dy, near_plane, far_plane) < d &&
          !joins(depth_in, size, p, (int2)(dx, dy), d, near_plane, far_plane))
        return true;
  return false;
}

// Whether every neighbour of pixel p shows its surface.
inline bool inside_surface(__global const float* depth_in, int2 size, int2 p, float near_plane, float far_plane) {
  const float d = depth_or_none(depth_in, size, p.x, p.y, near_plane, far_plane);
  if (!(d < SSRCL_NO_SURFACE)) return false;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if ((dx != 0 || dy != 0) && !joins(depth_in, size, p, (int2)(dx, dy), d, near_plane, far_plane)) return false;
  return true;
}

// The colour a hit on edge pixel p of depth d reads: its own, held within the range of the nearest
// pixels on its surface (its 3x3 neighbourhood, else the ring of 5x5 around it) that have no other
// surface around them; its own where there are none.
inline float3 edge_colour(__global const float* color_in, int color_channels, __global const float* depth_in,
                          int2 size, int2 p, float d, float3 own, float near_plane, float far_plane) {
  float3 lo = (float3)(INFINITY), hi = (float3)(-INFINITY);
  for (int ring = 1; ring <= 2 && !(lo.x <= hi.x); ++ring)
    for (int dy = -ring; dy <= ring; ++dy)
      for (int dx = -ring; dx <= ring; dx += (dy == -ring || dy == ring) ? 1 : 2 * ring) {
        const int2 q = p + (int2)(dx, dy);
        if (!in_frame(q, size) || !joins(depth_in, size, p, (int2)(dx, dy), d, near_plane, far_plane) ||
            !inside_surface(depth_in, size, q, near_plane, far_plane))
          continue;
        const float3 v = sanitize_radiance3(vload3(0, color_in + (size_t)(q.y * size.x + q.x) * color_channels));
        lo = fmin(lo, v);
        hi = fmax(hi, v);
      }
  return lo.x <= hi.x ? clamp(own, lo, hi) : own;
}

// Mixed (edge) pixels. Cycles writes the Normal and Roughness passes as the mean over a pixel's
// samples but Depth from its first sample alone (intern/cycles/kernel/film/data_passes.h), so a
// pixel holding two surfaces has the depth of one and the mean of their normals: shorter than 1,
// facing neither. Where its rays leave the screen, the fill read the environment along the mirror
// direction off that mean, which no surface in the pixel has (where a cup's foot meets a steel
// plate, 38 degrees from the plate's: a softbox 18 times the frame's peak where Cycles sees 0.11).
// So its fill takes the normal and roughness of the surface its depth is on: of the neighbours
// with a full-length normal whose plane passes through the pixel's point, the one nearest the mean
// in direction (the largest share of it). A pixel no neighbour explains keeps the mean. The trace
// keeps the mean (docs/BENCHMARKS.md "Mixed pixels": what the neighbour's normal does there).
#define SSRCL_FULL_NORMAL 0.9f  // written normals this long (up to its inverse) are one surface's

// The index of the neighbour whose surface mixed pixel (x, y) is on, or -1.
inline int mixed_pixel_source(const PixelLines* lines, int2 size, int x, int y, float3 nw, float3 p,
                              float16 normal_matrix, float near_plane, float far_plane,
                              __global const float* depth_in, __global const float* normal_in) {
  float len = written_length(nw);
  if (!(len > 0.0f && len < SSRCL_FULL_NORMAL)) return -1;
  float3 mean = nw / len;
  int best = -1;
  float best_share = -INFINITY;
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      int qx = x + dx, qy = y + dy;
      if ((dx == 0 && dy == 0) || qx < 0 || qy < 0 || qx >= size.x || qy >= size.y) continue;
      int j = qy * size.x + qx;
      float dj = depth_in[j];
      float3 nj = vload3(j, normal_in);
      float lj = written_length(nj);
      if (!surface_depth(dj, near_plane, far_plane) || !(lj >= SSRCL_FULL_NORMAL && lj <= 1.0f / SSRCL_FULL_NORMAL))
        continue;
      nj /= lj;
      float3 v;
      float3 origin = pixel_line(lines, (float2)((float)qx + 0.5f, (float)qy + 0.5f), &v);
      float3 pj = origin + (dj + origin.z) * (v * (-1.0f / v.z));
      if (!on_plane(p, pj, mat3_mul(normal_matrix, nj), -p.z)) continue;
      float share = dot(mean, nj);
      if (share > best_share) {
        best = j;
        best_share = share;
      }
    }
  return best;
}

// Runs in SSRCL_TILE^2 work-groups; listed pixels are counted in local memory first so the global
// counters (ray_count[SSRCL_COUNT_*]) see one atomic per group instead of one per pixel.
__kernel void setup(SetupParams params, __global const float* color_in,
                    __global const float* depth_in,
                    __global const float* normal_in,
                    __global const float* roughness_in,
                    __global float4* position_out, __global float* hzb_out, __global float4* normal_out,
                    __global float4* color_out,
                    __global int* pixel_rays, __global int* ray_list, __global int* tile_list,
                    __global int* ray_count, __global float4* plane_out,
                    __global float4* fill_normal_out) {
  __local int group_count, group_base, group_rays, group_traced, group_reflecting;
  const int2 size = (int2)(params.frame.width, params.frame.height);
  const float16 normal_matrix = vload16(0, params.frame.normal_matrix), inv_proj = vload16(0, params.frame.inv_proj);
  const PixelLines lines = pixel_lines(inv_proj, size);
  const float near_plane = params.frame.near_plane, far_plane = params.frame.far_plane;
  const int color_channels = params.color_channels, classify = params.classify;
  const float constant_roughness = params.constant_roughness;
  int x = get_global_id(0), y = get_global_id(1);
  bool inside = x < size.x && y < size.y;
  int i = y * size.x + x;
  bool traced = false, listed = false, reflecting = false;
  if (inside) {
    float d = depth_in[i];
    bool surface = surface_depth(d, near_plane, far_plane);
    float3 v;
    float3 origin = pixel_line(&lines, (float2)((float)x + 0.5f, (float)y + 0.5f), &v);
    float3 step = v * (-1.0f / v.z);
    float3 view_dir = normalize(step);
    float3 p = origin + (d + origin.z) * step;
    surface = surface && all(isfinite(p));

    float3 nw = vload3(i, normal_in);
    bool normal_ok;
    float3 nv = view_normal(normal_matrix, nw, &normal_ok);
    float r = pixel_roughness(constant_roughness, roughness_in, i);
    if (params.fill_normals) {
      int source = surface ? mixed_pixel_source(&lines, size, x, y, nw, p, normal_matrix, near_plane, far_plane,
                                                depth_in, normal_in)
                           : -1;
      bool source_ok;
      fill_normal_out[i] = source >= 0 ? (float4)(view_normal(normal_matrix, vload3(source, normal_in), &source_ok),
                                                  pixel_roughness(constant_roughness, roughness_in, source))
                                       : (float4)(nv, r);
    }

    // Colour (not premultiplied) with, in w, the weight prefiltered lookups give the pixel
    // (kernels/hit_prefilter.cl adds each batch's hits to the 1): 0 on sky, which rays never hit,
    // and on specular pixels, whose screen colour is what they reflect toward the camera and whose
    // plane the rays leaving a reflector cannot hit: averaged in, an emitter's light spread onto
    // them and no ray collected it (tabletop_cm, docs/BENCHMARKS.md "Speckle").
    float3 colour = sanitize_radiance3(vload3(0, color_in + (size_t)i * color_channels));
    if (surface && params.edge_colors && nearer_beside(depth_in, size, (int2)(x, y), d, near_plane, far_plane))
      colour = edge_colour(color_in, color_channels, depth_in, size, (int2)(x, y), d, colour, near_plane, far_plane);
    color_out[i] = surface ? (float4)(colour, specular_pixel(r) ? 0.0f : 1.0f) : (float4)(0.0f);

    float nearest = d;
    if (surface && normal_ok) {
      for (int corner = 0; corner < 4; ++corner) {
        float2 at = (float2)((float)(x + (corner & 1)), (float)(y + (corner >> 1)));
        float cd = plane_depth_at(&lines, at, p, nv);
        // Near-edge-on planes can reach any depth within the pixel; half the centre depth bounds
        // what a real surface does there.
        if (cd > 0.0f) nearest = fmin(nearest, fmax(cd, 0.5f * d));
      }
    }
    position_out[i] = surface ? (float4)(p, d) : (float4)(0.0f, 0.0f, 0.0f, SSRCL_NO_SURFACE);
    hzb_out[i] = surface ? nearest : SSRCL_NO_SURFACE;
    normal_out[i] = (float4)(nv, r);
    // Thickness is a depth along the viewing line; hits measure it along the normal, which is the
    // depth times |n.v| (near a silhouette a surface is thin along its normal however deep it is).
    // The adaptive model's depth, relative to d, follows in kernels/thickness.cl (1 until then).
    float thickness_rel = params.adaptive_thickness ? 1.0f : params.thickness_rel;
    plane_out[i] = surface ? surface_plane(p, nv, thickness_rel * d * fabs(dot(view_dir, nv))) : SSRCL_NO_PLANE;
    // Ray counts: 0 no reflection (sky, too rough), 1 mirror-like, -1 glossy but resolved from
    // its neighbours' rays only (strided tracing), else samples_per_pixel.
    // A normal facing away from the viewer (seen from behind) defines no reflection.
    bool reflects = surface && normal_ok && r <= params.max_roughness && dot(view_dir, nv) < 0.0f;
    bool strided_out = (x % params.trace_stride) != 0 || (y % params.trace_stride) != 0;
    int rays = !reflects                ? 0
               : r <= params.frame.mirror_roughness    ? 1
               : strided_out              ? -1
                                          : glossy_rays(r, params.samples_per_pixel, params.full_rays_roughness);
    pixel_rays[i] = rays;
    traced = rays > 0;
    reflecting = rays != 0;
    listed = traced || !classify;
  }

  bool leader = get_local_id(0) == 0 && get_local_id(1) == 0;
  if (leader) {
    group_count = 0;
    group_rays = 0;
    group_traced = 0;
    group_reflecting = 0;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  int slot = listed ? atomic_inc(&group_count) : 0;
  if (traced) {
    atomic_add(&group_rays, pixel_rays[i]);
    atomic_inc(&group_traced);
  }
  if (reflecting) atomic_inc(&group_reflecting);
  barrier(CLK_LOCAL_MEM_FENCE);
  if (leader) {
    group_base = atomic_add(&ray_count[SSRCL_COUNT_LISTED], group_count);
    atomic_add(&ray_count[SSRCL_COUNT_RAYS], group_rays);
    atomic_add(&ray_count[SSRCL_COUNT_TRACED], group_traced);
    if (group_reflecting > 0 || !classify)
      tile_list[atomic_inc(&ray_count[SSRCL_COUNT_TILES])] = get_group_id(1) * get_num_groups(0) + get_group_id(0);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (listed) ray_list[group_base + slot] = i;
}
