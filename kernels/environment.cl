// Environment fill: the part of each pixel's lobe the screen did not hold (1 - A, the edge fade
// included) takes the environment's radiance filtered for that lobe (include/ssrcl/environment.hpp:
// the mapping, and the prefiltered levels, one per roughness step). RGB becomes the complete
// reflection; A keeps the screen-space fraction.

// Bilinear read of one packed RGB level at direction d (world, +Z up, Blender's mapping):
// wraps around in azimuth, clamps at the poles.
inline float3 environment_bilinear(__global const float* texels, HzbLevel l, float3 d) {
  float u = 0.5f - atan2(d.y, d.x) * (0.5f * M_1_PI_F);
  float v = 0.5f - atan2(d.z, hypot(d.x, d.y)) * M_1_PI_F;
  float x = u * (float)l.width - 0.5f;
  float y = clamp(v * (float)l.height - 0.5f, 0.0f, (float)(l.height - 1));
  float fx = x - floor(x), fy = y - floor(y);
  int x0 = ((int)floor(x) % l.width + l.width) % l.width, x1 = (x0 + 1) % l.width;
  int y0 = min((int)floor(y), l.height - 1), y1 = min(y0 + 1, l.height - 1);
  __global const float* row0 = texels + 3 * ((size_t)l.offset + (size_t)y0 * l.width);
  __global const float* row1 = texels + 3 * ((size_t)l.offset + (size_t)y1 * l.width);
  float3 top = mix(vload3(x0, row0), vload3(x1, row0), fx);
  float3 bottom = mix(vload3(x0, row1), vload3(x1, row1), fx);
  return mix(top, bottom, fy);
}

// `view_to_world` rotates view-space directions into the environment's frame (the camera's
// inverse view rotation, then the environment rotation about +Z). Pixels with a surface and a
// front-facing normal get the fill, whatever their roughness: a pixel too rough to trace
// (A = 0) reflects the environment only.
__kernel void environment_fill(EnvironmentParams params, __global const float4* positions,
                               __global const float4* normals, __global const float* texels,
                               __global const HzbLevel* levels, __global float4* rgba) {
  const int2 size = (int2)(params.frame.width, params.frame.height);
  const float16 view_to_world = vload16(0, params.view_to_world);
  const int level_count = params.level_count;
  const int roughness_linear = SSRCL_ROUGHNESS_MAPPING == SSRCL_ROUGHNESS_LINEAR;
  const float intensity = params.intensity;
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= size.x || y >= size.y) return;
  int i = y * size.x + x;
  float4 p = positions[i];
  float4 n = normals[i];
  float3 view_dir = normalize(p.xyz);
  if (p.w == SSRCL_NO_SURFACE || !(dot(view_dir, n.xyz) < 0.0f)) return;
  float3 r = mat3_mul(view_to_world, view_dir - 2.0f * dot(view_dir, n.xyz) * n.xyz);
  // Levels are spaced evenly in Blender's roughness, sqrt(alpha). Between two, the mix weight
  // is taken in alpha^2, to which a narrow lobe's angular variance is proportional: the mixture
  // of the two blurs then spreads as far as the lobe in between (a weight linear in roughness
  // blurs up to 27% more at roughness 0.3).
  float alpha = clamp(roughness_linear ? n.w : n.w * n.w, 0.0f, 1.0f);
  float steps = (float)(level_count - 1);
  int k = min((int)(sqrt(alpha) * steps), level_count - 2);
  float a0 = (float)(k * k) / (steps * steps), a1 = (float)((k + 1) * (k + 1)) / (steps * steps);
  float weight = clamp((alpha * alpha - a0 * a0) / (a1 * a1 - a0 * a0), 0.0f, 1.0f);
  float3 env = mix(environment_bilinear(texels, levels[k], r), environment_bilinear(texels, levels[k + 1], r),
                   weight);
  float4 found = rgba[i];
  float missed = clamp(1.0f - found.w, 0.0f, 1.0f);
  float3 filled = sanitize_radiance3(found.xyz + missed * intensity * env);
  rgba[i] = (float4)(filled, found.w);
}
