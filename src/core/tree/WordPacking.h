// Doubles as 64-bit words and back, bit for bit: restart data is stored as flat lists of
// int64 words (LIGGGHTS restart records, AdaptiveGrid::serialise), and a restored run must
// continue exactly as the original, so no value may pass through a decimal or rounded form.
#pragma once

#include <cstdint>
#include <cstring>

namespace spacetree {

inline std::int64_t wordOfDouble(double d) {
  std::int64_t w;
  std::memcpy(&w, &d, sizeof w);
  return w;
}

inline double doubleOfWord(std::int64_t w) {
  double d;
  std::memcpy(&d, &w, sizeof d);
  return d;
}

}  // namespace spacetree
