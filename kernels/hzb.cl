// One reduction step of a depth pyramid: the nearest of the four texels below (the HZB), or with
// `farthest` the farthest (the back pyramid, kernels/back_pyramid.cl). The coarse level is
// ceil(size / 2), so coarse cell (x, y) covers fine cells 2x..2x+1, 2y..2y+1 (clamped at the edge):
// every fine texel lies under exactly one coarse texel, and a level-L cell is exactly the 2^L x 2^L
// pixel block the tracer assumes.
__kernel void depth_reduce(__global float* pyramid, __global const HzbLevel* levels, int dst_level, int farthest) {
  int x = get_global_id(0), y = get_global_id(1);
  ReduceCell c;
  if (!reduce_cell(levels, dst_level, x, y, &c)) return;
  float4 t = cell_texels(pyramid, &c);
  pyramid[c.dst.offset + y * c.dst.width + x] =
      farthest ? fmax(fmax(t.x, t.y), fmax(t.z, t.w)) : fmin(fmin(t.x, t.y), fmin(t.z, t.w));
}
