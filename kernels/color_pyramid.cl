// Colour pyramid for prefiltered lookups of rough reflections. Same level geometry as the HZB
// (each level ceil(previous / 2)); a coarse texel is the mean of the fine texels under it.
// Level 0 is the screen colour with a weight in w (setup.cl writes 1 on surfaces that rays
// collect, 0 on sky and specular pixels; hit_prefilter.cl adds each batch's hits), kept unweighted
// for full-resolution reads; coarser texels are (rgb * weight, weight), so lookups divide by w
// and average the weighted surfaces only (weighted_texel and the lookups are in color_lookup.cl).

__kernel void color_reduce(__global float4* pyramid, __global const HzbLevel* levels, int dst_level) {
  int x = get_global_id(0), y = get_global_id(1);
  ReduceCell c;
  if (!reduce_cell(levels, dst_level, x, y, &c)) return;
  __global const float4* s = pyramid + c.src.offset;
  int w = c.src.width;
  // Edge texels may cover one fine column or row only: average what exists, count each once.
  int sl = dst_level - 1;
  float4 sum = weighted_texel(s[c.y0 * w + c.x0], sl);
  float n = 1.0f;
  if (c.x1 != c.x0) { sum += weighted_texel(s[c.y0 * w + c.x1], sl); n += 1.0f; }
  if (c.y1 != c.y0) { sum += weighted_texel(s[c.y1 * w + c.x0], sl); n += 1.0f; }
  if (c.x1 != c.x0 && c.y1 != c.y0) { sum += weighted_texel(s[c.y1 * w + c.x1], sl); n += 1.0f; }
  pyramid[c.dst.offset + y * c.dst.width + x] = sum / n;
}
