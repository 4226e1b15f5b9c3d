// HZB: one reduction step of the min-depth pyramid. The coarse level is ceil(size / 2), so coarse
// cell (x, y) covers fine cells 2x..2x+1, 2y..2y+1 (clamped at the edge): every fine texel lies
// under exactly one coarse texel, and a level-L cell is exactly the 2^L x 2^L pixel block the
// tracer assumes.
__kernel void hzb_reduce(__global float* hzb, __global const HzbLevel* levels, int dst_level) {
  int x = get_global_id(0), y = get_global_id(1);
  ReduceCell c;
  if (!reduce_cell(levels, dst_level, x, y, &c)) return;
  float4 t = cell_texels(hzb, &c);
  hzb[c.dst.offset + y * c.dst.width + x] = fmin(fmin(t.x, t.y), fmin(t.z, t.w));
}
