// Resolve: radiance at each mirror hit, faded near the screen edges where screen-space data runs
// out. Output is premultiplied: rgb = radiance * A, A = confidence.
__kernel void resolve_mirror(int2 size, float edge_fade, __global const float4* hits,
                             __global const float4* color, __global float4* out_rgba,
                             __global float* out_distance) {
  int x = get_global_id(0), y = get_global_id(1);
  if (x >= size.x || y >= size.y) return;
  int i = y * size.x + x;
  float4 h = hits[i];
  if (!(h.w > 0.0f)) {
    out_rgba[i] = (float4)(0.0f);
    out_distance[i] = 0.0f;
    return;
  }
  int2 hp = clamp(convert_int2(floor(h.xy)), (int2)(0, 0), size - 1);
  float confidence = 1.0f;
  if (edge_fade > 0.0f) {
    float border = fmin(fmin(h.x, (float)size.x - h.x), fmin(h.y, (float)size.y - h.y));
    confidence = clamp(border / (edge_fade * (float)min(size.x, size.y)), 0.0f, 1.0f);
  }
  float3 c = color[hp.y * size.x + hp.x].xyz;
  out_rgba[i] = (float4)(c * confidence, confidence);
  out_distance[i] = h.z;
}
