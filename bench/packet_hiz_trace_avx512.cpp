// The packet trace in 16 AVX-512 lanes. Compiled with -march=x86-64-v4 (CMakeLists.txt): called
// only where packetTraceIsa() is Avx512. No standard-library templates here (see the header):
// what this file instantiates would be AVX-512 code other files might link to.
#include "packet_hiz_trace.hpp"

// GCC 12 warns of the undefined vectors its own intrinsics start from (GCC bug 105593).
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#include <immintrin.h>

#include <cstdlib>

namespace ssrcl::bench {
namespace {

#include "packet_hiz_trace.inl"

// The lane operations packet_hiz_trace.inl needs: masks are AVX-512 mask registers.
struct Avx512 {
  // Refilled once 4 lanes are free; 3 packets a thread (2: 1.2-1.5x over 1; 3: a little more;
  // docs/BENCHMARKS.md, native roofline).
  static constexpr int kRefillAt = 4, kPackets = 3;
  using M = __mmask16;
  SSRCL_PACKET_LANE_OPS(512)

  template <int P>
  static F round(F a) {
    return _mm512_roundscale_ps(a, P);
  }
  // min(index of the highest bit set, 2).
  static_assert(kClimb == 2, "climb caps at 2 levels");
  // min(index of the highest bit set, 2); -1 for 0, which a skipping lane never has (its next cell differs).
  static I climb(I a) { return _mm512_min_epi32(_mm512_sub_epi32(i(31), _mm512_lzcnt_epi32(a)), i(2)); }
  template <int P>
  static M cmp(F a, F b) {
    return _mm512_cmp_ps_mask(a, b, P);
  }
  static M eq(I a, I b) { return _mm512_cmpeq_epi32_mask(a, b); }
  static M ge(I a, I b) { return _mm512_cmpge_epi32_mask(a, b); }
  static F sel(M m, F a, F b) { return _mm512_mask_mov_ps(b, m, a); }  // a where m, else b
  static I sel(M m, I a, I b) { return _mm512_mask_mov_epi32(b, m, a); }
  static unsigned bits(M m) { return m; }
  static M mask(unsigned bits) { return M(bits); }
  // Bits of the first n (<= 16) bytes at p that are not 0.
  static unsigned nonzeroBytes(const unsigned char* p, int n) {
    const __m128i b = _mm_maskz_loadu_epi8(__mmask16((1u << n) - 1), p);
    return _mm512_test_epi32_mask(_mm512_cvtepu8_epi32(b), i(0xff));
  }
  static F gather(const float* base, I index, M m) {
    return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), m, index, base, 4);
  }
  static I gatherTexels(const uint32_t* texels, I index, M m) {
    return _mm512_mask_i32gather_epi32(_mm512_setzero_si512(), m, index, texels, 4);
  }
  // The 8-byte texels of `index`: their first and second floats.
  static void gatherPairs(const uint32_t* texels, I index, M m, F& lo, F& hi) {
    const I a =
        _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), __mmask8(m), _mm512_castsi512_si256(index), texels, 8);
    const I b = _mm512_mask_i32gather_epi64(_mm512_setzero_si512(), __mmask8(m >> 8),
                                            _mm512_extracti64x4_epi64(index, 1), texels, 8);
    const I even = _mm512_setr_epi32(0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30);
    lo = _mm512_castsi512_ps(_mm512_permutex2var_epi32(a, even, b));
    hi = _mm512_castsi512_ps(_mm512_permutex2var_epi32(a, add(even, i(1)), b));
  }
  // The low and high 16 bits of each lane as halfs.
  static void halfs(I t, F& lo, F& hi) {
    lo = _mm512_cvtph_ps(_mm512_cvtepi32_epi16(t));
    hi = _mm512_cvtph_ps(_mm512_cvtepi32_epi16(srli<16>(t)));
  }
  // 16 ints looked up by the low 4 bits of an index.
  using Table = I;
  static Table table(const int* values) { return _mm512_loadu_si512(values); }
  static I lookup(const Table& t, I index) { return _mm512_permutexvar_epi32(index, t); }
  // The lanes of a bit mask filled from consecutive floats, in order.
  using Expand = M;
  static Expand expander(unsigned bits) { return M(bits); }
  static F expandLoad(F old, Expand m, const float* p) { return _mm512_mask_expandloadu_ps(old, m, p); }
  static F expand(F old, Expand m, F from) { return _mm512_mask_expand_ps(old, m, from); }
  // The lanes of a bit mask stored to consecutive floats, in order.
  using Compress = M;
  static Compress compressor(unsigned bits) { return M(bits); }
  static void compressStore(float* p, Compress m, F v) { _mm512_mask_compressstoreu_ps(p, m, v); }
  static void scatter(float* p, M m, I index, F v) { _mm512_mask_i32scatter_ps(p, m, index, v, 4); }
};

}  // namespace

void tracePacketRowsAvx512(const PacketFrame& frame, const MinMaxPyramid& pyramid, int samples, uint32_t seed, int y0,
                           int y1, float* hitPoints, PacketCounters& counters) {
  Lanes<Avx512>::traceRows(frame, pyramid, samples, seed, y0, y1, hitPoints, counters);
}

const char* packetLaneOpsErrorAvx512() { return laneOpsError<Avx512>(); }

}  // namespace ssrcl::bench
