// Options of an AdaptiveGrid (fix spacetree's keywords map onto them).
#pragma once

#include "tree/GridType.h"
#include "tree/VertexKey.h"

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

}  // namespace spacetree
