// Reluctant coarsening spares a cool cell that the refinement criterion would refine again at
// once: for a pair of this refinement pass (the caller's sweep, or the grid's own search) one
// partner is hosted at a vertex of the cell's children, would sit on the cell's level once it
// is removed, and the criterion holds for it there (it would drop, the partner is held by its
// cell, they approach). Removing such a cell and refining it at the next pass only lifts and
// drops the same particles and shocks the same vertices again. Without this an approaching
// pair far from others had its cells removed and refined again every two or three updates
// (markers of 1-particle vertices settle at 1-2, below the threshold 4).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "tree/RefinedCells.h"
#include "tree/VertexCounters.h"

namespace spacetree {

class SpareCheck {
 public:
  // What one coarsening pass checks against. Valid from begin() to end().
  struct Pass {
    const RefinedCells* cells = nullptr;
    double epsilon = 0.0;
    const double (*x)[3] = nullptr;  // nullptr: nothing is spared
    const double (*v)[3] = nullptr;  // nullptr: every pair approaches
    const double* radius = nullptr;
    const int* host = nullptr;        // host and admissible level per particle
    const int* admissible = nullptr;
    int n = 0;
    const int* first = nullptr;       // the pass's pairs: (first[k], second[k]), k < count, ...
    const int* second = nullptr;
    std::size_t count = 0;
    const std::vector<std::pair<int, int>>* closePairs = nullptr;  // ... or these when first is null
    // Particles per host vertex (per level: vertex -> first particle + 1, then next per
    // particle) where the caller tracks them; else built from the hosts when first needed.
    const std::vector<VertexCounters>* firstAtVertex = nullptr;
    const std::vector<int>* nextAtVertex = nullptr;
  };
  void begin(const Pass& pass);
  void end() { begin(Pass{}); }

  // Whether the refined cell `cellKey` of `level`, removable by the tree grammar, is spared.
  bool wouldRefineAgain(int level, std::uint64_t cellKey);
  // Cells spared, to be re-examined by the next incremental coarsening (the criterion may no
  // longer hold then).
  std::vector<LevelCell>& sparedCells() { return spared_; }

 private:
  Pass pass_;
  bool indexed_ = false;       // partners_ built (on the first cell that needs them)
  bool hostsIndexed_ = false;  // scratch particle lists built (untracked hosts)
  std::vector<int> partnerStart_, partners_;  // partners per particle (CSR), both directions
  std::vector<VertexCounters> scratchFirstAt_;
  std::vector<int> scratchNextAt_;
  std::vector<LevelCell> spared_;

  void indexPartners();
  void indexHosts();
};

}  // namespace spacetree
