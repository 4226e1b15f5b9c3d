// The colour pyramid's texels (kernels/color_pyramid.cl builds it; setup.cl writes level 0) and
// lookups into it: bilinear within a level, trilinear across levels, for prefiltered hits of
// rough rays.

// A pixel with a specular lobe: renderers write roughness 1 (or none, read as 1) where a surface
// has none, so anything under 0.9 reflects.
inline bool specular_pixel(float roughness) { return roughness < 0.9f; }

inline float4 weighted_texel(float4 t, int level) { return level == 0 ? (float4)(t.xyz * t.w, t.w) : t; }

inline float4 pyramid_bilinear(__global const float4* pyramid, __global const HzbLevel* levels, int level,
                               float2 pixel) {
  HzbLevel l = levels[level];
  float2 uv = pixel / (float)(1 << level) - 0.5f;
  float2 f = uv - floor(uv);
  int2 a = convert_int2(floor(uv));
  int2 hi = (int2)(l.width - 1, l.height - 1);
  int2 p00 = clamp(a, (int2)(0), hi), p11 = clamp(a + 1, (int2)(0), hi);
  __global const float4* t = pyramid + l.offset;
  float4 t00 = weighted_texel(t[p00.y * l.width + p00.x], level);
  float4 t01 = weighted_texel(t[p00.y * l.width + p11.x], level);
  float4 t10 = weighted_texel(t[p11.y * l.width + p00.x], level);
  float4 t11 = weighted_texel(t[p11.y * l.width + p11.x], level);
  return mix(mix(t00, t01, f.x), mix(t10, t11, f.x), f.y);
}

// Trilinear lookup at a fractional level of detail, weights divided out: the mean colour of the
// surfaces in the footprint, each texel weighted by 1 + the hits that landed on it
// (hit_prefilter.cl). (Counting the sky's share as missed would be biased: rays that miss near a
// surface get no lookup to add theirs back.)
inline float4 pyramid_sample(__global const float4* pyramid, __global const HzbLevel* levels, int level_count,
                             float2 pixel, float lod) {
  lod = clamp(lod, 0.0f, (float)(level_count - 1));
  int l0 = (int)lod;
  int l1 = min(l0 + 1, level_count - 1);
  float4 c = mix(pyramid_bilinear(pyramid, levels, l0, pixel), pyramid_bilinear(pyramid, levels, l1, pixel),
                 lod - (float)l0);
  return c.w > 0.0f ? c / c.w : (float4)(0.0f);
}
