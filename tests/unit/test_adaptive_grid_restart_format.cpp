// The restart words of an AdaptiveGrid are a file format: restart files written by earlier
// builds must load and mean what they meant. The words below were written by serialise() of
// format version 1 (commit 57c6b90) for a reluctant grid, eps 2e-5, after 6 updates of two big
// spheres (r 4 mm, centres at x = 5.6 and 14.4 mm, y = z = 10 mm) and between them a block of
// 96 small ones (r 0.13-0.16 mm, within 9.1-10.9 mm per axis): depth 4, start-off depth 1, one
// refined cell on level 1 and one on level 2, heat markers on levels 2 and 3.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "tree/AdaptiveGrid.h"
#include "tree/WordPacking.h"

using spacetree::AdaptiveGrid;
using spacetree::AdaptiveGridOptions;
using spacetree::GridType;

namespace {

const std::vector<std::int64_t> kFormat1Words = {
    1398030663, 1, 2, 4536524183238306033, 12,
    8, 4, 4598175219545276416, 0, 1,
    -4656268051830637928, -4656268051830637924, -4656268051830637924, 4582661219555914529, 4,
    1, 1, 0, 0, 5,
    0, 1, 5497563381765, 1, 8796101410824,
    0, 0, 5, 0, 0,
    128, 7696588734471, 1, 7696588734472, 3,
    7696588734473, 3, 7696588734474, 1, 7696589783047,
    3, 7696589783048, 12, 7696589783049, 12,
    7696589783050, 3, 7696590831623, 3, 7696590831624,
    12, 7696590831625, 12, 7696590831626, 3,
    7696591880199, 1, 7696591880200, 3, 7696591880201,
    3, 7696591880202, 1, 8796100362247, 3,
    8796100362248, 12, 8796100362249, 12, 8796100362250,
    3, 8796101410823, 12, 8796101410824, 390,
    8796101410825, 390, 8796101410826, 12, 8796102459399,
    12, 8796102459400, 390, 8796102459401, 390,
    8796102459402, 12, 8796103507975, 3, 8796103507976,
    12, 8796103507977, 12, 8796103507978, 3,
    9895611990023, 3, 9895611990024, 12, 9895611990025,
    12, 9895611990026, 3, 9895613038599, 12,
    9895613038600, 390, 9895613038601, 390, 9895613038602,
    12, 9895614087175, 12, 9895614087176, 390,
    9895614087177, 390, 9895614087178, 12, 9895615135751,
    3, 9895615135752, 12, 9895615135753, 12,
    9895615135754, 3, 10995123617799, 1, 10995123617800,
    3, 10995123617801, 3, 10995123617802, 1,
    10995124666375, 3, 10995124666376, 12, 10995124666377,
    12, 10995124666378, 3, 10995125714951, 3,
    10995125714952, 12, 10995125714953, 12, 10995125714954,
    3, 10995126763527, 1, 10995126763528, 3,
    10995126763529, 3, 10995126763530, 1, 16,
    18691715498001, 23, 18691715498002, 23, 18691716546577,
    23, 18691716546578, 23, 19791227125777, 23,
    19791227125778, 23, 19791228174353, 23, 19791228174354,
    23, 0,
};

}  // namespace

TEST(AdaptiveGridRestartFormat, LoadsWordsOfFormatVersion1) {
  const std::vector<std::int64_t>& words = kFormat1Words;
  const AdaptiveGridOptions o = AdaptiveGrid::serialisedOptions(words.data(), words.size());
  EXPECT_EQ(o.type, GridType::Reluctant);
  EXPECT_EQ(o.epsilon, 2e-5);  // bit for bit
  EXPECT_EQ(o.maxLevel, 12);
  EXPECT_EQ(o.shock, 8);
  EXPECT_EQ(o.coarseningThreshold, 4);
  EXPECT_EQ(o.padding, 0.25);
  EXPECT_FALSE(o.pairsFromCaller);

  const AdaptiveGrid grid = AdaptiveGrid::deserialise(words.data(), words.size());
  EXPECT_EQ(grid.serialise(), words) << "read and written back word for word";
  EXPECT_EQ(grid.geometry().depth, 4);
  EXPECT_EQ(grid.statistics().regularDepth, 1);
  EXPECT_EQ(grid.statistics().geometryResets, 1u);
  // The cube holds every particle centre.
  const double lo[3] = {0.0056, 0.0091, 0.0091}, hi[3] = {0.0144, 0.0109, 0.0109};
  for (int d = 0; d < 3; ++d) {
    EXPECT_LE(grid.geometry().origin[d], lo[d]);
    EXPECT_GE(grid.geometry().origin[d] + grid.geometry().rootSize, hi[d]);
  }
  // The 27 cells of the start-off level 1, one of them refined, and one of its children:
  // 27 - 2 + 2 * 27 leaves; cells 1 + 27 + 27 + 27 over the levels.
  EXPECT_EQ(grid.leafCellCount(), 79u);
  EXPECT_EQ(grid.statistics().cells, 82u);
  // The refined cells are those around the small spheres' block.
  const double centre[3] = {0.01, 0.01, 0.01}, bigCentre[3] = {0.0056, 0.01, 0.01};
  EXPECT_TRUE(grid.isRefinedAt(1, centre));
  EXPECT_TRUE(grid.isRefinedAt(2, centre));
  EXPECT_FALSE(grid.isRefinedAt(3, centre));
  EXPECT_FALSE(grid.isRefinedAt(1, bigCentre));
}

TEST(AdaptiveGridRestartFormat, WordsHoldDoublesBitForBit) {
  using spacetree::doubleOfWord;
  using spacetree::wordOfDouble;
  EXPECT_EQ(wordOfDouble(1.0), std::int64_t(0x3FF0000000000000));  // IEEE 754 binary64 layout
  EXPECT_NE(wordOfDouble(-0.0), wordOfDouble(0.0));
  const double values[] = {-0.0, std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::max(),
                           -std::numeric_limits<double>::infinity(), 0.1, -2.5e-300};
  for (double d : values) {
    EXPECT_EQ(wordOfDouble(doubleOfWord(wordOfDouble(d))), wordOfDouble(d)) << d;
    EXPECT_EQ(std::signbit(doubleOfWord(wordOfDouble(d))), std::signbit(d)) << d;
  }
  const std::int64_t nanWithPayload = std::int64_t(0x7FF0000000000123);
  EXPECT_TRUE(std::isnan(doubleOfWord(nanWithPayload)));
  EXPECT_EQ(wordOfDouble(doubleOfWord(nanWithPayload)), nanWithPayload);
}

TEST(AdaptiveGridRestartFormat, HeatMarkersOnlyForTheReluctantGrid) {
  // An adaptive or regular grid has no heat markers, so its words never hold one: data that
  // does is refused, not silently dropped. The same words as a reluctant grid's load.
  const std::vector<std::int64_t>& words = kFormat1Words;
  for (GridType type : {GridType::Regular, GridType::Adaptive, GridType::Reluctant}) {
    std::vector<std::int64_t> w = words;
    w[2] = std::int64_t(type);  // header word 2: the grid type
    if (type == GridType::Reluctant) {
      EXPECT_NO_THROW(AdaptiveGrid::deserialise(w.data(), w.size()));
      continue;
    }
    try {
      AdaptiveGrid::deserialise(w.data(), w.size());
      ADD_FAILURE() << spacetree::gridTypeName(type) << " grid took heat markers";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("heat markers"), std::string::npos) << e.what();
    }
  }
}
