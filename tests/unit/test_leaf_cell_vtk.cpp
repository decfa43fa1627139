// The leaf-cell VTK file must be a well-formed legacy VTK unstructured grid whose voxels are
// exactly the grid's leaf cells (corners and levels read back from the binary data).
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "tree/AdaptiveGrid.h"
#include "tree/LeafCellVtk.h"

using spacetree::AdaptiveGrid;
using spacetree::AdaptiveGridOptions;
using spacetree::GridType;

namespace {

template <class T>
T readBigEndian(const std::string& s, std::size_t& at) {
  char bytes[sizeof(T)];
  for (std::size_t b = 0; b < sizeof(T); ++b) bytes[sizeof(T) - 1 - b] = s[at + b];  // to little
  at += sizeof(T);
  T v;
  std::memcpy(&v, bytes, sizeof(T));
  return v;
}

std::size_t after(const std::string& s, const std::string& token) {
  const std::size_t p = s.find(token);
  EXPECT_NE(p, std::string::npos) << token;
  return s.find('\n', p) + 1;
}

}  // namespace

TEST(LeafCellVtk, WritesEveryLeafCellAsAVoxelWithItsLevel) {
  const std::uint16_t probe = 1;
  if (*reinterpret_cast<const std::uint8_t*>(&probe) != 1) GTEST_SKIP() << "reader assumes little-endian host";
  AdaptiveGridOptions options;
  options.type = GridType::Adaptive;
  AdaptiveGrid grid(options);
  const double x[3][3] = {{0.1, 0.1, 0.1}, {0.5, 0.5, 0.5}, {0.9, 0.2, 0.7}};
  const double r[3] = {0.004, 0.1, 0.01};
  grid.update(x, nullptr, r, 3);

  std::map<std::array<double, 4>, int> expected;  // (x0, y0, z0, h) -> level
  grid.forEachLeafCell([&](int level, std::int64_t i, std::int64_t j, std::int64_t k) {
    const double h = grid.meshSize(level);
    const auto& o = grid.geometry().origin;
    expected[{o[0] + i * h, o[1] + j * h, o[2] + k * h, h}] = level;
  });
  ASSERT_GT(expected.size(), 27u);

  std::ostringstream out;
  const std::uint64_t n = spacetree::writeLeafCellsVtk(grid, out, "test\ntitle");
  const std::string s = out.str();
  ASSERT_EQ(n, expected.size());
  EXPECT_EQ(s.rfind("# vtk DataFile Version 3.0\ntest title\nBINARY\nDATASET UNSTRUCTURED_GRID\n", 0), 0u);

  std::size_t at = after(s, "POINTS " + std::to_string(8 * n) + " double");
  std::vector<std::array<double, 3>> points(8 * n);
  for (auto& p : points)
    for (double& c : p) c = readBigEndian<double>(s, at);
  at = after(s, "CELLS " + std::to_string(n) + " " + std::to_string(9 * n));
  std::vector<std::array<std::int32_t, 8>> cells(n);
  for (auto& c : cells) {
    ASSERT_EQ(readBigEndian<std::int32_t>(s, at), 8);
    for (auto& id : c) id = readBigEndian<std::int32_t>(s, at);
  }
  at = after(s, "CELL_TYPES " + std::to_string(n));
  for (std::uint64_t c = 0; c < n; ++c) ASSERT_EQ(readBigEndian<std::int32_t>(s, at), 11);
  at = after(s, "LOOKUP_TABLE default");
  std::map<std::array<double, 4>, int> found;
  for (std::uint64_t c = 0; c < n; ++c) {
    const int level = readBigEndian<std::int32_t>(s, at);
    const auto& lo = points[cells[c][0]];
    const auto& hi = points[cells[c][7]];
    const double h = hi[0] - lo[0];
    // VTK_VOXEL corner order: x fastest, then y, then z.
    for (int corner = 0; corner < 8; ++corner) {
      const auto& p = points[cells[c][corner]];
      const double tol = 1e-12 * grid.geometry().rootSize;
      EXPECT_NEAR(p[0], lo[0] + ((corner & 1) ? h : 0.0), tol);
      EXPECT_NEAR(p[1], lo[1] + ((corner & 2) ? h : 0.0), tol);
      EXPECT_NEAR(p[2], lo[2] + ((corner & 4) ? h : 0.0), tol);
    }
    found[{lo[0], lo[1], lo[2], grid.meshSize(level)}] = level;
    EXPECT_NEAR(h, grid.meshSize(level), 1e-12);
  }
  EXPECT_EQ(found, expected);
}
