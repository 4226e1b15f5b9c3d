// Deterministic sample sequences: a per-pixel Cranley-Patterson rotation (hashed from pixel and
// seed) of the R2 low-discrepancy sequence (Roberts 2018). Sample k of a pixel is well spread
// among that pixel's samples, and neighbouring pixels are decorrelated.

inline uint hash_u32(uint x) {
  // Integer finalizer with full avalanche (the "lowbias32" constants).
  x ^= x >> 16;
  x *= 0x7feb352dU;
  x ^= x >> 15;
  x *= 0x846ca68bU;
  x ^= x >> 16;
  return x;
}

inline float u32_to_unit(uint x) { return (float)(x >> 8) * (1.0f / 16777216.0f); }

inline float2 sample_2d(int pixel, int k, uint seed) {
  uint h = hash_u32((uint)pixel ^ hash_u32(seed + 0x9e3779b9U));
  float2 shift = SSRCL_FLOAT2(u32_to_unit(h), u32_to_unit(hash_u32(h)));
  // R2 with the plastic constant; k * a computed in fixed point so large k keeps its precision.
  uint kx = (uint)k * 3242174889U;  // 2^32 / plastic number
  uint ky = (uint)k * 2447445413U;  // 2^32 / plastic number^2
  float2 r2 = SSRCL_FLOAT2(u32_to_unit(kx), u32_to_unit(ky));
  float2 u = r2 + shift;
  return u - floor(u);
}
