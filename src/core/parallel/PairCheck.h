// The per-pair work a sweep hands to tasks: compare the triangles of two particles and report
// the contacts. The engine (TaskParallelPairChecks) only needs how many triangles a particle has
// (to size tasks and split big pairs at triangle level) and the check of a row range of the
// first particle's triangles against all of the second's.
#pragma once

#include <cstddef>

#include "parallel/TriangleContact.h"

namespace spacetree::parallel {

class PairCheck {
 public:
  virtual ~PairCheck() = default;

  // Triangles of a particle; a pair's work is triangleCount(first) * triangleCount(second).
  virtual std::size_t triangleCount(int particle) const = 0;

  // Whether check() may be called on row ranges. A check whose result for a pair is more than
  // the union of its triangle pairs (e.g. contact de-duplication across the pair) says false and
  // always gets whole pairs [0, triangleCount(first)).
  virtual bool splittable() const { return true; }

  // Compares triangles [firstBegin, firstEnd) of `first` with every triangle of `second`
  // (first < second) and adds one TriangleContact per triangle pair in contact to the sink.
  // Called concurrently from several threads on different pairs or row ranges: it must not
  // modify shared state, and its result must depend only on its arguments (determinism).
  virtual void check(int first, int second, std::size_t firstBegin, std::size_t firstEnd,
                     ContactSink& sink) const = 0;
};

}  // namespace spacetree::parallel
