// Pre-test of candidate runs for the within-cut-off sweep (Spacetree::WithinVisitor): each
// particle a of [aBegin, aEnd) (a vertex) against runs of contiguous sorted positions (its own
// particles after a, and each forward row's three neighbouring vertices), keeping
// the pairs whose squared distance is at most kRunTestMargin times the squared cut-off
// ((r_a + r_b + halo) scale)^2. The kept pairs are appended, a-major and in position order, to
// the visitor's queue (first, second), whose flush then decides each pair with the exact
// cut-off; the margin makes the kept pairs a superset of the flush's whatever the rounding or
// fused multiply-adds of either side, so the pairs visited do not depend on which version ran.
//
// On a level with several particles per vertex (a row's three neighbouring vertices hold 5-20
// particles) most candidates come in such runs and most miss: testing a run where it is found,
// with a's coordinates held and the run's loaded contiguously, saves queueing every candidate
// and gathering its coordinates again. Versions: two candidates at a time (SSE2, every x86-64)
// and, chosen at run time by what the processor has, four at a time with AVX2 or eight with
// AVX-512 (masked loads for the tail, compress-store of the kept positions).
#pragma once

#include <cstdint>

namespace spacetree {

// The sorted arrays the runs index (structure of arrays: centres and radii).
struct RunTestParticles {
  const double *x, *y, *z, *r;
  double halo, scale;  // the cut-off of (a, b) is (r_a + r_b + halo) scale
};

// Relative margin of the pre-test over the squared cut-off.
constexpr double kRunTestMargin = 1.0 + 1e-12;
// Slots a test may write beyond the last kept pair (the queue must have this much slack).
constexpr std::int32_t kRunTestSlack = 8;

// Contiguous candidate positions [from, to).
struct CandidateRun {
  std::int32_t from, to;
};

// Tests a in [aBegin, aEnd) against each run in turn (run-major, then a, then position; the
// first run as a triangle when `triangle`: [a + 1, to)) and writes the kept pairs to first[q..],
// second[q..]; returns q plus their count. The caller guarantees room for every candidate
// plus kRunTestSlack slots.
using RunTest = std::int32_t (*)(const RunTestParticles& p, std::int32_t aBegin, std::int32_t aEnd,
                                 const CandidateRun* runs, int nRuns, bool triangle, std::int32_t* first,
                                 std::int32_t* second, std::int32_t q);

// The fastest version this processor runs (chosen once).
RunTest selectedRunTest();
// Each version, for tests: the portable one always, the AVX2 and AVX-512 ones only where the
// processor has AVX2 / AVX-512F+VL (else nullptr).
RunTest portableRunTest();
RunTest avx2RunTest();
RunTest avx512RunTest();

}  // namespace spacetree
