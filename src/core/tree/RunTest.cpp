// The versions of the run pre-test (RunTest.h). Each computes, per candidate (a, b),
//   d2 = (x_a - x_b)^2 + (y_a - y_b)^2 + (z_a - z_b)^2,  c = (r_a + r_b + halo) scale,
// keeps b when d2 <= c^2 kRunTestMargin, and writes a and b at the next slot whatever the
// outcome, advancing the slot only when kept (no branch on the outcome: most candidates miss,
// in no predictable pattern).
#include "tree/RunTest.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define SPACETREE_RUN_TEST_X86 1
#endif

namespace spacetree {
namespace {

// a against the candidates [b, to) one by one (a run's tail).
inline std::int32_t testOneByOne(const RunTestParticles& p, std::int32_t a, std::int32_t b, std::int32_t to,
                                 std::int32_t* first, std::int32_t* second, std::int32_t q) {
  const double xa = p.x[a], ya = p.y[a], za = p.z[a], ra = p.r[a];
  for (; b < to; ++b) {
    const double dx = xa - p.x[b], dy = ya - p.y[b], dz = za - p.z[b];
    const double c = (ra + p.r[b] + p.halo) * p.scale;
    first[q] = a;
    second[q] = b;
    q += dx * dx + dy * dy + dz * dz <= c * c * kRunTestMargin ? 1 : 0;
  }
  return q;
}

std::int32_t testPortable(const RunTestParticles& p, std::int32_t aBegin, std::int32_t aEnd, const CandidateRun* runs,
                          int nRuns, bool triangle, std::int32_t* first, std::int32_t* second, std::int32_t q) {
  for (int run = 0; run < nRuns; ++run) {
    const std::int32_t from = runs[run].from, to = runs[run].to;
    const bool fromNext = run == 0 && triangle;
    for (std::int32_t a = aBegin; a < aEnd; ++a) {
      const double xa = p.x[a], ya = p.y[a], za = p.z[a], ra = p.r[a];
      std::int32_t b = fromNext ? a + 1 : from;
#ifdef __SSE2__
      // Two at a time: both slots are written, the second candidate over the first when the
      // first misses.
      const __m128d x2 = _mm_set1_pd(xa), y2 = _mm_set1_pd(ya), z2 = _mm_set1_pd(za), r2 = _mm_set1_pd(ra);
      const __m128d halo2 = _mm_set1_pd(p.halo), scale2 = _mm_set1_pd(p.scale), margin2 = _mm_set1_pd(kRunTestMargin);
      for (; b + 2 <= to; b += 2) {
        const __m128d dx = _mm_sub_pd(x2, _mm_loadu_pd(p.x + b)), dy = _mm_sub_pd(y2, _mm_loadu_pd(p.y + b)),
                      dz = _mm_sub_pd(z2, _mm_loadu_pd(p.z + b));
        const __m128d d2 = _mm_add_pd(_mm_add_pd(_mm_mul_pd(dx, dx), _mm_mul_pd(dy, dy)), _mm_mul_pd(dz, dz));
        const __m128d c = _mm_mul_pd(_mm_add_pd(_mm_add_pd(r2, _mm_loadu_pd(p.r + b)), halo2), scale2);
        const int kept = _mm_movemask_pd(_mm_cmple_pd(d2, _mm_mul_pd(_mm_mul_pd(c, c), margin2)));
        first[q] = a;
        first[q + 1] = a;
        second[q] = b;
        second[q + (kept & 1)] = b + 1;
        q += (kept & 1) + (kept >> 1);
      }
#endif
      q = testOneByOne(p, a, b, to, first, second, q);
    }
  }
  return q;
}

#ifdef SPACETREE_RUN_TEST_X86
// Four at a time (AVX2, where the processor has no AVX-512): a is written to all four slots,
// each candidate at the next slot, which advances only when it is kept (AVX2 has no
// compress-store); the run's tail goes one by one.
__attribute__((target("avx2"))) std::int32_t testAvx2(const RunTestParticles& p, std::int32_t aBegin, std::int32_t aEnd,
                                                      const CandidateRun* runs, int nRuns, bool triangle,
                                                      std::int32_t* first, std::int32_t* second, std::int32_t q) {
  const __m256d halo4 = _mm256_set1_pd(p.halo), scale4 = _mm256_set1_pd(p.scale),
                margin4 = _mm256_set1_pd(kRunTestMargin);
  for (int run = 0; run < nRuns; ++run) {
    const std::int32_t from = runs[run].from, to = runs[run].to;
    const bool fromNext = run == 0 && triangle;
    for (std::int32_t a = aBegin; a < aEnd; ++a) {
      const double xa = p.x[a], ya = p.y[a], za = p.z[a], ra = p.r[a];
      const __m256d x4 = _mm256_set1_pd(xa), y4 = _mm256_set1_pd(ya), z4 = _mm256_set1_pd(za), r4 = _mm256_set1_pd(ra);
      const __m128i a4 = _mm_set1_epi32(a);
      std::int32_t b = fromNext ? a + 1 : from;
      for (; b + 4 <= to; b += 4) {
        const __m256d dx = _mm256_sub_pd(x4, _mm256_loadu_pd(p.x + b)), dy = _mm256_sub_pd(y4, _mm256_loadu_pd(p.y + b)),
                      dz = _mm256_sub_pd(z4, _mm256_loadu_pd(p.z + b));
        const __m256d d2 =
            _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)), _mm256_mul_pd(dz, dz));
        const __m256d c = _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(r4, _mm256_loadu_pd(p.r + b)), halo4), scale4);
        const int kept = _mm256_movemask_pd(_mm256_cmp_pd(d2, _mm256_mul_pd(_mm256_mul_pd(c, c), margin4), _CMP_LE_OQ));
        _mm_storeu_si128(reinterpret_cast<__m128i*>(first + q), a4);
        second[q] = b;
        q += kept & 1;
        second[q] = b + 1;
        q += (kept >> 1) & 1;
        second[q] = b + 2;
        q += (kept >> 2) & 1;
        second[q] = b + 3;
        q += kept >> 3;
      }
      q = testOneByOne(p, a, b, to, first, second, q);
    }
  }
  return q;
}

