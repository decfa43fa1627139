#include "tree/HostedGrid.h"

#include <algorithm>

namespace spacetree {

void HostedGrid::rehostAll(const double (*x)[3], int n) {
  if (hostsCurrent_ && hostsVersion_ == cells.version()) return;
  for (int i = 0; i < n; ++i) host[i] = cells.hostOf(x[i], admissible[i]);
  hostsCurrent_ = true;
  hostsVersion_ = cells.version();
}

void HostedGrid::collectStatistics() {
  const int depth = cells.hasCube() ? cells.depth() : 0;
  stats.levels.assign(std::size_t(depth) + 1, AdaptiveLevelStatistics{});
  stats.cells = 0;
  stats.regularDepth = cells.regularDepth();
  stats.deepestLevel = 0;
  if (!cells.hasCube()) return;
  for (int l = 0; l <= depth; ++l) {
    AdaptiveLevelStatistics& s = stats.levels[l];
    s.meshSize = cells.meshSize(l);
    s.cells = cells.cellsOn(l);
    stats.cells += s.cells;
  }
  for (int h : host) {
    ++stats.levels[h].realParticles;
    stats.deepestLevel = std::max(stats.deepestLevel, h);
  }
}

}  // namespace spacetree
