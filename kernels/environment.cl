// Environment fill: the part of each pixel's lobe the screen did not hold (1 - A, the edge fade
// included) takes the environment's radiance filtered for that lobe (include/ssrcl/environment.hpp:
// the mapping, and the prefiltered levels, one per roughness step). RGB becomes the complete
// reflection; A keeps the screen-space fraction.

// Where direction d (world, +Z up, Blender's mapping) falls in the map, as (u, v) in [0, 1].
inline float2 environment_uv(float3 d) {
  return (float2)(0.5f - atan2(d.y, d.x) * (0.5f * M_1_PI_F), 0.5f - atan2(d.z, hypot(d.x, d.y)) * M_1_PI_F);
}

// Bilinear read of one packed RGB level at (u, v): wraps around in azimuth, clamps at the poles.
inline float3 environment_bilinear(__global const float* texels, HzbLevel l, float2 uv) {
  float x = uv.x * (float)l.width - 0.5f;
  float y = clamp(uv.y * (float)l.height - 0.5f, 0.0f, (float)(l.height - 1));
  float fx = x - floor(x), fy = y - floor(y);
  int x0 = ((int)floor(x) % l.width + l.width) % l.width, x1 = (x0 + 1) % l.width;
  int y0 = min((int)floor(y), l.height - 1), y1 = min(y0 + 1, l.height - 1);
  __global const float* row0 = texels + 3 * ((size_t)l.offset + (size_t)y0 * l.width);
  __global const float* row1 = texels + 3 * ((size_t)l.offset + (size_t)y1 * l.width);
  float3 top = mix(vload3(x0, row0), vload3(x1, row0), fx);
  float3 bottom = mix(vload3(x0, row1), vload3(x1, row1), fx);
  return mix(top, bottom, fy);
}

// Cycles' pixel is a filtered mean over its footprint (Blender's default pixel filter,
// Blackman-Harris 1.5 px wide: a standard deviation of 0.21 px along each axis), and so is its
// Normal pass. Where the normal varies from pixel to pixel (ripples, a bumped floor), the
// environment along the pixel's one normal is a point sample of what the footprint averages: its
// highlights jump from pixel to pixel as the camera moves. The fill averages four lookups at
// (+-SSRCL_FILL_FOOTPRINT, +-SSRCL_FILL_FOOTPRINT) px from the pixel's centre, four points with the
// filter's variance, each along the normal interpolated there from the pixel and its neighbours on
// its own surface (a neighbour off it counts as the pixel's own normal): each on the other's plane
// and turned by at most 45 degrees from it, as the temporal blend takes a surface to be the same
// (TemporalSettings::maxNormalDegrees); where a cup's foot meets a plate, the foot's normals
// interpolated into the plate's pixels lit them from a softbox (product_pepper 23.35 -> 10.98 dB).
#define SSRCL_FILL_FOOTPRINT 0.21f
#define SSRCL_SAME_SURFACE_COS 0.70710678f

// The normals of pixel (x, y)'s 3x3 neighbourhood, row by row, where they lie on its surface (the
// pixel's own normal n elsewhere); true when every one is n itself (a flat surface: one read does).
inline bool surface_normals(__global const float4* positions, __global const float4* normals, int2 size, int x, int y,
                            float4 p, float3 n, float3* around) {
  bool flat = true;
  for (int t = 0; t < 9; ++t) {
    const int2 q = (int2)(x + t % 3 - 1, y + t / 3 - 1);
    float3 nq = n;
    if (q.x >= 0 && q.y >= 0 && q.x < size.x && q.y < size.y) {
      const int j = q.y * size.x + q.x;
      const float4 pj = positions[j], nj = normals[j];
      if (pj.w != SSRCL_NO_SURFACE && dot(nj.xyz, n) >= SSRCL_SAME_SURFACE_COS && on_plane(pj.xyz, p.xyz, n, p.w) &&
          on_plane(p.xyz, pj.xyz, nj.xyz, p.w))
        nq = nj.xyz;
    }
    around[t] = nq;
    flat = flat && all(nq == n);
  }
  return flat;
}

