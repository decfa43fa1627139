// Persistent dynamically adaptive spacetree grid (paper §5.1). It keeps the refined cells of
// every level from step to step and decides on which level each particle is hosted; the
// Spacetree sweep then runs on those levels (Spacetree::build with geometry() and
// hostLevels()). The sweep is exact for any host level at or coarser than the finest one a
// particle fits, so adaptivity only trades cells against comparisons, never correctness.
//
// Host level: descend from the root while the cell containing the particle centre is refined
// and the next level still fits the particle (h >= 2(r + eps)); then lift while the nearest
// vertex on that level is hanging (not all 2^d adjacent cells exist).
//
// Levels above regularDepth are refined everywhere and never stored: for Regular that is the
// finest level any particle fits (today's placement); for Adaptive and Reluctant it is the
// paper's start-off grid, the finest level the biggest particle fits. Below it refined cells
// are kept sparsely in one hash set per level.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "tree/AdaptiveGridStatistics.h"
#include "tree/GridGeometry.h"
#include "tree/GridType.h"
#include "tree/Spacetree.h"
#include "tree/VertexCounters.h"
#include "tree/VertexKey.h"
#include "tree/VertexKeySet.h"

namespace spacetree {

struct AdaptiveGridOptions {
  GridType type = GridType::Adaptive;
  double epsilon = 0.0;             // halo, as in SpacetreeOptions
  int maxLevel = kMaxSpacetreeLevel;
  int shock = 8;                    // heat added to vertices created by a refinement (reluctant)
  int coarseningThreshold = 4;      // a cooler vertex may be coarsened (reluctant); < shock
  double padding = 0.25;            // cube margin per side, relative to the particle extent
  // Reluctant only: the caller reports the close pairs its own sweep found (refineForPairs)
  // instead of update() searching them with a second sweep.
  bool pairsFromCaller = false;
  // Adaptive and reluctant: the persistent grid re-hosts only particles whose host may have
  // changed since the last update and coarsens only around the vertices that stopped being
  // kept (kept-vertex counters instead of re-deriving the tree grammar from every particle);
  // the reluctant grid anneals only the heat markers whose inputs changed or that have not
  // converged yet. The result is the grid (cells, markers, hosts) a full update gives
  // (tested); false forces the full update.
  bool incremental = true;
};

class AdaptiveGrid {
 public:
  // Throws std::invalid_argument for inconsistent options (threshold >= shock, ...).
  explicit AdaptiveGrid(AdaptiveGridOptions options = {});

  // One step: re-host the moved particles, refine, coarsen, re-host (reluctant with
  // pairsFromCaller: re-host and anneal; refineForPairs refines and coarsens). Velocities drive the
  // reluctant approach test (v may be nullptr: every close pair then counts as approaching).
  // The cube is re-chosen (grid reset to the start-off grid) when a particle leaves it or no
  // longer fits the root cell.
  void update(const double (*x)[3], const double (*v)[3], const double* radius, int n);

  // Reluctant grid with pairsFromCaller: refines for the pairs (first[k], second[k]) that the
  // sweep on this step's tree found (bounding spheres + eps overlap), keeping those that
  // approach (v may be nullptr), then coarsens (cool cells, except those the criterion would
  // refine again at once for these pairs). This is what the paper triggers from inside the
  // traversal; particles drop into the new cells and lift out of the removed ones at once
  // (hosts re-derived). x must be the positions of the last update(). With pairsFromCaller,
  // update() does not coarsen: call this after every update().
  void refineForPairs(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                      const int* first, const int* second, std::size_t count);

  // Builds `tree` on this grid's cube with this grid's host levels (tree options must use the
  // same epsilon). Particles must be those of the last update().
  void buildSpacetree(Spacetree& tree, const double (*x)[3], const double* radius, int n,
                      int nActive) const;

  const AdaptiveGridOptions& options() const { return options_; }
  const GridGeometry& geometry() const { return geometry_; }
  const std::vector<int>& hostLevels() const { return host_; }
  int hostLevel(int particle) const { return host_[particle]; }
  int admissibleLevel(int particle) const { return admissible_[particle]; }
  double meshSize(int level) const;
  // Whether the cell of `level` containing point p is refined.
  bool isRefinedAt(int level, const double p[3]) const;
  const AdaptiveGridStatistics& statistics() const { return stats_; }

