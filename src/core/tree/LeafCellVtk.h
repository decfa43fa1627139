// Legacy VTK (ASCII header, big-endian binary data) of an AdaptiveGrid's leaf cells, written
// directly, no VTK library: an UNSTRUCTURED_GRID of VTK_VOXEL cells (8 own corners each) with
// the cell's level as cell data. ParaView opens it as is; a series file.*.vtk animates.
#pragma once

#include <cstdint>
#include <ostream>

#include "tree/AdaptiveGrid.h"

namespace spacetree {

// Writes the leaf cells; returns how many. `title` goes into the header line (one line, at
// most 255 characters are kept). Throws std::runtime_error if the stream fails.
std::uint64_t writeLeafCellsVtk(const AdaptiveGrid& grid, std::ostream& out, const char* title);

}  // namespace spacetree
