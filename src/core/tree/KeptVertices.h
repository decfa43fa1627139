// Which vertices the coarsening must keep, counted instead of re-derived (the incremental
// adaptive and reluctant updates). The analysed tree grammar keeps a vertex that is hot
// (adaptive: hosts a particle; reluctant: its heat marker reaches the threshold) or has a kept
// child; counting the reasons per vertex (own + kept children) lets an update change only the
// paths below which something changed, and lists the vertices that stopped being kept: only
// the cells around them may have become removable.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "tree/VertexCounters.h"

namespace spacetree {

class KeptVertices {
 public:
  // No vertex kept. Levels up to the start-off depth are never coarsened and not counted;
  // the start-off depth stays while counting (a change forces a full update, which resets).
  void reset(std::size_t levels, int regularDepth);
  // One reason more (delta 1) or less (-1) to keep the vertex; a vertex that becomes kept or
  // free passes that on to its parent vertices.
  void add(int level, std::uint64_t vertexKey, int delta);
  bool isKept(int level, std::uint64_t vertexKey) const { return count_[level].get(vertexKey) > 0; }
  // Vertices of `level` that stopped being kept since clearLost() (some may be kept again).
  const std::vector<std::uint64_t>& lost(int level) const { return lost_[std::size_t(level)]; }
  void clearLost() {
    for (auto& lost : lost_) lost.clear();
  }
  // Counter entries, zeros included (vertices no longer kept stay as zeros until a reset).
  std::size_t entries() const;

 private:
  std::vector<VertexCounters> count_;
  std::vector<std::vector<std::uint64_t>> lost_;
  int regularDepth_ = 0;
};

}  // namespace spacetree