  // Leaf cells (cells that exist and are not refined), for output: f(level, i, j, k) with the
  // cell's integer coordinates on its level (lower corner origin + (i, j, k) h(level)).
  template <class F>
  void forEachLeafCell(F&& f) const;
  std::uint64_t leafCellCount() const;
  // Non-hanging vertices per level (index = level, as statistics().levels); computed on
  // request, not per update.
  std::vector<std::uint64_t> verticesPerLevel() const;

  // Restart: everything the grid keeps between updates that changes later updates (options,
  // cube, refined cells per level, reluctant heat markers, the cumulative reset count) as a
  // flat word list; doubles are stored bit-exact, sets in ascending key order, so a restored
  // grid's next updates equal the original's. Per-particle hosts are not stored: they are
  // recomputed by update(), which must come before the next buildSpacetree().
  std::vector<std::int64_t> serialise() const;
  // Inverse of serialise(). Throws std::invalid_argument for data that serialise() cannot
  // have written (wrong magic/version, truncated, inconsistent sizes or levels).
  static AdaptiveGrid deserialise(const std::int64_t* words, std::size_t count);
  // The stored state under other options: shock, threshold, padding and pairsFromCaller only
  // steer later updates and may differ; the type and epsilon must equal the stored ones and
  // the stored depth must not exceed options.maxLevel (else std::invalid_argument).
  static AdaptiveGrid deserialise(const std::int64_t* words, std::size_t count,
                                  const AdaptiveGridOptions& options);
  // The options stored in serialised data (same checks on the header as deserialise()).
  static AdaptiveGridOptions serialisedOptions(const std::int64_t* words, std::size_t count);

 private:
  // Heat markers sum their children's markers (up to 343 per vertex per level): saturate
  // instead of overflowing; anything this hot vetoes coarsening anyway.
  static constexpr std::int64_t kMaxHeat = std::int64_t(1) << 40;
  using CellSet = VertexKeySet;  // open addressing: look-ups dominate the update
  using Markers = VertexCounters;
  using KeySet = VertexKeySet;
  struct Index3 {
    std::int64_t i, j, k;
  };

