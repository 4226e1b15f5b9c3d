// Shared definitions for every ssrcl kernel. The host concatenates this file before the others.
//
// Conventions: pixel (x, y) covers [x, x+1) x [y, y+1), y = 0 is the top row. Matrices are
// float16 in row-major order (s0123 = first row) and act on column vectors. Depth is planar
// view depth (positive in front of the camera); SSRCL_NO_SURFACE marks sky and invalid pixels.

#define SSRCL_NO_SURFACE FLT_MAX

// One HZB level: offset into the packed mip buffer and its size.
typedef struct {
  int offset;
  int width;
  int height;
  int pad;
} HzbLevel;

inline float4 mat_mul(float16 m, float4 v) {
  return (float4)(dot(m.s0123, v), dot(m.s4567, v), dot(m.s89ab, v), dot(m.scdef, v));
}

inline float3 mat3_mul(float16 m, float3 v) {
  return (float3)(dot(m.s012, v), dot(m.s456, v), dot(m.s89a, v));
}

// Camera-space point on the line through NDC (x, y) at NDC depth z.
inline float3 unproject(float16 inv_proj, float2 ndc, float z) {
  float4 h = mat_mul(inv_proj, (float4)(ndc, z, 1.0f));
  return h.xyz / h.w;
}

inline float2 pixel_to_ndc(float2 pixel, int2 size) {
  return (float2)(2.0f * pixel.x / (float)size.x - 1.0f, 1.0f - 2.0f * pixel.y / (float)size.y);
}

inline float2 ndc_to_pixel(float2 ndc, int2 size) {
  return (float2)((ndc.x + 1.0f) * 0.5f * (float)size.x, (1.0f - ndc.y) * 0.5f * (float)size.y);
}

inline float hzb_fetch(__global const float* hzb, __global const HzbLevel* levels, int level, int2 cell) {
  HzbLevel l = levels[level];
  cell = clamp(cell, (int2)(0, 0), (int2)(l.width - 1, l.height - 1));
  return hzb[l.offset + cell.y * l.width + cell.x];
}

// View-space surface point of pixel `pix` at planar depth `depth`, and the unit viewing direction
// (eye -> point); valid for perspective and orthographic cameras alike.
inline float3 pixel_view_point(float16 inv_proj, int2 size, int2 pix, float depth, float3* view_dir) {
  float2 ndc = pixel_to_ndc(convert_float2(pix) + 0.5f, size);
  float3 a = unproject(inv_proj, ndc, -1.0f), b = unproject(inv_proj, ndc, 0.0f);
  *view_dir = normalize(b - a);
  return a + (b - a) * ((-depth - a.z) / (b.z - a.z));
}

// Confidence of a hit at screen position s: fades to 0 over `edge_fade` of the smaller screen side.
inline float edge_confidence(float2 s, int2 size, float edge_fade) {
  if (!(edge_fade > 0.0f)) return 1.0f;
  float border = fmin(fmin(s.x, (float)size.x - s.x), fmin(s.y, (float)size.y - s.y));
  return clamp(border / (edge_fade * (float)min(size.x, size.y)), 0.0f, 1.0f);
}

// Planar depth where the viewing line through screen point `pixel` meets the plane through p with
// normal n, or a negative value where that line runs parallel to it or meets it behind the eye.
inline float plane_depth_at(float16 inv_proj, int2 size, float2 pixel, float3 p, float3 n) {
  float2 ndc = pixel_to_ndc(pixel, size);
  float3 a = unproject(inv_proj, ndc, -1.0f), b = unproject(inv_proj, ndc, 0.0f);
  float denom = dot(b - a, n);
  if (fabs(denom) < 1e-20f) return -1.0f;
  float lambda = dot(p - a, n) / denom;
  return lambda >= 0.0f ? -(a.z + lambda * (b.z - a.z)) : -1.0f;
}
