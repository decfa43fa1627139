// Structure-of-arrays batch of triangle pairs: the unit of work of the vectorised penalty
// kernel. Lane l holds one pair; every coordinate of all lanes lies contiguously, so a loop over
// the lanes maps one-to-one onto SIMD registers (8 doubles = two AVX2 or one AVX-512 register).
#pragma once

#include "geometry/Triangle.h"

namespace spacetree::geometry {

constexpr int kTrianglePairBatchSize = 16;

struct TrianglePairBatch {
  // coordinate[t][v][c][lane]: triangle t (0 = first, 1 = second), vertex v, axis c.
  alignas(64) double coordinate[2][3][3][kTrianglePairBatchSize];

  void set(int lane, const Triangle& first, const Triangle& second) {
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) {
        coordinate[0][v][c][lane] = first[v][c];
        coordinate[1][v][c][lane] = second[v][c];
      }
  }
};

}  // namespace spacetree::geometry
