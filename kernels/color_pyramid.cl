// Colour pyramid for prefiltered lookups of rough reflections. Same level geometry as the HZB
// (each level ceil(previous / 2)); a coarse texel is the mean of the fine texels under it.
// Level 0 is the screen colour with a weight in w (setup.cl writes 1 on surfaces that rays
// collect, 0 on sky and specular pixels; hit_prefilter.cl adds each batch's hits), kept unweighted
// for full-resolution reads; coarser texels are (rgb * weight, weight), so lookups divide by w
// and average the weighted surfaces only (weighted_texel and the lookups are in color_lookup.cl).

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
