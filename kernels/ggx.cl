// GGX (Trowbridge-Reitz) microfacet lobe in a local frame where the normal is +Z.
// o is the unit direction toward the viewer, l toward the light (the reflected ray), both local.
// Roughness maps to alpha before it reaches these functions (alpha = roughness^2 by default).

#define SSRCL_PI 3.14159265358979f

// Smith's Lambda for GGX; w.z is the cosine to the normal.
// sin^2 is taken from x and y rather than 1 - cos^2, which cancels near the normal.
inline float ggx_lambda(float3 w, float alpha) {
  float c2 = w.z * w.z;
  if (c2 <= 0.0f) return INFINITY;
  float tan2 = (w.x * w.x + w.y * w.y) / c2;
  return 0.5f * (sqrt(1.0f + alpha * alpha * tan2) - 1.0f);
}

inline float ggx_g1(float3 w, float alpha) { return w.z > 0.0f ? 1.0f / (1.0f + ggx_lambda(w, alpha)) : 0.0f; }

// cos^2 (alpha^2 - 1) + 1 written as alpha^2 cos^2 + sin^2: exact as alpha -> 0.
inline float ggx_d(float3 h, float alpha) {
  float a2 = alpha * alpha;
  float k = a2 * h.z * h.z + (h.x * h.x + h.y * h.y);
  return h.z > 0.0f ? a2 / (SSRCL_PI * k * k) : 0.0f;
}

// Density of the reflected direction when its half vector h is drawn from the visible-normal
// distribution: D_o(h) / (4 o.h) = G1(o) D(h) / (4 o.z).
inline float ggx_vndf_pdf_from_half(float3 o, float3 h, float alpha) {
  return o.z > 0.0f ? ggx_g1(o, alpha) * ggx_d(h, alpha) / (4.0f * o.z) : 0.0f;
}

// The same density for a given l; h = normalize(o + l) cancels for l near the mirror direction
// at grazing views, so callers that still have the sampled h use the form above.
inline float ggx_vndf_reflection_pdf(float3 o, float3 l, float alpha) {
  float3 h = o + l;
  float len = length(h);
  return len > 0.0f ? ggx_vndf_pdf_from_half(o, h / len, alpha) : 0.0f;
}

// The visible-normal sample's point (p1, p2) on the projected disk and w, its normal's share
// along the stretched view vh (Heitz 2018), for one ray (T float) or eight in lanes (T float8,
// kernels/ggx_lanes.cl): one text, so that both round alike. ux, uy: the random numbers, vz: vh.z.
// One argument reduction for sine and cosine (PoCL's sincos equals its cos and sin bit for bit on
// every phi this can take, 2 pi k / 2^24, at about half their cost).
#define SSRCL_VNDF_DISK(T, ux, uy, vz)                               \
  T p1, p2, w;                                                       \
  {                                                                  \
    T r_ = sqrt(ux), phi_ = 2.0f * SSRCL_PI * (uy), cos_phi_;        \
    T sin_phi_ = sincos(phi_, &cos_phi_);                            \
    p1 = r_ * cos_phi_;                                              \
    p2 = r_ * sin_phi_;                                              \
    T s_ = 0.5f * (1.0f + (vz));                                     \
    p2 = (1.0f - s_) * sqrt(fmax(1.0f - p1 * p1, 0.0f)) + s_ * p2;   \
    w = sqrt(fmax(1.0f - p1 * p1 - p2 * p2, 0.0f));                  \
  }

// Visible-normal sampling (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"):
// stretch the view to the unit-roughness configuration, sample the projected hemisphere there,
// unstretch. Stable for alpha -> 0 (returns +Z) and for grazing o.
inline float3 ggx_sample_vndf(float3 o, float alpha, float2 u) {
  float3 vh = normalize(SSRCL_FLOAT3(alpha * o.x, alpha * o.y, o.z));
  float lensq = vh.x * vh.x + vh.y * vh.y;
  float3 t1 = lensq > 0.0f ? SSRCL_FLOAT3(-vh.y, vh.x, 0.0f) * rsqrt(lensq) : SSRCL_FLOAT3(1.0f, 0.0f, 0.0f);
  float3 t2 = cross(vh, t1);
  SSRCL_VNDF_DISK(float, u.x, u.y, vh.z)
  float3 nh = p1 * t1 + p2 * t2 + w * vh;
  // z kept off 0: at alpha -> 0 a rounding to 0 would turn the mirror normal into a horizontal one.
  return normalize(SSRCL_FLOAT3(alpha * nh.x, alpha * nh.y, fmax(nh.z, 1e-6f)));
}

// Orthonormal basis around unit n (Duff et al. 2017, branchless).
inline void basis_from_normal(float3 n, float3* t, float3* b) {
  float sign = n.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (sign + n.z);
  float c = n.x * n.y * a;
  *t = SSRCL_FLOAT3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  *b = SSRCL_FLOAT3(c, sign + n.y * n.y * a, -n.y);
}

// Roughness to alpha: Cycles and most renderers square it (SSRCL_ROUGHNESS_SQUARED), or linear.
inline float roughness_to_alpha(float roughness, int mapping) {
  return mapping == SSRCL_ROUGHNESS_LINEAR ? roughness : roughness * roughness;
}
