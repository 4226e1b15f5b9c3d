// Each pixel's surface as the trace's hit test reads it (trace.cl hit_pixel): the plane through
// the pixel's view-space point p with unit normal n, stored as (n, dot(p, n)) / thickness in one
// float4. A full-resolution step then reads one 16-byte record instead of a point, a normal and a
// thickness from three arrays (three cache lines; the trace is bound by these reads). A ray's
// signed distance to the plane comes in units of the thickness: the test's signs and crossing
// ratio do not change with the scale, and "behind by less than the thickness" is "by less than 1".
// Setup writes it (setup.cl); the adaptive thickness model rescales it (thickness.cl).

// Sky and invalid pixels: no normal to face, and every ray in front of the plane (at -infinity).
#define SSRCL_NO_PLANE ((float4)(0.0f, 0.0f, 0.0f, -INFINITY))

// A thickness below the plane test's float resolution (FLT_EPSILON of the point's distance; an
// edge-on surface has thickness 0) is raised to it, and one beyond a million times that distance
// (where 1 / thickness would underflow to a zero normal that nothing hits) is lowered to it: the
// record stays finite and non-zero.
inline float4 surface_plane(float3 p, float3 n, float thickness) {
  float distance = length(p);
  return (float4)(n, dot(p, n)) * (1.0f / clamp(thickness, FLT_EPSILON * distance, 1e6f * distance));
}
