// Deterministic sample sequences: the R2 low-discrepancy sequence (Roberts 2018), rotated
// (Cranley-Patterson) per pixel by the pixel's point of a lattice over the screen and per seed by
// a hashed shift. Sample k of a pixel is well spread among that pixel's samples, and the
// rotations of any 3x3 to 7x7 block of pixels lie evenly over the square (their nearest two at
// 0.66-0.71 of an even grid's spacing; independent hashed rotations, as before, put them at
// 0.14 of it on average): the resolve reuses the rays of a pixel's neighbours, which together
// then cover its lobe evenly. docs/BENCHMARKS.md "Rays spread over neighbours"; the lattice's
// generators from scripts/search-sample-lattice.py.

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

inline float2 sample_2d(int x, int y, int k, uint seed) {
  // In 32-bit fixed point, where sums wrap as fractions do: large x, y and k keep their precision.
  const uint h = hash_u32(hash_u32(seed + 0x9e3779b9U));
  // The pixel's lattice point x A + y B.
  const uint lx = (uint)x * 3203536409U + (uint)y * 434070340U, ly = (uint)x * 273750888U + (uint)y * 836569341U;
  // R2's point k: k over the plastic number and over its square.
  const uint rx = (uint)k * 3242174889U, ry = (uint)k * 2447445413U;
  return SSRCL_FLOAT2(u32_to_unit(h + lx + rx), u32_to_unit(hash_u32(h) + ly + ry));
}
