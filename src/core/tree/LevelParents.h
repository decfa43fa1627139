// How a vertex of level l + 1 hangs below level l (3-way refinement: child coordinates are
// three times the parent's). The grid types walk these relations bottom-up: heat markers and
// kept flags pass to the parent vertices, a vertex blocks or frees the parent cells around it.
#pragma once

#include <algorithm>
#include <cstdint>

#include "tree/GridGeometry.h"
#include "tree/VertexKey.h"

namespace spacetree {

// The vertices u of `level` (as packed keys) whose 7^3 children on level + 1 contain the
// child vertex w = (i, j, k): w lies in the closure of the 2^d cells around u, |w - 3u| <= 3.
template <class F>
void forEachParentVertex(int level, std::int64_t i, std::int64_t j, std::int64_t k, F&& f) {
  const std::int64_t n = kPowersOfThree[level];
  auto lo = [](std::int64_t w) { return std::max<std::int64_t>(0, (w - 3 + 2) / 3); };  // ceil((w-3)/3), w >= 0
  auto hi = [n](std::int64_t w) { return std::min<std::int64_t>(n, (w + 3) / 3); };
  for (std::int64_t a = lo(i); a <= hi(i); ++a)
    for (std::int64_t b = lo(j); b <= hi(j); ++b)
      for (std::int64_t c = lo(k); c <= hi(k); ++c) f(packVertexKey(a, b, c));
}

// The cells c one level up (as packed keys) whose closed patch of 3^d children has the vertex
// w = (i, j, k) (w >= 0) among its vertices: 3c <= w <= 3c + 3 per axis, up to 2^d cells.
template <class F>
void forEachParentCell(std::int64_t i, std::int64_t j, std::int64_t k, F&& f) {
  auto first = [](std::int64_t w) { return w % 3 == 0 && w > 0 ? w / 3 - 1 : w / 3; };
  const std::int64_t ai = first(i), aj = first(j), ak = first(k);
  for (std::int64_t a = ai; a <= i / 3; ++a)
    for (std::int64_t b = aj; b <= j / 3; ++b)
      for (std::int64_t e = ak; e <= k / 3; ++e) f(packVertexKey(a, b, e));
}

}  // namespace spacetree
