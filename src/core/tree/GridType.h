// Which grid decides the level a particle is hosted on (paper §4, §5.1).
#pragma once

#include <stdexcept>
#include <string>

namespace spacetree {

enum class GridType {
  Regular,    // every cell refined down to the finest level any particle fits
  Adaptive,   // naive: refine wherever a particle would drop, coarsen by the analysed tree grammar
  Reluctant,  // refine only for approaching, touching pairs; aggressive coarsening by heat markers
};

inline const char* gridTypeName(GridType type) {
  switch (type) {
    case GridType::Regular: return "regular";
    case GridType::Adaptive: return "adaptive";
    case GridType::Reluctant: return "reluctant";
  }
  return "?";
}

// Inverse of gridTypeName (input decks spell the type); throws std::invalid_argument.
inline GridType parseGridType(const std::string& name) {
  if (name == "regular") return GridType::Regular;
  if (name == "adaptive") return GridType::Adaptive;
  if (name == "reluctant") return GridType::Reluctant;
  throw std::invalid_argument("spacetree: unknown grid type '" + name +
                              "' (regular, adaptive or reluctant)");
}

}  // namespace spacetree
