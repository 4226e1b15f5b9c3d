// The packet trace in 8 AVX2 lanes, for CPUs without AVX-512. Compiled with -march=x86-64-v3
// (CMakeLists.txt): called only where packetTraceIsa() is Avx2. No standard-library templates
// here (see the header): what this file instantiates would be AVX2 code other files might link to.
#include <immintrin.h>

#include <cstdlib>

#include "packet_hiz_trace.hpp"

namespace ssrcl::bench {
namespace {

#include "packet_hiz_trace.inl"

// The lane operations packet_hiz_trace.inl needs: masks are vectors of 0 or -1 a lane.
struct Avx2 {
  using M = __m256i;
  SSRCL_PACKET_LANE_OPS(256)

  template <int P>
  static F round(F a) {
    return _mm256_round_ps(a, P | _MM_FROUND_NO_EXC);
  }
  // min(index of the highest bit set, 2), 0 for 0 (no vplzcntd): 2 less one for each of "no bit
  // above bit 0" and "none above bit 1", as unsigned.
  static_assert(kClimb == 2, "climb caps at 2 levels");
  static I climb(I a) {
    const I zero = _mm256_setzero_si256();
    return add(add(i(2), _mm256_cmpeq_epi32(_mm256_and_si256(a, i(~1)), zero)),
               _mm256_cmpeq_epi32(_mm256_and_si256(a, i(~3)), zero));
  }
  template <int P>
  static M cmp(F a, F b) {
    return asI(_mm256_cmp_ps(a, b, P));
  }
  static M eq(I a, I b) { return _mm256_cmpeq_epi32(a, b); }
  static M ge(I a, I b) { return _mm256_xor_si256(_mm256_cmpgt_epi32(b, a), i(-1)); }
  static F sel(M m, F a, F b) { return _mm256_blendv_ps(b, a, asF(m)); }  // a where m, else b
  static I sel(M m, I a, I b) { return asI(sel(m, asF(a), asF(b))); }
  static unsigned bits(M m) { return unsigned(_mm256_movemask_ps(asF(m))); }
  static M mask(unsigned bits) {
    const I bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    return _mm256_cmpeq_epi32(_mm256_and_si256(i(int(bits)), bit), bit);
  }
  // Bits of the first n (<= 8) bytes at p that are not 0.
  static unsigned nonzeroBytes(const unsigned char* p, int n) {
    unsigned b = 0;
    for (int k = 0; k < n; ++k) b |= unsigned(p[k] != 0) << k;
    return b;
  }
  static F gather(const float* base, I index, M m) {
    return _mm256_mask_i32gather_ps(_mm256_setzero_ps(), base, index, asF(m), 4);
  }
  // Eight loads, not vpgatherdd: Zen 3's gather is slow (eight loads: 0-8% faster a trace). Idle
  // lanes read word 0 (texel (-1, -1) of level 0: zero, a border texel).
  static I gatherTexels(const uint32_t* texels, I index, M m) {
    alignas(32) int at[kLanes];
    _mm256_store_si256(reinterpret_cast<I*>(at), _mm256_and_si256(index, m));
    return _mm256_setr_epi32(texels[at[0]], texels[at[1]], texels[at[2]], texels[at[3]], texels[at[4]], texels[at[5]],
                             texels[at[6]], texels[at[7]]);
  }
  // The 8-byte texels of `index`: their first and second floats.
  static void gatherPairs(const uint32_t* texels, I index, M m, F& lo, F& hi) {
    const auto* t = reinterpret_cast<const long long*>(texels);
    const I a = _mm256_mask_i32gather_epi64(_mm256_setzero_si256(), t, _mm256_castsi256_si128(index),
                                            _mm256_cvtepi32_epi64(_mm256_castsi256_si128(m)), 8);
    const I b = _mm256_mask_i32gather_epi64(_mm256_setzero_si256(), t, _mm256_extracti128_si256(index, 1),
                                            _mm256_cvtepi32_epi64(_mm256_extracti128_si256(m, 1)), 8);
    // Within 128-bit halves: texels 0 1 4 5 | 2 3 6 7, put in order by 64-bit quarters.
    lo = _mm256_castpd_ps(_mm256_permute4x64_pd(
        _mm256_castps_pd(_mm256_shuffle_ps(asF(a), asF(b), _MM_SHUFFLE(2, 0, 2, 0))), _MM_SHUFFLE(3, 1, 2, 0)));
    hi = _mm256_castpd_ps(_mm256_permute4x64_pd(
        _mm256_castps_pd(_mm256_shuffle_ps(asF(a), asF(b), _MM_SHUFFLE(3, 1, 3, 1))), _MM_SHUFFLE(3, 1, 2, 0)));
  }
  // The low and high 16 bits of each lane as halfs: gathered into 128-bit halves, then converted.
  static void halfs(I t, F& lo, F& hi) {
    const I split = _mm256_shuffle_epi8(t, _mm256_setr_epi8(0, 1, 4, 5, 8, 9, 12, 13, 2, 3, 6, 7, 10, 11, 14, 15, 0, 1,
                                                            4, 5, 8, 9, 12, 13, 2, 3, 6, 7, 10, 11, 14, 15));
    const I ordered = _mm256_permute4x64_epi64(split, _MM_SHUFFLE(3, 1, 2, 0));
    lo = _mm256_cvtph_ps(_mm256_castsi256_si128(ordered));
    hi = _mm256_cvtph_ps(_mm256_extracti128_si256(ordered, 1));
  }
  // 16 ints looked up by the low 4 bits of an index: bit 3 (shifted to the sign) picks the half.
  struct Table {
    I low, high;
  };
  static Table table(const int* values) {
    return {_mm256_loadu_si256(reinterpret_cast<const I*>(values)),
            _mm256_loadu_si256(reinterpret_cast<const I*>(values + 8))};
  }
  static I lookup(const Table& t, I index) {
    return sel(slli<28>(index), _mm256_permutevar8x32_epi32(t.high, index), _mm256_permutevar8x32_epi32(t.low, index));
  }
  // Lane indices, a byte each, of the set bits of `bits` packed low (compress) or spread to
  // them (expand): BMI2 on the 8-byte identity, whose bytes are lanes 0 to 7. No slower than a
  // table or a loop on Zen 3; Zen 1 and 2 run pdep / pext in microcode (not measured there).
  static uint64_t laneBytes(unsigned bits) { return _pdep_u64(bits, 0x0101010101010101ull) * 0xff; }
  static I byteLanes(uint64_t lanes) { return _mm256_cvtepu8_epi32(_mm_cvtsi64_si128((long long)lanes)); }
  // The lanes of a bit mask filled from consecutive floats, in order.
  struct Expand {
    I from;
    M m;
  };
  static Expand expander(unsigned bits) {
    return {byteLanes(_pdep_u64(0x0706050403020100ull, laneBytes(bits))), mask(bits)};
  }
  static F expand(F old, const Expand& e, F from) { return sel(e.m, _mm256_permutevar8x32_ps(from, e.from), old); }
  // Reads 8 floats from p whichever lanes take them (the ray buffer has room).
  static F expandLoad(F old, const Expand& e, const float* p) { return expand(old, e, _mm256_loadu_ps(p)); }
  // The lanes of a bit mask stored to consecutive floats, in order; writes 8 floats at p (the
  // ray buffer has room; the next rays overwrite the rest).
  using Compress = I;
  static Compress compressor(unsigned bits) { return byteLanes(_pext_u64(0x0706050403020100ull, laneBytes(bits))); }
  static void compressStore(float* p, Compress from, F v) { _mm256_storeu_ps(p, _mm256_permutevar8x32_ps(v, from)); }
  static void scatter(float* p, M m, I index, F v) {
    alignas(32) int at[kLanes];
    alignas(32) float value[kLanes];
    _mm256_store_si256(reinterpret_cast<I*>(at), index);
    _mm256_store_ps(value, v);
    for (unsigned b = bits(m); b; b &= b - 1) {
      const int k = __builtin_ctz(b);
      p[at[k]] = value[k];
    }
  }
  // Refilled once 4 lanes are free (2 or 3: no faster); 2 packets a thread (1: 10-20% slower; 3:
  // 5-14% slower, as a step's vectors outgrow the 16 registers). Measured on Zen 3, 1920x1080.
  static constexpr int kRefillAt = 4, kPackets = 2;
};

}  // namespace

void tracePacketRowsAvx2(const PacketFrame& frame, const MinMaxPyramid& pyramid, int samples, uint32_t seed, int y0,
                         int y1, float* hitPoints, PacketCounters& counters) {
  Lanes<Avx2>::traceRows(frame, pyramid, samples, seed, y0, y1, hitPoints, counters);
}

const char* packetLaneOpsErrorAvx2() { return laneOpsError<Avx2>(); }

}  // namespace ssrcl::bench
