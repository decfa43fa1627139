#include "tree/KeptVertices.h"

#include "tree/LevelParents.h"
#include "tree/VertexKey.h"

namespace spacetree {

void KeptVertices::reset(std::size_t levels, int regularDepth) {
  count_.resize(levels);
  for (VertexCounters& counts : count_) counts.reset(0);
  lost_.assign(levels, {});
  regularDepth_ = regularDepth;
}

void KeptVertices::add(int level, std::uint64_t vertexKey, int delta) {
  std::int64_t& count = count_[level][vertexKey];
  const bool before = count > 0;
  count += delta;
  const bool after = count > 0;
  if (before == after) return;
  if (!after) lost_[level].push_back(vertexKey);
  if (level - 1 > regularDepth_) {
    const VertexIndex w = unpackVertexKey(vertexKey);
    forEachParentVertex(level - 1, w.i, w.j, w.k, [&](std::uint64_t u) { add(level - 1, u, after ? 1 : -1); });
  }
}

std::size_t KeptVertices::entries() const {
  std::size_t entries = 0;
  for (const VertexCounters& counts : count_) entries += counts.size();
  return entries;
}

}  // namespace spacetree
