// HZB: one reduction step of the min-depth pyramid. The coarse level is ceil(size / 2), so coarse
// cell (x, y) covers fine cells 2x..2x+1, 2y..2y+1 (clamped at the edge): every fine texel lies
// under exactly one coarse texel, and a level-L cell is exactly the 2^L x 2^L pixel block the
// tracer assumes.
__kernel void hzb_reduce(__global float* hzb, __global const HzbLevel* levels, int dst_level) {
  int x = get_global_id(0), y = get_global_id(1);
  HzbLevel dst = levels[dst_level];
  if (x >= dst.width || y >= dst.height) return;
  HzbLevel src = levels[dst_level - 1];
  int x0 = 2 * x, y0 = 2 * y;
  int x1 = min(x0 + 1, src.width - 1), y1 = min(y0 + 1, src.height - 1);
  __global const float* s = hzb + src.offset;
  float m = fmin(fmin(s[y0 * src.width + x0], s[y0 * src.width + x1]),
                 fmin(s[y1 * src.width + x0], s[y1 * src.width + x1]));
  hzb[dst.offset + y * dst.width + x] = m;
}
