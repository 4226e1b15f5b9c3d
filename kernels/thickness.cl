// Adaptive surface thickness: how far behind a pixel's surface a ray may pass and still hit it.
//
// A depth buffer shows the front of every object and nothing of its depth. Objects are about as
// deep as they are wide, so each pixel's thickness follows the visible extent of the surface it
// belongs to, along the unbroken run of surface through it on its row and on its column: a pole,
// a can or a plank is as deep as its narrow side is wide, a floor's runs are long. Thickness =
// scale * chord, kept within [min_rel, max_rel] of the pixel's depth. Setup wrote each pixel's
// surface plane (surface_plane.cl) for a thickness of the depth itself times |n.v| (hits measure
// along the normal): it is rescaled by the thickness relative to the depth.
//
// The chord is the depth of the surface along the viewing line, estimated as a round object's
// would be: a pixel at view-space distances a and b from the two ends of its run lies under a chord
// 2 sqrt(a b) deep (exact for a sphere, whichever line through the pixel; for an upright cylinder,
// along its rows). The larger of the row's and the column's chords, no longer than the shorter
// run (an object is no deeper than its narrow side is wide): silhouettes are thin, middles deep,
// and a can is as deep at its top as at its middle.

// Runs break at depth discontinuities, found from depth alone (common.cl predicts): shading normals
// (smoothed, bumped, filtered over silhouettes) can differ from the geometry by tens of degrees.
// Neighbours join where their depths differ by under 2%, or where either side's line predicts the
// other.

inline bool joined(__global const float4* positions, int k, int length, int step, int base) {
  float da = positions[base + (k - 1) * step].w, db = positions[base + k * step].w;
  if (da >= SSRCL_NO_SURFACE || db >= SSRCL_NO_SURFACE) return false;
  if (fabs(db - da) <= 0.02f * fmin(da, db)) return true;
  if (k >= 2 && positions[base + (k - 2) * step].w < SSRCL_NO_SURFACE &&
      predicts(positions[base + (k - 2) * step].w, da, db))
    return true;
  return k + 1 < length && positions[base + (k + 1) * step].w < SSRCL_NO_SURFACE &&
         predicts(positions[base + (k + 1) * step].w, db, da);
}

// One work-item per row (axis 0) or column (axis 1). Axis 0 writes each pixel's (run length, chord)
// to `row`; axis 1 compares with its column's and rescales the plane.
__kernel void surface_thickness(ThicknessParams params, __global const float4* positions,
                                __global float2* row, __global float4* planes) {
  const int2 size = (int2)(params.frame.width, params.frame.height);
  const int axis = params.axis;
  const float scale = params.scale, min_rel = params.min_rel, max_rel = params.max_rel;
  int line = get_global_id(0);
  int count = axis == 0 ? size.y : size.x;
  if (line >= count) return;
  int length = axis == 0 ? size.x : size.y;
  int step = axis == 0 ? 1 : size.x;
  int base = axis == 0 ? line * size.x : line;
  int start = 0;
  for (int k = 1; k <= length; ++k) {
    int prev = base + (k - 1) * step;
    if (k < length && joined(positions, k, length, step, base)) continue;
    // The run [start, k) ends here. A flat run (every depth on the line through its two ends, in
    // 1 / depth or depth, within 1%) is a slab seen from the front (a wall, a floor, a board, a
    // sign): how deep it goes cannot be told from its width, and slabs standing free are thin, so
    // it contributes no chord. A curved run gets each pixel's chord.
    float d_first = positions[base + start * step].w, d_last = positions[prev].w;
    bool flat = true;
    for (int j = start + 1; j < k - 1 && flat; ++j) {
      float f = (float)(j - start) / (float)(k - 1 - start), d = positions[base + j * step].w;
      flat = fabs(1.0f / d - mix(1.0f / d_first, 1.0f / d_last, f)) <= 0.01f / d ||
             fabs(d - mix(d_first, d_last, f)) <= 0.01f * d;
    }
    float3 first = positions[base + start * step].xyz, last = positions[prev].xyz;
    float run = distance(first, last);
    for (int j = start; j < k; ++j) {
      int i = base + j * step;
      float3 p = positions[i].xyz;
      float chord = flat ? 0.0f : 2.0f * sqrt(distance(first, p) * distance(p, last));
      if (axis == 0) {
        row[i] = (float2)(run, chord);
      } else {
        float d = positions[i].w;
        float2 r = row[i];
        float depth_chord = fmin(fmax(chord, r.y), fmin(run, r.x));
        if (d < SSRCL_NO_SURFACE) planes[i] *= d / clamp(scale * depth_chord, min_rel * d, max_rel * d);
      }
    }
    start = k;
  }
}

// Where a back-face depth pass knows it (back > 0: host/io/back_depth.cpp leaves 0 elsewhere), a
// pixel's thickness is exact: its viewing line leaves the surface at planar depth `back`, at
// q = p + (back - d) s, s the line's step per unit of planar depth (p / d through the eye, -z
// orthographic), which lies (back - d) |s.n| behind the plane along its normal. That replaces the
// model's thickness (adaptive or constant) in the plane record; the plane's normal is its direction.
// `guess` keeps the model's thickness in units of the exact one there, 0 elsewhere: where the
// exact interval leaves a ray with nothing, the trace falls back on it (trace.cl SSRCL_BACK_KNOWN).
__kernel void known_thickness(ThicknessParams params, __global const float4* positions,
                              __global const float* back, __global float4* planes, __global float* guess) {
  int i = get_global_id(0);
  if (i >= params.frame.width * params.frame.height) return;
  float4 position = positions[i], plane = planes[i];
  float b = back[i], d = position.w;
  guess[i] = 0.0f;
  if (!(b > 0.0f) || d >= SSRCL_NO_SURFACE || plane.w == -INFINITY) return;  // SSRCL_NO_PLANE
  float3 n = normalize(plane.xyz);
  float3 s = params.orthographic ? (float3)(0.0f, 0.0f, -1.0f) : position.xyz / d;
  float4 exact = surface_plane(position.xyz, n, (b - d) * fabs(dot(s, n)));
  planes[i] = exact;
  // The records are (n, dot(p, n)) / thickness: the ratio of their normals' lengths.
  guess[i] = length(exact.xyz) / length(plane.xyz);
}
