// Kernels that expose device functions to the tests; the pipeline never launches them.

// Test hook: `count` reflected directions for the local view direction o (normal +Z) drawn exactly
// as the tracer draws them (sequence index = work-item), with their density, for the sampler's
// statistical tests. out[i] = (l.xyz, pdf).
__kernel void ggx_sample_directions(float4 o, float alpha, uint seed, int count, __global float4* out) {
  int i = get_global_id(0);
  if (i >= count) return;
  float3 ov = normalize(o.xyz);
  float3 h = ggx_sample_vndf(ov, alpha, sample_2d(0, i, seed));
  float3 l = 2.0f * dot(ov, h) * h - ov;
  out[i] = (float4)(l, ggx_vndf_reflection_pdf(ov, l, alpha));
}