  bool needsNewGeometry(const double (*x)[3], const double* radius, int n) const;
  void chooseGeometry(const double (*x)[3], const double* radius, int n);
  void cacheMeshSizes();  // meshSize_ / inverseMeshSize_ of geometry_
  int finestFit(double required) const;
  std::int64_t cellsPerAxis(int level) const { return kPowersOfThree[level]; }
  Index3 cellOf(int level, const double p[3]) const;
  Index3 nearestVertex(int level, const double p[3]) const;
  bool isRefined(int level, std::int64_t i, std::int64_t j, std::int64_t k) const;
  bool cellExists(int level, std::int64_t i, std::int64_t j, std::int64_t k) const;
  bool isHanging(int level, std::int64_t i, std::int64_t j, std::int64_t k) const;
  int computeHost(const double p[3], int admissible) const;
  // computeHost, also giving the level where the descent stopped (before the lifts).
  int hostPath(const double p[3], int admissible, int& descent) const;
  void rehostAll(const double (*x)[3], int n);
  bool refineCell(int level, std::int64_t i, std::int64_t j, std::int64_t k);
  bool refineAroundVertex(int level, const Index3& v);
  void refineNaively(const double (*x)[3], int n);
  void searchClosePairs(const double (*x)[3], const double (*v)[3], const double* radius, int n);
  void refineForClosePairs(const double (*x)[3], const double* radius, int n);
  // A coarser particle at q is virtual on a vertex of cell c of `level`: within its radius
  // + 2 eps + h sqrt(3) of one of the cell's 2^d corners (the reluctant criterion's "held").
  bool linksToCell(int level, const Index3& c, const double q[3], double radius) const;
  void updateHeatMarkers(const double (*x)[3], int n);
  void coarsen(const double (*x)[3], int n);
  void collectStatistics();
  // Incremental adaptive update (options_.incremental): see update().
  bool updateIncrementally(const double (*x)[3], const double* radius, int n);
  void resetIncrementalState(const double (*x)[3], int n);
  void addKept(int level, std::uint64_t vertexKey, int delta);
  bool isKept(int level, std::uint64_t vertexKey) const { return keepCount_[level].get(vertexKey) > 0; }
  bool isBlocked(int level, std::int64_t i, std::int64_t j, std::int64_t k) const;
  void coarsenAroundLostVertices();
  // Reluctant coarsening spares a cool cell that the refinement criterion would refine again at
  // once: for a pair of this pass (the caller's sweep, or the grid's own search) one partner is
  // hosted at a vertex of the cell's children, would sit on the cell's level once it is removed,
  // and the criterion holds for it there (it would drop, the partner is held by its cell, they
  // approach). Removing such a cell and refining it at the next pass only lifts and drops the
  // same particles and shocks the same vertices again. Context of one coarsening:
  struct SpareCheck {
    const double (*x)[3] = nullptr;
    const double (*v)[3] = nullptr;
    const double* radius = nullptr;
    int n = 0;
    const int* first = nullptr;   // the pass's pairs: arrays, or closePairs_ when null
    const int* second = nullptr;
    std::size_t count = 0;
    bool indexed = false;         // partners_ built (on the first cell that needs them)
    bool hostsIndexed = false;    // scratch particle lists (untracked grid) built
  };
  SpareCheck spare_;  // x == nullptr: no refinement pass running, nothing is spared
  std::vector<int> partnerStart_, partners_;
  std::vector<Markers> scratchFirstAt_;
  std::vector<int> scratchNextAt_;
  std::vector<std::pair<int, std::uint64_t>> spared_;  // (level, cell): spared, re-examined next time
  void beginSpareCheck(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                       const int* first, const int* second, std::size_t count);
  bool wouldRefineAgain(int level, std::uint64_t cellKey);
  void coarsenReluctant(const double (*x)[3], int n);  // coarsening of a pass, with rehosts
  int admissibleFor(double radius);
  // Incremental reluctant update (options_.incremental), AdaptiveGridReluctant.cpp.
  bool reluctantTracking() const { return options_.type == GridType::Reluctant && incrementalValid_; }
  bool updateReluctantIncrementally(const double (*x)[3], const double (*v)[3], const double* radius, int n);
  void resetReluctantState(const double (*x)[3], const double* radius, int n);
  double hostMargin(const double p[3], int admissible, int host, int descent) const;
  void rehostParticle(const double (*x)[3], int i);
  void linkHost(int i);
  void unlinkHost(int i);
  void addHeatInput(int level, std::uint64_t vertexKey, std::int64_t delta);
  std::size_t heatSlot(int level, std::uint64_t vertexKey);
  std::uint32_t parentSlots(int level, std::size_t heatSlot);
  void markDirty(int level, std::size_t heatSlot);
  void setHeat(int level, std::size_t heatSlot, std::int64_t value);
  void addShock(int level, std::uint64_t vertexKey);
  void annealDirtyMarkers();
  void rehostAroundRefined(const double (*x)[3], std::size_t firstRefined);
  void rehostAroundRemoved(const double (*x)[3]);
  void rehostCandidates(const double (*x)[3]);
  std::size_t reluctantEntries() const;
  // Vertices of `level` whose 7^3 children on level + 1 contain child vertex (i, j, k).
  template <class F>
  void forEachParentVertex(int level, std::int64_t i, std::int64_t j, std::int64_t k, F&& f) const;

  AdaptiveGridOptions options_;
  Spacetree pairSearch_;  // reluctant approach test: close pairs on the current levels
  GridGeometry geometry_;
  bool haveGeometry_ = false;
  int regularDepth_ = 0;
  std::vector<CellSet> refined_;  // per level, cells (not above regularDepth_) that are refined
  std::vector<Markers> heat_;     // per level, reluctant heat markers of vertices (0: none)
  std::vector<Markers> heatNext_; // scratch of updateHeatMarkers(), swapped with heat_
  std::vector<int> host_, admissible_;
  std::vector<double> required_;
  std::vector<std::pair<int, int>> closePairs_;
  // Scratch of coarsen(), kept between updates (no reallocation and page faults per update).
  std::vector<KeySet> keep_;
  KeySet parentsOfRefined_;
  std::vector<std::uint64_t> removals_;
  AdaptiveGridStatistics stats_;

