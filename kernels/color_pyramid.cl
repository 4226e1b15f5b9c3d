// Colour pyramid for prefiltered lookups of rough reflections. Same level geometry as the HZB
// (each level ceil(previous / 2)); a coarse texel is the mean of the fine texels under it.
// Level 0 is the screen colour with a weight in w (setup.cl: 1 on surfaces that rays collect, 0
// on sky and specular pixels), kept unweighted for full-resolution reads; coarser texels are
// (rgb * weight, weight), so lookups divide by w and average the weighted surfaces only.

// A pixel with a specular lobe: renderers write roughness 1 (or none, read as 1) where a surface
// has none, so anything under 0.9 reflects.
inline bool specular_pixel(float roughness) { return roughness < 0.9f; }

inline float4 weighted_texel(float4 t, int level) { return level == 0 ? (float4)(t.xyz * t.w, t.w) : t; }

__kernel void color_reduce(__global float4* pyramid, __global const HzbLevel* levels, int dst_level) {
  int x = get_global_id(0), y = get_global_id(1);
  HzbLevel dst = levels[dst_level];
  if (x >= dst.width || y >= dst.height) return;
  HzbLevel src = levels[dst_level - 1];
  int x0 = 2 * x, y0 = 2 * y;
  int x1 = min(x0 + 1, src.width - 1), y1 = min(y0 + 1, src.height - 1);
  __global const float4* s = pyramid + src.offset;
  // Edge texels may cover one fine column or row only: average what exists, count each once.
  int sl = dst_level - 1;
  float4 sum = weighted_texel(s[y0 * src.width + x0], sl);
  float n = 1.0f;
  if (x1 != x0) { sum += weighted_texel(s[y0 * src.width + x1], sl); n += 1.0f; }
  if (y1 != y0) { sum += weighted_texel(s[y1 * src.width + x0], sl); n += 1.0f; }
  if (x1 != x0 && y1 != y0) { sum += weighted_texel(s[y1 * src.width + x1], sl); n += 1.0f; }
  pyramid[dst.offset + y * dst.width + x] = sum / n;
}

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

// Trilinear lookup at a fractional level of detail, coverage divided out: the mean colour of
// the surfaces in the footprint. (Counting the sky's share as missed would be biased: rays that
// miss near a surface get no lookup to add theirs back.)
inline float4 pyramid_sample(__global const float4* pyramid, __global const HzbLevel* levels, int level_count,
                             float2 pixel, float lod) {
  lod = clamp(lod, 0.0f, (float)(level_count - 1));
  int l0 = (int)lod;
  int l1 = min(l0 + 1, level_count - 1);
  float4 c = mix(pyramid_bilinear(pyramid, levels, l0, pixel), pyramid_bilinear(pyramid, levels, l1, pixel),
                 lod - (float)l0);
  return c.w > 0.0f ? c / c.w : (float4)(0.0f);
}
