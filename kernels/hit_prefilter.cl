// Prefiltered hits (TraceSettings::prefilter), run after each traced batch. trace.cl records a
// rough ray's hit on a surface the pyramid holds as where to look up instead of a colour:
// ray_radiance.xyz = (screen position, -1 - mip level), marked by the negative z (colours are never
// negative). These kernels count the batch's hits per pixel, weight the colour pyramid's level 0
// by them, reduce it (color_pyramid.cl) and give each such record the pyramid's mean over its
// footprint.
//
// Why weighted by hits: a footprint's mean stands for the rays that land in it. Weighted by
// coverage alone, an emitter's light spread over every surface texel beside it, whether rays
// reached them or not, and the rays that hit the emitter lost it: night_street's mean signed
// error went 0.025 below the full-resolution pass's (same rays), 0.0035 below with the hits
// (docs/BENCHMARKS.md "Speckle"). Where hits are dense the mean is over what they found.

inline bool deferred_lookup(float4 radiance) { return radiance.z < 0.0f; }

// The record of work-item gid, enumerated as trace.cl does; -1 where that sample was not traced.
inline long batch_record(TraceParams params, __global const int* ray_list, __global const int* pixel_rays, int gid) {
  if (gid >= params.listed * params.batch_size) return -1;
  int i = ray_list[gid / params.batch_size], slot = gid % params.batch_size;
  return params.first_sample + slot < pixel_rays[i] ? (long)i * params.batch_size + slot : -1;
}

inline int lookup_pixel(TraceParams params, float2 s) {
  int2 cell = clamp(convert_int2(floor(s)), (int2)(0), (int2)(params.frame.width - 1, params.frame.height - 1));
  return cell.y * params.frame.width + cell.x;
}

__kernel void count_hits(TraceParams params, __global const int* ray_list, __global const int* pixel_rays,
                         __global const float4* ray_radiance, __global int* counts) {
  long r = batch_record(params, ray_list, pixel_rays, get_global_id(0));
  if (r < 0) return;
  float4 rad = ray_radiance[r];
  if (deferred_lookup(rad)) atomic_inc(&counts[lookup_pixel(params, rad.xy)]);
}

// Level 0's weight becomes 1 + the pixel's hits in this batch where the pyramid holds the pixel
// (setup.cl writes 1 there, 0 on sky and specular pixels; a weight > 0 keeps marking them from batch
// to batch); the count is cleared for the next batch. The 1 keeps the texels no ray reached in the
// mean where hits are sparse: hits alone brighten night_street by as much the other way (+0.009,
// and 0.6 dB of its speckle back), 1 + hits leaves -0.0035; 0.5 + hits +0.001 with 0.2 dB of
// speckle back, 2 + hits -0.009 (docs/BENCHMARKS.md "Speckle").
__kernel void weights_from_counts(TraceParams params, __global float4* pyramid, __global int* counts) {
  int i = get_global_id(0);
  if (i >= params.frame.width * params.frame.height) return;
  pyramid[i].w = pyramid[i].w > 0.0f ? 1.0f + (float)counts[i] : 0.0f;
  counts[i] = 0;
}

__kernel void prefilter_hits(TraceParams params, __global const int* ray_list, __global const int* pixel_rays,
                             __global const float4* pyramid, __global const HzbLevel* levels,
                             __global float4* ray_radiance) {
  long r = batch_record(params, ray_list, pixel_rays, get_global_id(0));
  if (r < 0) return;
  float4 rad = ray_radiance[r];
  if (!deferred_lookup(rad)) return;
  float4 c = pyramid_sample(pyramid, levels, params.level_count, rad.xy, -1.0f - rad.z);
  ray_radiance[r] = (float4)(c.xyz, rad.w);
}