// Eight at a time: masked loads past the run's end (nothing read there), the kept positions
// compress-stored; a is written to all eight slots. A run of at most eight against several a
// (a row of a vertex's forward neighbours) is loaded once.
__attribute__((target("avx512f,avx512vl"))) std::int32_t testAvx512(const RunTestParticles& p, std::int32_t aBegin,
                                                                    std::int32_t aEnd, const CandidateRun* runs,
                                                                    int nRuns, bool triangle, std::int32_t* first,
                                                                    std::int32_t* second, std::int32_t q) {
  const double *x = p.x, *y = p.y, *z = p.z, *r = p.r;
  const __m512d halo8 = _mm512_set1_pd(p.halo), scale8 = _mm512_set1_pd(p.scale),
                margin8 = _mm512_set1_pd(kRunTestMargin);
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  auto within = [&](std::int32_t a, __m512d bx, __m512d by, __m512d bz, __m512d br, __mmask8 valid)
                    __attribute__((target("avx512f,avx512vl"))) {
    const __m512d dx = _mm512_sub_pd(_mm512_set1_pd(x[a]), bx), dy = _mm512_sub_pd(_mm512_set1_pd(y[a]), by),
                  dz = _mm512_sub_pd(_mm512_set1_pd(z[a]), bz);
    const __m512d d2 = _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)), _mm512_mul_pd(dz, dz));
    const __m512d c = _mm512_mul_pd(_mm512_add_pd(_mm512_add_pd(_mm512_set1_pd(r[a]), br), halo8), scale8);
    return _mm512_mask_cmp_pd_mask(valid, d2, _mm512_mul_pd(_mm512_mul_pd(c, c), margin8), _CMP_LE_OQ);
  };
  auto keep = [&](std::int32_t a, std::int32_t b, __mmask8 kept) __attribute__((target("avx512f,avx512vl"))) {
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(first + q), _mm256_set1_epi32(a));
    _mm256_mask_compressstoreu_epi32(second + q, kept, _mm256_add_epi32(_mm256_set1_epi32(b), lane));
    q += __builtin_popcount(unsigned(kept));
  };
  auto validUpTo = [](std::int32_t n) { return n >= 8 ? __mmask8(0xff) : __mmask8((1u << n) - 1u); };
  for (int run = 0; run < nRuns; ++run) {
    const std::int32_t from = runs[run].from, to = runs[run].to;
    const bool fromNext = run == 0 && triangle;
    if (!fromNext && to - from <= 8) {
      const __mmask8 valid = validUpTo(to - from);
      const __m512d bx = _mm512_maskz_loadu_pd(valid, x + from), by = _mm512_maskz_loadu_pd(valid, y + from),
                    bz = _mm512_maskz_loadu_pd(valid, z + from), br = _mm512_maskz_loadu_pd(valid, r + from);
      for (std::int32_t a = aBegin; a < aEnd; ++a) keep(a, from, within(a, bx, by, bz, br, valid));
      continue;
    }
    for (std::int32_t a = aBegin; a < aEnd; ++a)
      for (std::int32_t b = fromNext ? a + 1 : from; b < to; b += 8) {
        const __mmask8 valid = validUpTo(to - b);
        keep(a, b,
             within(a, _mm512_maskz_loadu_pd(valid, x + b), _mm512_maskz_loadu_pd(valid, y + b),
                    _mm512_maskz_loadu_pd(valid, z + b), _mm512_maskz_loadu_pd(valid, r + b), valid));
      }
  }
  return q;
}
#endif

}  // namespace

RunTest portableRunTest() { return &testPortable; }

RunTest avx512RunTest() {
#ifdef SPACETREE_RUN_TEST_X86
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl")) return &testAvx512;
#endif
  return nullptr;
}

RunTest avx2RunTest() {
#ifdef SPACETREE_RUN_TEST_X86
  if (__builtin_cpu_supports("avx2")) return &testAvx2;
#endif
  return nullptr;
}

RunTest selectedRunTest() {
  static const RunTest selected = [] {
    if (const RunTest fast = avx512RunTest()) return fast;
    if (const RunTest avx2 = avx2RunTest()) return avx2;
    return portableRunTest();
  }();
  return selected;
}

}  // namespace spacetree