// The normal at offset o (|o| < 1 px per axis) from the pixel's centre: bilinear between the four
// pixel centres around it (around: surface_normals), unit length.
inline float3 footprint_normal(const float3* around, float2 o) {
  const int cx = o.x > 0.0f ? 1 : 0, cy = o.y > 0.0f ? 1 : 0;  // the corner's column and row in around
  const float2 f = select(o + 1.0f, o, isgreater(o, (float2)(0.0f)));  // o from that corner's centre
  const float3 top = mix(around[cy * 3 + cx], around[cy * 3 + cx + 1], f.x);
  const float3 bottom = mix(around[(cy + 1) * 3 + cx], around[(cy + 1) * 3 + cx + 1], f.x);
  return normalize(mix(top, bottom, f.y));
}

// `view_to_world` rotates view-space directions into the environment's frame (the camera's
// inverse view rotation, then the environment rotation about +Z). Pixels with a surface and a
// front-facing normal get the fill, whatever their roughness: a pixel too rough to trace
// (A = 0) reflects the environment only.
__kernel void environment_fill(EnvironmentParams params, __global const float4* positions,
                               __global const float4* normals, __global const float* texels,
                               __global const HzbLevel* levels, __global float4* rgba) {
  const int2 size = (int2)(params.frame.width, params.frame.height);
  const float16 view_to_world = vload16(0, params.view_to_world);
  const int level_count = params.level_count;
  const int roughness_linear = SSRCL_ROUGHNESS_MAPPING == SSRCL_ROUGHNESS_LINEAR;
  const float intensity = params.intensity;
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= size.x || y >= size.y) return;
  int i = y * size.x + x;
  float4 p = positions[i];
  float4 n = normals[i];
  float3 view_dir = normalize(p.xyz);
  if (p.w == SSRCL_NO_SURFACE || !(dot(view_dir, n.xyz) < 0.0f)) return;
  float4 found = rgba[i];
  float missed = clamp(1.0f - found.w, 0.0f, 1.0f);
  if (missed == 0.0f) {  // the screen holds the whole lobe
    rgba[i] = (float4)(sanitize_radiance3(found.xyz), found.w);
    return;
  }
  // Levels are spaced evenly in Blender's roughness, sqrt(alpha). Between two, the mix weight
  // is taken in alpha^2, to which a narrow lobe's angular variance is proportional: the mixture
  // of the two blurs then spreads as far as the lobe in between (a weight linear in roughness
  // blurs up to 27% more at roughness 0.3).
  float alpha = clamp(roughness_linear ? n.w : n.w * n.w, 0.0f, 1.0f);
  float steps = (float)(level_count - 1);
  int k = min((int)(sqrt(alpha) * steps), level_count - 2);
  float a0 = (float)(k * k) / (steps * steps), a1 = (float)((k + 1) * (k + 1)) / (steps * steps);
  float weight = clamp((alpha * alpha - a0 * a0) / (a1 * a1 - a0 * a0), 0.0f, 1.0f);
  float3 around[9];
  const int reads = surface_normals(positions, normals, size, x, y, p, n.xyz, around) ? 1 : 4;
  float3 env = 0.0f;
  for (int s = 0; s < reads; ++s) {
    const float2 o = (float2)((s & 1) ? SSRCL_FILL_FOOTPRINT : -SSRCL_FILL_FOOTPRINT,
                              (s & 2) ? SSRCL_FILL_FOOTPRINT : -SSRCL_FILL_FOOTPRINT);
    const float3 ns = reads == 1 ? n.xyz : footprint_normal(around, o);
    const float2 uv = environment_uv(mat3_mul(view_to_world, view_dir - 2.0f * dot(view_dir, ns) * ns));
    env += mix(environment_bilinear(texels, levels[k], uv), environment_bilinear(texels, levels[k + 1], uv), weight);
  }
  env /= (float)reads;
  float3 filled = sanitize_radiance3(found.xyz + missed * intensity * env);
  rgba[i] = (float4)(filled, found.w);
}
