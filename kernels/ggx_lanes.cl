// GGX reflection sampling for eight rays at once, one per float8 lane: trace.cl's
// sample_reflection (ggx.cl's visible-normal sampling and density) with every expression in the
// same form and order, so each lane rounds as the scalar code does and draws the same direction.
// PoCL runs a work-item's rays one after another in scalar code; this was a third of the trace.

typedef struct {
  float8 x, y, z;
} Lanes3;

inline Lanes3 lanes3(float8 x, float8 y, float8 z) {
  Lanes3 v = {x, y, z};
  return v;
}

inline float8 dot3_lanes(Lanes3 a, Lanes3 b) { return dot_lanes(a.x, a.y, a.z, b.x, b.y, b.z); }

// normalize() as PoCL computes it for a float3 of ordinary length: p * rsqrt(dot(p, p)).
inline Lanes3 normalize_lanes(Lanes3 p) {
  float8 r = rsqrt(dot3_lanes(p, p));
  return lanes3(p.x * r, p.y * r, p.z * r);
}

inline float8 ggx_lambda_lanes(Lanes3 w, float8 alpha) {
  float8 c2 = w.z * w.z;
  float8 tan2 = (w.x * w.x + w.y * w.y) / c2;
  return select(0.5f * (sqrt(1.0f + alpha * alpha * tan2) - 1.0f), (float8)(INFINITY), c2 <= 0.0f);
}

inline float8 ggx_vndf_pdf_from_half_lanes(Lanes3 o, Lanes3 h, float8 alpha) {
  float8 g1 = select((float8)(0.0f), 1.0f / (1.0f + ggx_lambda_lanes(o, alpha)), o.z > 0.0f);
  float8 a2 = alpha * alpha;
  float8 k = a2 * h.z * h.z + (h.x * h.x + h.y * h.y);
  float8 d = select((float8)(0.0f), a2 / (SSRCL_PI * k * k), h.z > 0.0f);
  return select((float8)(0.0f), g1 * d / (4.0f * o.z), o.z > 0.0f);
}

// cross() as PoCL computes it: each product rounded (no fused multiply-add).
inline Lanes3 cross_lanes(Lanes3 a, Lanes3 b) {
#pragma OPENCL FP_CONTRACT OFF
  return lanes3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}

inline Lanes3 ggx_sample_vndf_lanes(Lanes3 o, float8 alpha, float8 ux, float8 uy) {
  Lanes3 vh = normalize_lanes(lanes3(alpha * o.x, alpha * o.y, o.z));
  float8 lensq = vh.x * vh.x + vh.y * vh.y;
  float8 inv = rsqrt(lensq);
  int8 tilted = lensq > 0.0f;
  Lanes3 t1 = lanes3(select((float8)(1.0f), -vh.y * inv, tilted), select((float8)(0.0f), vh.x * inv, tilted),
                     select((float8)(0.0f), 0.0f * inv, tilted));
  Lanes3 t2 = cross_lanes(vh, t1);
  SSRCL_VNDF_DISK(float8, ux, uy, vh.z)
  Lanes3 nh = lanes3(p1 * t1.x + p2 * t2.x + w * vh.x, p1 * t1.y + p2 * t2.y + w * vh.y,
                     p1 * t1.z + p2 * t2.z + w * vh.z);
  return normalize_lanes(lanes3(alpha * nh.x, alpha * nh.y, fmax(nh.z, 1e-6f)));
}

// sample_reflection per lane: the direction (zero where the sample points below the surface), and
// its pdf in *pdf (0 for mirror lanes).
inline Lanes3 sample_reflection_lanes(Lanes3 o, Lanes3 n, int8 mirror, float8 alpha, float8 ux, float8 uy,
                                      float8* pdf) {
  float8 on = dot3_lanes(o, n);
  Lanes3 reflected = lanes3(2.0f * on * n.x - o.x, 2.0f * on * n.y - o.y, 2.0f * on * n.z - o.z);
  // basis_from_normal
  float8 sign = select((float8)(-1.0f), (float8)(1.0f), n.z >= 0.0f);
  float8 a = -1.0f / (sign + n.z);
  float8 c = n.x * n.y * a;
  Lanes3 tx = lanes3(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  Lanes3 ty = lanes3(c, sign + n.y * n.y * a, -n.y);
  Lanes3 ol = lanes3(dot3_lanes(o, tx), dot3_lanes(o, ty), on);
  Lanes3 h = ggx_sample_vndf_lanes(ol, alpha, ux, uy);
  float8 oh = dot3_lanes(ol, h);
  Lanes3 ll = lanes3(2.0f * oh * h.x - ol.x, 2.0f * oh * h.y - ol.y, 2.0f * oh * h.z - ol.z);
  int8 above = ll.z > 0.0f;
  Lanes3 d = normalize_lanes(lanes3(ll.x * tx.x + ll.y * ty.x + ll.z * n.x, ll.x * tx.y + ll.y * ty.y + ll.z * n.y,
                                    ll.x * tx.z + ll.y * ty.z + ll.z * n.z));
  *pdf = select(select((float8)(0.0f), ggx_vndf_pdf_from_half_lanes(ol, h, alpha), above), (float8)(0.0f), mirror);
  return lanes3(select(select((float8)(0.0f), d.x, above), reflected.x, mirror),
                select(select((float8)(0.0f), d.y, above), reflected.y, mirror),
                select(select((float8)(0.0f), d.z, above), reflected.z, mirror));
}
