// One reduction step of the HZB: the nearest of the four texels below. The coarse level is
// ceil(size / 2), so coarse cell (x, y) covers fine cells 2x..2x+1, 2y..2y+1 (clamped at the edge):
// every fine texel lies under exactly one coarse texel, and a level-L cell is exactly the 2^L x 2^L
// pixel block the tracer assumes.
__kernel void depth_reduce(__global float* pyramid, __global const HzbLevel* levels, int dst_level) {
  int x = get_global_id(0), y = get_global_id(1);
  ReduceCell c;
  if (!reduce_cell(levels, dst_level, x, y, &c)) return;
  int4 i = cell_texel_indices(&c);
  pyramid[c.dst.offset + y * c.dst.width + x] =
      fmin(fmin(pyramid[i.x], pyramid[i.y]), fmin(pyramid[i.z], pyramid[i.w]));
}
