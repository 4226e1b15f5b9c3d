// The packet trace of packet_hiz_trace.hpp for any lane width: templates over a lane type L
// (packet_hiz_trace_avx512.cpp: 16 AVX-512 lanes, packet_hiz_trace_avx2.cpp: 8 AVX2 lanes) that
// gives the vector types F (float), I (int32) and M (a mask of lanes), the operations whose
// instructions differ between the widths, and two tunables:
//   kRefillAt: lanes are refilled once this many are free (refilling costs about a step's
//     instructions, and waiting for more leaves lanes idle);
//   kPackets: packets per thread, whose steps interleave (a step waits on its texel loads and on
//     the chain of decisions that make its index; the other packets' steps fill the wait).
// Float arithmetic is GCC's vector operators. Included inside an anonymous namespace by each of
// those files alone: every function here then has internal linkage, so no code compiled for one
// -march can be merged into the other's.

constexpr int kIota[16] = {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15};

// A lane type's vectors of W (512 or 256) bits, and the operations whose intrinsics differ in
// the width alone.
#define SSRCL_PACKET_LANE_OPS(W)                                                         \
  static constexpr int kLanes = W / 32;                                                  \
  using F = __m##W;                                                                      \
  using I = __m##W##i;                                                                   \
  static I iota() { return _mm##W##_loadu_si##W(reinterpret_cast<const I*>(kIota)); }    \
  static F abs(F a) { return _mm##W##_andnot_ps(f(-0.0f), a); }                          \
  static F f(float v) { return _mm##W##_set1_ps(v); }                                    \
  static I i(int v) { return _mm##W##_set1_epi32(v); }                                   \
  static F fma(F a, F b, F c) { return _mm##W##_fmadd_ps(a, b, c); }   /* a b + c */     \
  static F fms(F a, F b, F c) { return _mm##W##_fmsub_ps(a, b, c); }   /* a b - c */     \
  static F fnma(F a, F b, F c) { return _mm##W##_fnmadd_ps(a, b, c); } /* c - a b */     \
  static F min(F a, F b) { return _mm##W##_min_ps(a, b); }                               \
  static F max(F a, F b) { return _mm##W##_max_ps(a, b); }                               \
  static F sqrt(F a) { return _mm##W##_sqrt_ps(a); }                                     \
  static F signOf(F a) { return _mm##W##_or_ps(f(1.0f), _mm##W##_and_ps(a, f(-0.0f))); } \
  static F cvt(I a) { return _mm##W##_cvtepi32_ps(a); }                                  \
  static F asF(I a) { return _mm##W##_castsi##W##_ps(a); }                               \
  static I asI(F a) { return _mm##W##_castps_si##W(a); }                                 \
  static I add(I a, I b) { return _mm##W##_add_epi32(a, b); }                            \
  static I sub(I a, I b) { return _mm##W##_sub_epi32(a, b); }                            \
  static I mullo(I a, I b) { return _mm##W##_mullo_epi32(a, b); }                        \
  static I xor_(I a, I b) { return _mm##W##_xor_si##W(a, b); }                           \
  static I or_(I a, I b) { return _mm##W##_or_si##W(a, b); }                             \
  static I min(I a, I b) { return _mm##W##_min_epi32(a, b); }                            \
  template <int N>                                                                       \
  static I srli(I a) {                                                                   \
    return _mm##W##_srli_epi32(a, N);                                                    \
  }                                                                                      \
  template <int N>                                                                       \
  static I slli(I a) {                                                                   \
    return _mm##W##_slli_epi32(a, N);                                                    \
  }                                                                                      \
  static I sllv(I a, I n) { return _mm##W##_sllv_epi32(a, n); }                          \
  static I srav(I a, I n) { return _mm##W##_srav_epi32(a, n); }

constexpr int kClimb = 2;                      // levels a skip may climb (L::climb caps at it)
constexpr float kPi = 3.14159265358979f;

int imin(int a, int b) { return a < b ? a : b; }

// A generated ray, one array per field (struct of arrays, so lanes load with one expand each):
// t at a cell boundary x is x * ix + nx (ix = 1 / ds.x); 1/z at t is k0 + t * dk; the ray
// starts at t0 in cell (cx, cy) of level 0, its own pixel left behind.
enum Field { kIx, kNx, kIy, kNy, kK0, kDk, kIdk, kT0, kCx, kCy, kPixel, kFields };

struct RayBuffer {
  float* field[kFields];
  float* tHit;
  size_t count = 0;
};

template <class L>
struct Lanes {
  using F = typename L::F;
  using I = typename L::I;
  using M = typename L::M;

  struct V3 {
    F x, y, z;
  };

  // Ordered comparisons of floats: false where either is NaN.
  static M gt(F a, F b) { return L::template cmp<_CMP_GT_OQ>(a, b); }
  static M ge(F a, F b) { return L::template cmp<_CMP_GE_OQ>(a, b); }
  static M lt(F a, F b) { return L::template cmp<_CMP_LT_OQ>(a, b); }
  static M le(F a, F b) { return L::template cmp<_CMP_LE_OQ>(a, b); }
  static M eq(F a, F b) { return L::template cmp<_CMP_EQ_OQ>(a, b); }
  static M ne(F a, F b) { return L::template cmp<_CMP_NEQ_OQ>(a, b); }

  // sin and cos of 2 pi u: of the half angle by Taylor series to 1e-6 on [-pi/2, pi/2], doubled.
  static void sinCos2Pi(F u, F& s, F& c) {
    const F x = (u - L::template round<_MM_FROUND_TO_NEAREST_INT>(u)) * kPi;  // half angle in [-pi/2, pi/2]
    const F x2 = x * x;
    F sp = L::f(1.0f / 362880.0f);
    sp = L::fma(sp, x2, L::f(-1.0f / 5040.0f));
    sp = L::fma(sp, x2, L::f(1.0f / 120.0f));
    sp = L::fma(sp, x2, L::f(-1.0f / 6.0f));
    sp = L::fma(sp, x2, L::f(1.0f));
    const F sh = sp * x;
    F cp = L::f(-1.0f / 3628800.0f);
    cp = L::fma(cp, x2, L::f(1.0f / 40320.0f));
    cp = L::fma(cp, x2, L::f(-1.0f / 720.0f));
    cp = L::fma(cp, x2, L::f(1.0f / 24.0f));
    cp = L::fma(cp, x2, L::f(-0.5f));
    const F ch = L::fma(cp, x2, L::f(1.0f));
    s = 2.0f * (sh * ch);
    c = L::fms(ch, ch, sh * sh);
  }

  // A uniform in [0, 1) from 24 bits of Wellons' lowbias32 hash.
  static F hashUniform(I v) {
    v = L::xor_(v, L::template srli<16>(v));
    v = L::mullo(v, L::i(0x7feb352d));
    v = L::xor_(v, L::template srli<15>(v));
    v = L::mullo(v, L::i(int(0x846ca68bu)));
    v = L::xor_(v, L::template srli<16>(v));
    return L::cvt(L::template srli<8>(v)) * (1.0f / 16777216.0f);
  }

  static F dot(const V3& a, const V3& b) { return L::fma(a.x, b.x, L::fma(a.y, b.y, a.z * b.z)); }
  static V3 scale(const V3& a, F s) { return {a.x * s, a.y * s, a.z * s}; }
  static V3 normalize(const V3& a) { return scale(a, 1.0f / L::sqrt(dot(a, a))); }
  // 2 (o . n) n - o: o reflected about n.
  static V3 reflect(const V3& o, const V3& n) {
    const F d2 = 2.0f * dot(o, n);
    return {L::fms(d2, n.x, o.x), L::fms(d2, n.y, o.y), L::fms(d2, n.z, o.z)};
  }

  // A GGX microfacet normal seen from o (view-space, towards the eye) about normal n, by the
  // visible-normal distribution (spherical caps, Dupuy and Benyoub 2023); alpha = roughness^2.
  static V3 sampleVndf(const V3& o, const V3& n, F alpha, F u1, F u2) {
    // Tangent frame of n (Duff et al. 2017).
    const F one = L::f(1.0f), zero = L::f(0.0f);
    const F sign = L::signOf(n.z);
    const F a = -1.0f / (sign + n.z);
    const F b = (n.x * n.y) * a;
    const V3 t1{L::fma(sign * (n.x * n.x), a, one), sign * b, zero - sign * n.x};
    const V3 t2{b, L::fma(n.y * n.y, a, sign), zero - n.y};
    const V3 vh = normalize({alpha * dot(o, t1), alpha * dot(o, t2), dot(o, n)});
    F s, c;
    sinCos2Pi(u1, s, c);
    const F z = L::fms(one - u2, one + vh.z, vh.z);
    const F sinTheta = L::sqrt(L::max(zero, L::fnma(z, z, one)));
    const V3 h{L::fma(sinTheta, c, vh.x), L::fma(sinTheta, s, vh.y), z + vh.z};
    const V3 m = normalize({alpha * h.x, alpha * h.y, L::max(h.z, zero)});
    return {L::fma(m.x, t1.x, L::fma(m.y, t2.x, m.z * n.x)), L::fma(m.x, t1.y, L::fma(m.y, t2.y, m.z * n.y)),
            L::fma(m.x, t1.z, L::fma(m.y, t2.z, m.z * n.z))};
  }

  static F projectRow(const float* P, int row, const V3& p) {
    return L::fma(L::f(P[row]), p.x, L::fma(L::f(P[4 + row]), p.y, L::fma(L::f(P[8 + row]), p.z, L::f(P[12 + row]))));
  }

  // The screen ray of lanes `valid` from point p along dir (trace.cl make_screen_ray: to the near
  // or far plane, cut at the screen's edge), appended to the buffer.
  static void appendRays(const PacketFrame& fr, M valid, const V3& p, const V3& dir, I x, I y, I pixel,
                         RayBuffer& out) {
    const F zero = L::f(0.0f), one = L::f(1.0f);
    const F pz = p.z, lengthMax = -1e6f * pz;
    const M up = gt(dir.z, zero), down = lt(dir.z, zero);
    const F toNear = (L::f(-fr.nearPlane * 1.001f) - pz) / dir.z;
    const F toFar = (L::f(-fr.farPlane) - pz) / dir.z;
    F len = L::sel(down, toFar, L::sel(up, toNear, lengthMax));
    len = L::min(len, lengthMax);
    valid = M(valid & gt(len, zero));
    const V3 p1{L::fma(dir.x, len, p.x), L::fma(dir.y, len, p.y), L::fma(dir.z, len, p.z)};
    const float* P = fr.projection;
    const F w0 = projectRow(P, 3, p), w1 = projectRow(P, 3, p1);
    valid = M(valid & gt(w0, zero) & gt(w1, zero));
    const F k0 = one / w0, k1 = one / w1;
    const F hw = L::f(0.5f * float(fr.width)), hh = L::f(0.5f * float(fr.height));
    const F s0x = L::fma(projectRow(P, 0, p), k0, one) * hw;
    const F s0y = L::fnma(projectRow(P, 1, p), k0, one) * hh;
    F dsx = L::fma(projectRow(P, 0, p1), k1, one) * hw - s0x;
    F dsy = L::fnma(projectRow(P, 1, p1), k1, one) * hh - s0y;
    // Cut at the screen's edge.
    const M right = gt(dsx, zero), downY = gt(dsy, zero);
    const F ex = L::sel(right, L::f(float(fr.width)), zero);
    const F ey = L::sel(downY, L::f(float(fr.height)), zero);
    const F inf = L::f(__builtin_inff());
    const F tex = L::sel(ne(dsx, zero), (ex - s0x) / dsx, inf);
    const F tey = L::sel(ne(dsy, zero), (ey - s0y) / dsy, inf);
    const F tMax = L::min(one, L::min(tex, tey));
    dsx = dsx * tMax;
    dsy = dsy * tMax;
    const F dk = (k1 - k0) * tMax;
    const F major = L::max(L::abs(dsx), L::abs(dsy));
    valid = M(valid & gt(major, zero) & lt(major, inf) & lt(L::abs(s0x), inf) & lt(L::abs(s0y), inf));
    const unsigned validBits = L::bits(valid);
    if (!validBits) return;
    // A still axis never reaches a boundary: its t there is huge and positive (ix > 0 so the
    // boundary ahead is the upper one, and the pixel centre lies below it).
    const F huge = L::f(1e30f);
    const F ix = L::sel(ne(dsx, zero), one / dsx, huge);
    const F iy = L::sel(ne(dsy, zero), one / dsy, huge);
    const F nx = zero - s0x * ix, ny = zero - s0y * iy;
    // Leave the origin pixel: t where it crosses the pixel's boundary ahead, and the next cell.
    const M posX = gt(ix, zero), posY = gt(iy, zero);
    const I oneI = L::i(1), minusOne = L::i(-1);
    const F tx = L::fma(L::cvt(L::sel(posX, L::add(x, oneI), x)), ix, nx);
    const F ty = L::fma(L::cvt(L::sel(posY, L::add(y, oneI), y)), iy, ny);
    const M stepX = le(tx, ty);
    const I sx = L::sel(posX, oneI, minusOne), sy = L::sel(posY, oneI, minusOne);
    const I cx = L::sel(stepX, L::add(x, sx), x), cy = L::sel(stepX, y, L::add(y, sy));
    const size_t at = out.count;
    const F fields[kFields] = {ix, nx, iy, ny, k0, dk, one / dk, L::min(tx, ty), L::asF(cx), L::asF(cy), L::asF(pixel)};
    const typename L::Compress lanes = L::compressor(validBits);
    for (int f = 0; f < kFields; ++f) L::compressStore(out.field[f] + at, lanes, fields[f]);
    out.count = at + size_t(__builtin_popcount(validBits));
  }

  // Rays of rows [y0, y1), L::kLanes pixels at a time.
  static void generateRays(const PacketFrame& fr, int samples, uint32_t seed, int y0, int y1, RayBuffer& out) {
    const I lane = L::iota();
    const F zero = L::f(0.0f);
    for (int y = y0; y < y1; ++y)
      for (int x0 = 0; x0 < fr.width; x0 += L::kLanes) {
        const size_t first = size_t(y) * fr.width + x0;
        const unsigned flags = L::nonzeroBytes(fr.reflects + first, imin(L::kLanes, fr.width - x0));
        if (!flags) continue;
        M valid = L::mask(flags);
        const I pixel = L::add(L::i(int(first)), lane);
        const I at4 = L::template slli<2>(pixel);
        const auto load = [&](const float* base, int c) { return L::gather(base + c, at4, valid); };
        const V3 p{load(fr.positions, 0), load(fr.positions, 1), load(fr.positions, 2)};
        const V3 n{load(fr.normals, 0), load(fr.normals, 1), load(fr.normals, 2)};
        // Towards the eye (at the view-space origin: perspective).
        const V3 o = normalize({zero - p.x, zero - p.y, zero - p.z});
        valid = M(valid & gt(dot(o, n), zero));
        const I xs = L::add(L::i(x0), lane), ys = L::i(y);
        if (samples == 0) {
          appendRays(fr, valid, p, reflect(o, n), xs, ys, pixel, out);
          continue;
        }
        const F r = load(fr.normals, 3);
        const F alpha = L::max(r * r, L::f(1e-4f));
        for (int s = 0; s < samples; ++s) {
          const I key = L::add(L::mullo(pixel, L::i(samples)), L::i(s));
          const I k2 = L::template slli<1>(key);
          const I seedV = L::i(int(seed * 0x9e3779b9u));
          const F u1 = hashUniform(L::xor_(k2, seedV));
          const F u2 = hashUniform(L::xor_(L::add(k2, L::i(1)), seedV));
          const V3 dir = reflect(o, sampleVndf(o, n, alpha, u1, u2));
          // Directions below the surface get no ray (they would start inside it).
          appendRays(fr, M(valid & gt(dot(dir, n), zero)), p, dir, xs, ys, pixel, out);
        }
      }
  }

  // A cell's range of 1/z, [lo, hi], for the lanes of `m`: the load of the format's texels.
  // Half: level 0 holds 1/z itself (exact, as the linear march reads it; the range is
  // [1/z * farRatio, 1/z]), the coarser levels two halfs.
  template <TexelFormat T>
  static void fetchRange(const uint32_t* texels, I index, M m, M fine, F farRatio, const typename L::Table& table,
                         F& lo, F& hi) {
    if constexpr (T == TexelFormat::Float) {
      L::gatherPairs(texels, index, m, lo, hi);
    } else {
      const I t = T == TexelFormat::Half ? L::gatherTexels(texels, index, m) : L::lookup(table, index);
      const F u = L::asF(t);
      F lowHalf, highHalf;
      L::halfs(t, lowHalf, highHalf);
      lo = L::sel(fine, u * farRatio, lowHalf);
      hi = L::sel(fine, u, highHalf);
    }
  }

  // L::kLanes lanes, each a ray where trace_hiz's loop stands: t, its cell (cx, cy) of level `level`.
  struct Packet {
    F ix, nx, iy, ny, k0, dk, idk, t, result, dt, perDt;  // dt: the march's sample spacing
    I posX, posY, cx, cy, level, steps, slot;             // posX, posY: 1 where the ray goes to +x, +y
    M live, done;                                         // done: finished, result not yet written
  };

  template <TexelFormat T>
  static void traceBuffer(const MinMaxPyramid& pyr, int maxIterations, const RayBuffer& rays,
                          PacketCounters& counters) {
    const F farRatio = L::f(pyr.farRatio);
    int baseTable[kMaxPacketLevels] = {}, shiftTable[kMaxPacketLevels] = {};
    for (int l = 0; l < pyr.levelCount; ++l) {
      baseTable[l] = pyr.levels[l].base;
      shiftTable[l] = pyr.levels[l].shift;
    }
    const typename L::Table bases = L::table(baseTable), shifts = L::table(shiftTable);
    // NoMemory: 16 texels of level 0's middle row, looked up by the low bits of the index.
    typename L::Table texelTable{};
    if constexpr (T == TexelFormat::NoMemory) {
      const PyramidLevel& l0 = pyr.levels[0];
      int middle[16];  // within the pyramid however small the frame
      for (int k = 0; k < 16; ++k) {
        const size_t at = size_t(l0.base) + (size_t(l0.height / 2) << l0.shift) + size_t(l0.width / 2 + k);
        middle[k] = int(pyr.texels[at < pyr.words ? at : pyr.words - 1]);
      }
      texelTable = L::table(middle);
    }
    const I zeroI = L::i(0), one = L::i(1), lastLevel = L::i(pyr.levelCount - 1);
    const I maxSteps = L::i(maxIterations);
    const I lane = L::iota();
    const F zero = L::f(0.0f), oneF = L::f(1.0f), halfF = L::f(0.5f);
    const unsigned allLanes = (1u << L::kLanes) - 1;
    size_t next = 0;
    long long laneSteps = 0, packetSteps = 0, hits = 0;
    // One step of packet k, after its free lanes take new rays; false when it has none left.
    const auto advance = [&](Packet & k) __attribute__((always_inline)) {
      const unsigned liveBits = L::bits(k.live), freeLanes = ~liveBits & allLanes;
      const int nFree = __builtin_popcount(freeLanes);
      if (next < rays.count && (nFree >= L::kRefillAt || !liveBits)) {
        L::scatter(rays.tHit, k.done, k.slot, k.result);
        k.done = L::mask(0);
        const size_t take = rays.count - next < size_t(nFree) ? rays.count - next : size_t(nFree);
        const unsigned taken = take == size_t(nFree) ? freeLanes : _pdep_u32((1u << take) - 1, freeLanes);
        const M m = L::mask(taken);
        const typename L::Expand e = L::expander(taken);
        const auto in = [&](F old, int f) { return L::expandLoad(old, e, rays.field[f] + next); };
        k.ix = in(k.ix, kIx);
        k.nx = in(k.nx, kNx);
        k.iy = in(k.iy, kIy);
        k.ny = in(k.ny, kNy);
        k.k0 = in(k.k0, kK0);
        k.dk = in(k.dk, kDk);
        k.idk = in(k.idk, kIdk);
        k.t = in(k.t, kT0);
        k.cx = L::asI(in(L::asF(k.cx), kCx));
        k.cy = L::asI(in(L::asF(k.cy), kCy));
        k.slot = L::asI(L::expand(L::asF(k.slot), e, L::asF(L::add(lane, L::i(int(next))))));
        k.result = L::sel(m, L::f(-1.0f), k.result);
        k.level = L::sel(m, zeroI, k.level);
        k.steps = L::sel(m, zeroI, k.steps);
        // Half a pixel along the major axis: 0.5 / max(|ds.x|, |ds.y|) = 0.5 min(|ix|, |iy|).
        k.dt = L::sel(m, halfF * L::min(L::abs(k.ix), L::abs(k.iy)), k.dt);
        k.perDt = L::sel(m, oneF / k.dt, k.perDt);
        k.posX = L::sel(m, L::sel(gt(k.ix, zero), one, zeroI), k.posX);
        k.posY = L::sel(m, L::sel(gt(k.iy, zero), one, zeroI), k.posY);
        k.live = M(k.live | m);
        next += take;
      }
      const unsigned live = L::bits(k.live);
      if (!live) return false;
      ++packetSteps;
      laneSteps += __builtin_popcount(live);
      const F size = L::asF(L::template slli<23>(L::add(k.level, L::i(127))));
      // Where the ray leaves its cell, and its 1/z over the part of the cell it crosses.
      const F tx = L::fma(L::cvt(L::add(k.cx, k.posX)) * size, k.ix, k.nx);
      const F ty = L::fma(L::cvt(L::add(k.cy, k.posY)) * size, k.iy, k.ny);
      const F tExit = L::min(tx, ty), tEnd = L::min(tExit, oneF);
      const F u0 = L::fma(k.t, k.dk, k.k0), u1 = L::fma(tEnd, k.dk, k.k0);
      const F rayLo = L::min(u0, u1), rayHi = L::max(u0, u1);
      const I index = L::add(L::add(L::lookup(bases, k.level), L::sllv(k.cy, L::lookup(shifts, k.level))), k.cx);
      const M fine = L::eq(k.level, zeroI);
      F lo, hi;
      fetchRange<T>(pyr.texels, index, k.live, fine, farRatio, texelTable, lo, hi);
      const M meets = M(k.live & ge(rayHi, lo) & le(rayLo, hi));
      // Met: t moves on to where the ray's 1/z enters the range (trace.cl's tCross), within the cell.
      F enter = L::sel(gt(u0, hi), (hi - k.k0) * k.idk, k.t);
      enter = L::sel(lt(u0, lo), (lo - k.k0) * k.idk, enter);
      const F tMet = L::min(L::max(enter, k.t), tEnd);
      // A pixel is hit where a sample of the half-pixel march (t = (i + 1/2) dt) lies in its range: the
      // first sample from tMet on, before the ray leaves the range (towards the eye through its
      // near end, away through its far end) and the pixel.
      const F sample = (L::template round<_MM_FROUND_TO_POS_INF>(L::fms(tMet, k.perDt, halfF)) + halfF) * k.dt;
      const M nearer = gt(k.dk, zero);
      const M still = eq(k.dk, zero);
      const F leave = L::sel(still, tEnd, (L::sel(nearer, hi, lo) - k.k0) * k.idk);
      const M sampled = le(sample, L::min(leave, tEnd));
      const M hit = M(meets & fine & sampled), descend = M(meets & ~fine), skip = M(k.live & ~hit & ~descend);
      // Descending: the child holding the ray at tMet, by the t where it crosses the cell's middle.
      const I cx2 = L::add(k.cx, k.cx), cy2 = L::add(k.cy, k.cy);
      const F halfSize = size * halfF;
      const F midX = L::fma(L::cvt(L::add(cx2, one)) * halfSize, k.ix, k.nx);
      const F midY = L::fma(L::cvt(L::add(cy2, one)) * halfSize, k.iy, k.ny);
      // Past the middle along the ray: the upper child where the ray goes to +x, else the lower.
      const M pastX = ge(tMet, midX), pastY = ge(tMet, midY);
      const I childX = L::add(cx2, L::sel(pastX, k.posX, L::xor_(k.posX, one)));
      const I childY = L::add(cy2, L::sel(pastY, k.posY, L::xor_(k.posY, one)));
      // Skipping: the next cell along the ray, then its parent (one level up, as trace_hiz climbs).
      const M stepX = le(tx, ty);
      const I sx = L::sub(L::add(k.posX, k.posX), one), sy = L::sub(L::add(k.posY, k.posY), one);
      I nextX = L::sel(stepX, L::add(k.cx, sx), k.cx), nextY = L::sel(stepX, k.cy, L::add(k.cy, sy));
      // Up as many levels as the next cell has ancestors the current one does not share (the
      // highest bit in which their coordinates differ), at most kClimb: the parent of a sibling is
      // the cell just descended from, whose range the ray met (docs/BENCHMARKS.md, native roofline: one level into
      // another parent 11% fewer steps than always one up, two 6.6% fewer again, no cap more).
      const I differ = L::or_(L::xor_(nextX, k.cx), L::xor_(nextY, k.cy));
      const I up = L::min(L::climb(differ), L::sub(lastLevel, k.level));
      nextX = L::srav(nextX, up);
      nextY = L::srav(nextY, up);
      k.cx = L::sel(skip, nextX, L::sel(descend, childX, k.cx));
      k.cy = L::sel(skip, nextY, L::sel(descend, childY, k.cy));
      k.level = L::sel(descend, L::sub(k.level, one), L::sel(skip, L::add(k.level, up), k.level));
      k.t = L::sel(skip, tExit, L::sel(descend, tMet, k.t));
      k.result = L::sel(hit, sample, k.result);
      k.steps = L::sel(k.live, L::add(k.steps, one), k.steps);
      const M left = M(skip & gt(tExit, oneF));
      const M capped = M(k.live & L::ge(k.steps, maxSteps));
      const M finished = M(hit | left | capped);
      hits += __builtin_popcount(L::bits(hit));
      k.live = M(k.live & ~finished);
      k.done = M(k.done | finished);
      return true;
    };
    Packet packets[L::kPackets] = {};
    for (bool any = true; any;) {
      any = false;
      for (Packet& k : packets) any |= advance(k);
    }
    for (Packet& k : packets) L::scatter(rays.tHit, k.done, k.slot, k.result);
    counters.rays += (long long)rays.count;
    counters.hits += hits;
    counters.laneSteps += laneSteps;
    counters.packetSteps += packetSteps;
  }

  static void traceRows(const PacketFrame& frame, const MinMaxPyramid& pyramid, int samples, uint32_t seed, int y0,
                        int y1, float* hitPoints, PacketCounters& counters) {
    const size_t capacity = size_t(y1 - y0) * frame.width * size_t(samples > 0 ? samples : 1) + L::kLanes;
    float* storage = static_cast<float*>(std::aligned_alloc(64, (kFields + 1) * capacity * sizeof(float)));
    if (!storage) return;
    RayBuffer rays;
    for (int f = 0; f < kFields; ++f) rays.field[f] = storage + f * capacity;
    rays.tHit = storage + kFields * capacity;
    generateRays(frame, samples, seed, y0, y1, rays);
    for (size_t k = 0; k < rays.count; ++k) rays.tHit[k] = -1.0f;
    if (pyramid.format == TexelFormat::Half)
      traceBuffer<TexelFormat::Half>(pyramid, frame.maxIterations, rays, counters);
    if (pyramid.format == TexelFormat::Float)
      traceBuffer<TexelFormat::Float>(pyramid, frame.maxIterations, rays, counters);
    if (pyramid.format == TexelFormat::NoMemory)
      traceBuffer<TexelFormat::NoMemory>(pyramid, frame.maxIterations, rays, counters);
    if (hitPoints) {
      for (size_t i = 3 * size_t(y0) * frame.width; i < 3 * size_t(y1) * frame.width; ++i) hitPoints[i] = -1.0f;
      for (size_t k = 0; k < rays.count; ++k) {
        const float t = rays.tHit[k];
        if (!(t >= 0.0f)) continue;
        int pixel;
        __builtin_memcpy(&pixel, rays.field[kPixel] + k, 4);
        // x at t from t = x * ix + nx.
        float* out = hitPoints + 3 * size_t(pixel);
        out[0] = (t - rays.field[kNx][k]) / rays.field[kIx][k];
        out[1] = (t - rays.field[kNy][k]) / rays.field[kIy][k];
        out[2] = rays.field[kK0][k] + t * rays.field[kDk][k];
      }
    }
    std::free(storage);
  }
};

// The lane type's own operations against what each means lane by lane, over every mask and table
// index: nullptr, or the name of the first that differs (test_native_roofline). A wrong lane
// there moves only a few of the trace's hits (a level looked up wrong past level 7 moved 5 of
// ~9,000 at 320x180), too few for the hit tests to see.
template <class L>
const char* laneOpsError() {
  using F = typename L::F;
  using I = typename L::I;
  constexpr int n = L::kLanes;
  const auto floats = [](F v, float* out) { __builtin_memcpy(out, &v, sizeof v); };
  const auto ints = [](I v, int* out) { __builtin_memcpy(out, &v, sizeof v); };
  float iota[n], got[2 * n];
  int lanes[n];
  for (int k = 0; k < n; ++k) iota[k] = float(k);
  for (unsigned bits = 0; bits < (1u << n); ++bits) {
    if (L::bits(L::mask(bits)) != bits) return "mask / bits";
    floats(L::expand(L::f(-1.0f), L::expander(bits), L::cvt(L::iota())), got);
    for (int k = 0, next = 0; k < n; ++k)
      if (got[k] != ((bits >> k) & 1 ? float(next++) : -1.0f)) return "expand";
    floats(L::expandLoad(L::f(-1.0f), L::expander(bits), iota), got);
    for (int k = 0, next = 0; k < n; ++k)
      if (got[k] != ((bits >> k) & 1 ? float(next++) : -1.0f)) return "expandLoad";
    L::compressStore(got, L::compressor(bits), L::cvt(L::iota()));
    for (int k = 0, next = 0; k < n; ++k)
      if ((bits >> k) & 1 && got[next++] != float(k)) return "compressStore";
  }
  const auto fromInts = [](const int* in) {
    I v;
    __builtin_memcpy(&v, in, sizeof v);
    return v;
  };
  int values[16], index[n];
  for (int k = 0; k < 16; ++k) values[k] = 1000 + 7 * k;
  const typename L::Table table = L::table(values);
  for (int shift = 0; shift < 16; ++shift) {
    for (int k = 0; k < n; ++k) index[k] = (k + shift) & 15;
    ints(L::lookup(table, fromInts(index)), lanes);
    for (int k = 0; k < n; ++k)
      if (lanes[k] != values[(k + shift) & 15]) return "lookup";
  }
  for (uint64_t a = 1; a < (1ull << 31); a = a < 4096 ? a + 1 : a * 3 + 1) {
    ints(L::climb(L::add(L::iota(), L::i(int(a)))), lanes);
    for (int k = 0; k < n; ++k) {
      const unsigned v = unsigned(a) + unsigned(k);
      if (lanes[k] != imin(31 - __builtin_clz(v), 2)) return "climb";
    }
  }
  int packed[n];
  for (int k = 0; k < n; ++k)  // halfs k and 100 + k
    packed[k] = int(_cvtss_sh(float(k), 0) | unsigned(_cvtss_sh(100.0f + float(k), 0)) << 16);
  F lo, hi;
  L::halfs(fromInts(packed), lo, hi);
  floats(lo, got);
  floats(hi, got + n);
  for (int k = 0; k < n; ++k)
    if (got[k] != float(k) || got[n + k] != 100.0f + float(k)) return "halfs";
  return nullptr;
}
