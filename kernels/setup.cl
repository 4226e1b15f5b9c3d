// Setup: turn the renderer's passes into what tracing needs, and list the pixels worth a ray.
// Writes each pixel's view-space surface point with its planar depth in w (SSRCL_NO_SURFACE for
// sky/invalid), HZB level 0, view-space normals with roughness in w, sanitized color (colour
// pyramid level 0), each pixel's ray count (0 for sky and pixels above max_roughness, 1 for
// mirror-like ones), and appends traced pixels to ray_list.
//
// A pixel's surface is the plane through its point with its normal. HZB level 0 is the nearest
// depth of that plane over the pixel's square (its centre depth for invalid normals), so the
// pyramid bounds the surface everywhere in the pixel, not only at its centre: a grazing floor
// is 10% nearer at a pixel's near edge than at its centre.

// Radiance rule: NaN becomes 0, negatives 0, and values clamp at 1e20 so that weighted sums
// in later stages cannot overflow float.
#define SSRCL_MAX_RADIANCE 1e20f

// Depth at and beyond which a pixel is background whatever the far plane (Cycles writes 1e10).
#define SSRCL_BACKGROUND_DEPTH 1e10f

inline float sanitize_radiance(float v) {
  return isnan(v) ? 0.0f : clamp(v, 0.0f, SSRCL_MAX_RADIANCE);
}

// Runs in 2D work-groups; traced pixels are counted in local memory first so the global counters
// (ray_count[0] listed pixels, ray_count[1] rays) see one atomic per group instead of one per pixel.
__kernel void setup(int2 size, float near_plane, float far_plane, float16 normal_matrix, float16 inv_proj,
                    __global const float* color_in, int color_channels,
                    __global const float* depth_in,
                    __global const float* normal_in,
                    __global const float* roughness_in, float constant_roughness,
                    float max_roughness, float mirror_roughness, int samples_per_pixel, int trace_stride,
                    __global float4* position_out, __global float* hzb_out, __global float4* normal_out,
                    __global float4* color_out,
                    __global int* pixel_rays, __global int* ray_list, __global int* ray_count) {
  __local int group_count, group_base, group_rays;
  int x = get_global_id(0), y = get_global_id(1);
  bool inside = x < size.x && y < size.y;
  int i = y * size.x + x;
  bool traced = false;
  if (inside) {
    float d = depth_in[i];
    // Cycles' background depth (1e10) means no surface even under an infinite far plane.
    bool surface = isfinite(d) && d >= near_plane && d <= far_plane && d < SSRCL_BACKGROUND_DEPTH;
    float3 view_dir;
    float3 p = pixel_view_point(inv_proj, size, (int2)(x, y), d, &view_dir);
    surface = surface && all(isfinite(p));

    // Colour carries surface coverage in w (premultiplied), so prefiltered lookups average
    // surfaces only: rays never hit the sky, and its colour must not bleed into hits.
    __global const float* c = color_in + (size_t)i * color_channels;
    color_out[i] = surface ? (float4)(sanitize_radiance(c[0]), sanitize_radiance(c[1]), sanitize_radiance(c[2]), 1.0f)
                           : (float4)(0.0f);

    // Normals need not be unit length: scaled to their largest component first, so that neither
    // huge (length overflows) nor denormal ones (length underflows) are lost. Zero or non-finite
    // normals leave the pixel without a reflection (it still occludes, facing the camera).
    float3 nw = vload3(i, normal_in);
    float scale = fmax(fabs(nw.x), fmax(fabs(nw.y), fabs(nw.z)));
    bool normal_ok = isfinite(scale) && scale > 0.0f;
    float3 nv = mat3_mul(normal_matrix, normal_ok ? nw / scale : (float3)(0.0f));
    float len = length(nv);
    normal_ok = normal_ok && isfinite(len) && len > 1e-20f;
    nv = normal_ok ? nv / len : (float3)(0.0f, 0.0f, 1.0f);

    float r = constant_roughness >= 0.0f ? constant_roughness : roughness_in[i];
    r = isnan(r) ? 1.0f : clamp(r, 0.0f, 1.0f);

    float nearest = d;
    if (surface && normal_ok) {
      for (int corner = 0; corner < 4; ++corner) {
        float2 at = (float2)((float)(x + (corner & 1)), (float)(y + (corner >> 1)));
        float cd = plane_depth_at(inv_proj, size, at, p, nv);
        // Near-edge-on planes can reach any depth within the pixel; half the centre depth bounds
        // what a real surface does there.
        if (cd > 0.0f) nearest = fmin(nearest, fmax(cd, 0.5f * d));
      }
    }
    position_out[i] = surface ? (float4)(p, d) : (float4)(0.0f, 0.0f, 0.0f, SSRCL_NO_SURFACE);
    hzb_out[i] = surface ? nearest : SSRCL_NO_SURFACE;
    normal_out[i] = (float4)(nv, r);
    // Ray counts: 0 no reflection (sky, too rough), 1 mirror-like, -1 glossy but resolved from
    // its neighbours' rays only (strided tracing), else samples_per_pixel.
    // A normal facing away from the viewer (seen from behind) defines no reflection.
    bool reflects = surface && normal_ok && r <= max_roughness && dot(view_dir, nv) < 0.0f;
    bool strided_out = (x % trace_stride) != 0 || (y % trace_stride) != 0;
    pixel_rays[i] = !reflects ? 0 : r <= mirror_roughness ? 1 : strided_out ? -1 : samples_per_pixel;
    traced = pixel_rays[i] > 0;
  }

  bool leader = get_local_id(0) == 0 && get_local_id(1) == 0;
  if (leader) {
    group_count = 0;
    group_rays = 0;
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  int slot = traced ? atomic_inc(&group_count) : 0;
  if (traced) atomic_add(&group_rays, pixel_rays[i]);
  barrier(CLK_LOCAL_MEM_FENCE);
  if (leader) {
    group_base = atomic_add(&ray_count[0], group_count);
    atomic_add(&ray_count[1], group_rays);
  }
  barrier(CLK_LOCAL_MEM_FENCE);
  if (traced) ray_list[group_base + slot] = i;
}
