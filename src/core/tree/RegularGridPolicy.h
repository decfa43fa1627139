// The regular grid (paper §4): every cell refined down to the finest level any particle fits,
// so the start-off grid is the whole grid; it is re-hosted in full at every update and never
// refined or coarsened. The interface every grid type implements for AdaptiveGrid::update:
//   startOffDepth(coarsestFit, finestFit)  levels refined everywhere, from the particles' fits
//   tracking()                             incremental state valid (updateIncrementally may run)
//   updateIncrementally(g, x, v, r, n)     the change-driven update; false: do a full one
//   forgetIncrementalState()               the next update is a full one
//   newCube(levels)                        the cube was re-chosen (cells reset)
//   adapt(g, x, v, r, n)                   the full update, after the hosts were re-derived
//   refineForPairs(g, x, v, r, n, ...)     refinement for the caller's pairs; false: none ran
//   heatMarkers()                          the markers to serialise (nullptr: none)
#pragma once

#include <cstddef>

#include "tree/AdaptiveGridOptions.h"
#include "tree/HeatMarkers.h"
#include "tree/HostedGrid.h"

namespace spacetree {

class RegularGridPolicy {
 public:
  explicit RegularGridPolicy(const AdaptiveGridOptions&) {}

  int startOffDepth(int, int finestFit) const { return finestFit; }
  bool tracking() const { return false; }
  bool updateIncrementally(HostedGrid&, const double (*)[3], const double (*)[3], const double*, int) {
    return false;
  }
  void forgetIncrementalState() {}
  void newCube(std::size_t) {}
  void adapt(HostedGrid&, const double (*)[3], const double (*)[3], const double*, int) {}
  bool refineForPairs(HostedGrid&, const double (*)[3], const double (*)[3], const double*, int, const int*,
                      const int*, std::size_t) {
    return false;
  }
  HeatMarkers* heatMarkers() { return nullptr; }
  const HeatMarkers* heatMarkers() const { return nullptr; }
};

}  // namespace spacetree