  // Incremental state (Adaptive): host vertex key per particle, and per level the number of
  // reasons a vertex is kept from coarsening (particles hosted there + kept child vertices).
  bool incrementalValid_ = false;
  std::vector<std::uint64_t> hostKey_;
  std::vector<Markers> keepCount_;
  std::vector<std::vector<std::uint64_t>> lostKept_;  // per level: vertices no longer kept
  bool trackRefinements_ = false;
  std::vector<std::pair<int, std::uint64_t>> newRefined_;  // (level, cell) refined this update
  std::vector<int> moved_;
  std::vector<KeySet> candidates_;
  std::vector<double> meshSize_, inverseMeshSize_;  // meshSize(level) and 1 / it, per level
  // Grid changes (refinements, coarsenings, new cube) count up gridVersion_; rehostAll() is
  // skipped when the positions and the grid are those of its last run.
  std::uint64_t gridVersion_ = 0, hostsGridVersion_ = 0;
  bool hostsCurrent_ = false;
  std::size_t keepEntries_ = 0;  // counter entries after the last rebuild
  double lastRadius_ = -1.0;
  int lastAdmissible_ = 0;

  // Incremental state (Reluctant; keepCount_ counts hot markers + kept children there):
  // per particle the position of its last host derivation and how far it may move from it
  // before the derivation could read another cell or vertex (<= 0: always re-derived);
  // particles listed per host vertex (to find those under a changed cell); per vertex the
  // heat marker's input (particles hosted + children's markers) and the vertices whose marker
  // may change at the next annealing.
  std::vector<std::array<double, 3>> referencePosition_;
  std::vector<double> margin_;
  std::vector<double> hostRadius_;  // radius of the last admissible level derivation
  std::vector<int> fragile_;  // margin <= 0: re-derived at every grid change
  std::vector<int> nextAtVertex_, previousAtVertex_;
  std::vector<Markers> firstAtVertex_;  // per level: host vertex -> first particle + 1 (0: none)
  // Per level, indexed by the marker's slot in heat_: input, and whether listed in dirty_.
  std::vector<std::vector<std::int64_t>> heatInput_;
  std::vector<std::vector<char>> dirtyFlag_;
  std::vector<std::vector<std::uint32_t>> dirty_, annealing_;  // per level: slots in heat_
  // Per level and slot: where its parents' slots start in parentPool_ (kNoParents: not listed).
  static constexpr std::uint32_t kNoParents = ~std::uint32_t(0);
  std::vector<std::vector<std::uint32_t>> parentsAt_, parentPool_;
  std::vector<std::pair<int, std::uint64_t>> removedCells_;  // (level, cell) coarsened
  std::vector<int> rehostQueue_;
  std::vector<char> queued_;
  std::vector<int> newAdmissible_;
  std::size_t rehostCount_ = 0;
};

template <class F>
void AdaptiveGrid::forEachLeafCell(F&& f) const {
  if (!haveGeometry_) return;
  const int depth = geometry_.depth;
  // The start-off level: every cell exists, the stored refined ones are not leaves.
  const std::int64_t n = cellsPerAxis(regularDepth_);
  for (std::int64_t i = 0; i < n; ++i)
    for (std::int64_t j = 0; j < n; ++j)
      for (std::int64_t k = 0; k < n; ++k)
        if (!isRefined(regularDepth_, i, j, k)) f(regularDepth_, i, j, k);
  // Below it: the children of refined cells that are not refined themselves.
  for (int l = regularDepth_ + 1; l <= depth; ++l)
    for (std::uint64_t parentKey : refined_[l - 1].keys) {
      const VertexIndex c = unpackVertexKey(parentKey);
      for (std::int64_t a = 3 * c.i; a < 3 * c.i + 3; ++a)
        for (std::int64_t b = 3 * c.j; b < 3 * c.j + 3; ++b)
          for (std::int64_t e = 3 * c.k; e < 3 * c.k + 3; ++e)
            if (!isRefined(l, a, b, e)) f(l, a, b, e);
    }
}

template <class F>
void AdaptiveGrid::forEachParentVertex(int level, std::int64_t i, std::int64_t j, std::int64_t k,
                                       F&& f) const {
  // Child w of vertex u: w lies in the closure of the 2^d cells around u, i.e. |w - 3u| <= 3.
  const std::int64_t n = cellsPerAxis(level);
  auto lo = [](std::int64_t w) { return std::max<std::int64_t>(0, (w - 3 + 2) / 3); };  // ceil((w-3)/3), w >= 0
  auto hi = [n](std::int64_t w) { return std::min<std::int64_t>(n, (w + 3) / 3); };
  for (std::int64_t a = lo(i); a <= hi(i); ++a)
    for (std::int64_t b = lo(j); b <= hi(j); ++b)
      for (std::int64_t c = lo(k); c <= hi(k); ++c) f(packVertexKey(a, b, c));
}

}  // namespace spacetree
