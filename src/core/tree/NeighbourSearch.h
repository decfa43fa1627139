// One neighbour-list build of the multilevel search, in the order it has to happen: update the
// persistent adaptive grid (when one is used), build the spacetree on it (else on a cube of its
// own), sweep the pairs within r_i + r_j + skin, and let the reluctant grid refine for the pairs
// the sweep listed. It owns the tree, the optional grid and the one halo both use, eps = skin/2,
// so a caller (the LIGGGHTS list builder) hands positions in once and gets the pairs back.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "tree/AdaptiveGrid.h"
#include "tree/AdaptiveGridOptions.h"
#include "tree/Spacetree.h"

namespace spacetree {

class NeighbourSearch {
 public:
  // What the caller's judge says about a pair within the cut-off.
  enum class Verdict { Skip, Keep, KeepMarked };
  // Pairs the judge kept, in sweep order: (first[k], second[k]) with first < second, and
  // second stored as ~second when the judge marked the pair.
  struct ListedPairs {
    std::vector<int> first, second;
    void clear() {
      first.clear();
      second.clear();
    }
    std::size_t size() const { return first.size(); }
  };

  // Lists pairs closer than r_i + r_j + skin: eps = skin / 2 for the tree and the grid.
  // Throws std::invalid_argument for a negative or non-finite skin. A changed skin rebuilds
  // the grid (start-off grid: its cells were refined for the old halo).
  void setSkin(double skin);
  double epsilon() const { return treeOptions_.epsilon; }
  // Deepest level of the tree (and of the grid, whose own maxLevel is capped to it).
  void setMaxLevel(int maxLevel);
  int maxLevel() const { return treeOptions_.maxLevel; }

  // The options a grid of this search gets: the requested type and tuning, this search's
  // eps, maxLevel capped to the search's, and the pairs reported by the search's sweep.
  AdaptiveGridOptions gridOptions(AdaptiveGridOptions requested) const;
  // Use a persistent grid with gridOptions(requested): a new one (the start-off grid), or the
  // current one when its options are the same. Throws what AdaptiveGrid throws for
  // inconsistent options.
  void useNewGrid(const AdaptiveGridOptions& requested);
  void useGrid(const AdaptiveGridOptions& requested);
  // Use this grid (e.g. restored from a restart file); its options must be gridOptions(its
  // options), else std::invalid_argument.
  void useGrid(AdaptiveGrid grid);
  void dropGrid() { grid_.reset(); }
  const AdaptiveGrid* grid() const { return grid_.get(); }

  // The build: grid update, tree, sweep, refinement. judge(i, j, squaredDistance) gets every
  // pair (i < j, at least one of them active, i.e. < nActive) with
  //   |x_i - x_j|^2 <= ((r_i + r_j + skin) (1 + relativeTolerance))^2
  // (tolerance 0: bit for bit LIGGGHTS' granular cut-off) and returns whether to list it; a
  // judge(i, j, squaredDistance, radiusSum) also gets radius[i] + radius[j] (the same sum);
  // the listed pairs go to `pairs` (cleared first). v may be nullptr (the reluctant grid then
  // treats every close pair as approaching). Throws std::invalid_argument for non-finite
  // positions or radii, or negative radii.
  template <class Judge>
  void findPairs(const double (*x)[3], const double (*v)[3], const double* radius, int n, int nActive,
                 double relativeTolerance, Judge&& judge, ListedPairs& pairs);

  const Spacetree& tree() const { return tree_; }
  // Seconds of the last build spent in the grid (update and refinement).
  double lastGridSeconds() const { return gridSeconds_; }
  // Mesh size of the finest cell that hosts a particle at the last build (0 before any).
  double finestCell() const { return tree_.finestPopulatedMeshSize(); }

 private:
  using Clock = std::chrono::steady_clock;
  // Pairs reserved per particle (a dense pack of one size lists up to 6 within contact).
  static constexpr std::size_t kReservedPairsPerParticle = 8;
  void buildTree(const double (*x)[3], const double (*v)[3], const double* radius, int n, int nActive);
  void refineAfterSweep(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                        const ListedPairs& pairs);

  SpacetreeOptions treeOptions_;
  Spacetree tree_;
  std::unique_ptr<AdaptiveGrid> grid_;
  double gridSeconds_ = 0.0;
  std::vector<int> unmarked_;  // scratch: the listed partners without the mark
};

template <class Judge>
void NeighbourSearch::findPairs(const double (*x)[3], const double (*v)[3], const double* radius, int n,
                                int nActive, double relativeTolerance, Judge&& judge, ListedPairs& pairs) {
  buildTree(x, v, radius, n, nActive);
  pairs.clear();
  // Room for the pairs of a dense pack before the sweep: growing the vectors during the sweep
  // copies them, and the copies stay in the process's peak memory. Reserved pages that are
  // never written cost no memory.
  const std::size_t room = std::size_t(n) * kReservedPairsPerParticle;
  if (pairs.first.capacity() < room) {
    pairs.first.reserve(room);
    pairs.second.reserve(room);
  }
  tree_.forEachPairWithin(
      [&](int a, int b, double squaredDistance, double radiusSum) {
        const int i = a < b ? a : b, j = a < b ? b : a;
        Verdict verdict;
        if constexpr (std::is_invocable_v<Judge&, int, int, double, double>)
          verdict = judge(i, j, squaredDistance, radiusSum);
        else
          verdict = judge(i, j, squaredDistance);
        if (verdict == Verdict::Skip) return;
        pairs.first.push_back(i);
        pairs.second.push_back(verdict == Verdict::KeepMarked ? ~j : j);
      },
      relativeTolerance);
  refineAfterSweep(x, v, radius, n, pairs);
}

}  // namespace spacetree
