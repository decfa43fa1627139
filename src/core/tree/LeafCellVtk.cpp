#include "tree/LeafCellVtk.h"

#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace spacetree {

namespace {
// Legacy VTK binary data is big-endian whatever the machine.
template <class T>
void putBigEndian(std::vector<char>& buffer, T value) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  const std::uint16_t probe = 1;
  const bool little = *reinterpret_cast<const std::uint8_t*>(&probe) == 1;
  for (std::size_t b = 0; b < sizeof(T); ++b) buffer.push_back(little ? bytes[sizeof(T) - 1 - b] : bytes[b]);
}
}  // namespace

std::uint64_t writeLeafCellsVtk(const AdaptiveGrid& grid, std::ostream& out, const char* title) {
  const std::uint64_t cells = grid.leafCellCount();
  if (cells > std::uint64_t(INT32_MAX) / 9)
    throw std::runtime_error("leaf-cell VTK: too many cells for a legacy VTK file");
  std::string header = title ? title : "spacetree leaf cells";
  for (char& c : header)
    if (c == '\n' || c == '\r') c = ' ';
  if (header.size() > 255) header.resize(255);

  const GridGeometry& g = grid.geometry();
  out << "# vtk DataFile Version 3.0\n" << header << "\nBINARY\nDATASET UNSTRUCTURED_GRID\n";
  out << "POINTS " << 8 * cells << " double\n";
  std::vector<char> buffer;
  buffer.reserve((1 << 16) + 256);
  std::vector<std::uint8_t> levels;
  levels.reserve(std::size_t(cells));
  auto flush = [&]() {
    out.write(buffer.data(), std::streamsize(buffer.size()));
    buffer.clear();
  };
  std::uint64_t written = 0;
  grid.forEachLeafCell([&](int level, std::int64_t i, std::int64_t j, std::int64_t k) {
    const double h = grid.meshSize(level);
    // VTK_VOXEL corner order: x fastest, then y, then z.
    for (int corner = 0; corner < 8; ++corner) {
      putBigEndian(buffer, g.origin[0] + double(i + (corner & 1)) * h);
      putBigEndian(buffer, g.origin[1] + double(j + ((corner >> 1) & 1)) * h);
      putBigEndian(buffer, g.origin[2] + double(k + ((corner >> 2) & 1)) * h);
    }
    levels.push_back(std::uint8_t(level));
    ++written;
    if (buffer.size() >= 1 << 16) flush();
  });
  flush();
  if (written != cells) throw std::logic_error("leaf-cell VTK: leaf count and leaf iteration disagree");

  out << "\nCELLS " << cells << " " << 9 * cells << "\n";
  for (std::uint64_t c = 0; c < cells; ++c) {
    putBigEndian(buffer, std::int32_t(8));
    for (int corner = 0; corner < 8; ++corner) putBigEndian(buffer, std::int32_t(8 * c + corner));
    if (buffer.size() >= 1 << 16) flush();
  }
  flush();
  out << "\nCELL_TYPES " << cells << "\n";
  for (std::uint64_t c = 0; c < cells; ++c) {
    putBigEndian(buffer, std::int32_t(11));  // VTK_VOXEL
    if (buffer.size() >= 1 << 16) flush();
  }
  flush();
  out << "\nCELL_DATA " << cells << "\nSCALARS level int 1\nLOOKUP_TABLE default\n";
  for (std::uint8_t l : levels) {
    putBigEndian(buffer, std::int32_t(l));
    if (buffer.size() >= 1 << 16) flush();
  }
  flush();
  out << "\n";
  if (!out) throw std::runtime_error("leaf-cell VTK: write failed");
  return cells;
}

}  // namespace spacetree
