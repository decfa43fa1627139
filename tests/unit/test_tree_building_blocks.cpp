// The tree's building blocks: root cube, radix sort, vertex key set, vertex bitmap.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "tree/GridGeometry.h"
#include "tree/RadixSort.h"
#include "tree/VertexBitmap.h"
#include "tree/VertexKeySet.h"

using namespace spacetree;

namespace {
// radixSortByKey on these records gives std::stable_sort's order.
template <class Record>
void expectStableSort(std::vector<Record> records, const char* what) {
  std::vector<Record> expected = records, scratch;
  std::stable_sort(expected.begin(), expected.end(), [](const Record& a, const Record& b) { return a.key < b.key; });
  radixSortByKey(records, scratch);
  ASSERT_EQ(records.size(), expected.size());
  for (std::size_t s = 0; s < records.size(); ++s) {
    ASSERT_EQ(records[s].key, expected[s].key) << what << " at " << s;
    ASSERT_EQ(records[s].index, expected[s].index) << what << ": not stable at " << s;
  }
}
}  // namespace

TEST(RadixSort, SortsLikeAStableSort) {
  std::mt19937_64 rng(3);
  for (std::uint64_t spread : {std::uint64_t(7), std::uint64_t(1) << 40, ~std::uint64_t(0)}) {
    std::vector<KeyedIndex> records;
    for (int i = 0; i < 5000; ++i) records.push_back(KeyedIndex{(rng() % spread) << 3, i});
    expectStableSort(records, "64-bit keys");
  }
}

TEST(RadixSort, SortsNarrowRecordsLikeAStableSort) {
  // The 8-byte records of trees whose keys fit into 32 bits: the same passes on a 32-bit key.
  std::mt19937_64 rng(5);
  for (std::uint32_t spread : {std::uint32_t(7), std::uint32_t(1) << 21, ~std::uint32_t(0)}) {
    std::vector<KeyedIndex32> records;
    for (int i = 0; i < 5000; ++i) records.push_back(KeyedIndex32{std::uint32_t(rng() % spread), i});
    expectStableSort(records, "32-bit keys");
  }
}

TEST(RadixSort, SortsKeysVaryingInAnyBandOfBits) {
  // Keys that agree outside a band (low, high bits of the band vary): every band width and
  // position takes its own number of passes and digit width; the result is a stable sort.
  std::mt19937_64 rng(11);
  for (int low : {0, 5, 23, 40}) {
    for (int width : {1, 11, 12, 13, 21, 24, 25, 37}) {
      if (low + width > 64) continue;
      const std::uint64_t band = (width == 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << width) - 1) << low;
      const std::uint64_t common = rng() & ~band;
      std::vector<KeyedIndex> records, scratch;
      for (int i = 0; i < 3000; ++i) records.push_back(KeyedIndex{common | (rng() & band), i});
      std::vector<KeyedIndex> expected = records;
      std::stable_sort(expected.begin(), expected.end(),
                       [](const KeyedIndex& a, const KeyedIndex& b) { return a.key < b.key; });
      radixSortByKey(records, scratch);
      for (std::size_t s = 0; s < records.size(); ++s) {
        ASSERT_EQ(records[s].key, expected[s].key) << "band " << low << "+" << width << " at " << s;
        ASSERT_EQ(records[s].index, expected[s].index) << "not stable at " << s;
      }
    }
  }
}

TEST(SortKeyPacking, KeepsTheOrderOfLevelVertexKeysAndRestoresThem) {
  // The tree sorts particles on the compact key and reads levelVertexKey back: both must order
  // (level, i, j, k) alike, for every depth, including indices at the bias and at 3^depth.
  std::mt19937_64 rng(13);
  for (int depth = 0; depth <= kMaxSpacetreeLevel; ++depth) {
    const SortKeyPacking packing(depth);
    EXPECT_LE(4 + 3 * packing.fieldBits, 64);
    const std::int64_t top = kPowersOfThree[depth] + kVertexKeyBias - 1;
    std::uniform_int_distribution<std::int64_t> index(-kVertexKeyBias, top);
    std::uniform_int_distribution<int> level(0, depth);
    std::vector<std::pair<std::uint64_t, std::uint64_t>> keys;  // (compact, levelVertexKey)
    for (int t = 0; t < 2000; ++t) {
      const int l = level(rng);
      const std::int64_t i = t == 0 ? top : index(rng), j = t == 1 ? -kVertexKeyBias : index(rng), k = index(rng);
      const std::uint64_t compact = packing.toSortKey(l, i, j, k), wide = levelVertexKey(l, packVertexKey(i, j, k));
      ASSERT_EQ(packing.fromSortKey(compact), wide) << "depth " << depth;
      keys.emplace_back(compact, wide);
    }
    for (std::size_t a = 1; a < keys.size(); ++a)
      ASSERT_EQ(keys[a - 1].first < keys[a].first, keys[a - 1].second < keys[a].second) << "depth " << depth;
    // keyBits holds the largest key (the tree sorts 32-bit records when keyBits <= 32), and
    // no fewer bits would: the deepest level and the top index need its highest bit.
    const std::uint64_t largest = packing.toSortKey(depth, top, top, top);
    ASSERT_LE(packing.keyBits, 64);
    EXPECT_EQ(packing.keyBits == 64 ? 0 : largest >> packing.keyBits, 0u) << "depth " << depth;
    if (depth > 0) EXPECT_EQ(largest >> (packing.keyBits - 1), 1u) << "depth " << depth;
    EXPECT_EQ(packing.levelOf(largest), depth);
  }
}

TEST(VertexKeySet, InsertsAndErasesLikeAStdSet) {
  // Clustered keys (long probe chains) and random batches of removals, small (erased one by
  // one with backward shifts) and large (table rebuilt): membership and members as a std::set.
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<int> coordinate(0, 12);
  auto randomKey = [&] { return spacetree::packVertexKey(coordinate(rng), coordinate(rng), coordinate(rng)); };
  spacetree::VertexKeySet set;
  set.reset(4);
  std::set<std::uint64_t> reference;
  for (int round = 0; round < 400; ++round) {
    for (int k = 0; k < 20; ++k) {
      const std::uint64_t key = randomKey();
      set.insert(key);
      reference.insert(key);
    }
    std::vector<std::uint64_t> removals;
    const int count = round % 10 == 0 ? 400 : 3;
    for (int k = 0; k < count; ++k) removals.push_back(randomKey());
    set.eraseAll(removals);
    for (std::uint64_t key : removals) reference.erase(key);
    ASSERT_EQ(set.size(), reference.size()) << "round " << round;
    ASSERT_EQ(std::set<std::uint64_t>(set.keys.begin(), set.keys.end()), reference) << "round " << round;
    for (int k = 0; k < 50; ++k) {
      const std::uint64_t key = randomKey();
      ASSERT_EQ(set.contains(key), reference.count(key) == 1) << "round " << round;
    }
  }
}

// The finest level of the chosen cube must hold the smallest particle: rootSize / 3^depth is
// rounded, and a mesh one ulp below the need would host the smallest particles a level higher,
// 27 times as many per vertex.
TEST(GridGeometry, FinestMeshOfTheRootCubeFitsTheSmallestParticle) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> need(1e-5, 1e-1), ratio(1.0, 1e4);
  for (int t = 0; t < 20000; ++t) {
    const double finest = need(rng), root = finest * ratio(rng);
    spacetree::GridGeometry g;
    spacetree::chooseRootCube(finest, root, spacetree::kMaxSpacetreeLevel, g);
    ASSERT_GE(spacetree::meshSizeOfLevel(g.rootSize, g.depth), finest) << "finest need " << finest;
    ASSERT_GE(g.rootSize, root);
    if (g.depth > 0) {
      ASSERT_LT(g.rootSize / 3.0, root * (1.0 + 1e-12)) << "one level fewer would do";
    }
  }
}

// The 27 vertices around any vertex of the index cube, their slots in the key-sorted list, and
// whether any is occupied, as a brute-force search over the occupied set finds them, on sparse
// and dense random sets, with vertices on the faces, edges and corners of the cube (where the
// 3x3x3 reaches the padding and the 3-bit reads straddle words).
TEST(VertexBitmap, FindsTheOccupiedVerticesAroundAVertexAndTheirSlots) {
  std::mt19937_64 rng(41);
  for (const std::int64_t last : {std::int64_t(1), std::int64_t(3), std::int64_t(9), std::int64_t(27)})
    for (const double fill : {0.01, 0.2, 0.9}) {
      std::uniform_int_distribution<std::int64_t> index(0, last);
      std::uniform_real_distribution<double> u(0.0, 1.0);
      std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t>> occupied;
      for (std::int64_t i = 0; i <= last; ++i)
        for (std::int64_t j = 0; j <= last; ++j)
          for (std::int64_t k = 0; k <= last; ++k)
            if (u(rng) < fill || (i == last && j == last && k == last)) occupied.insert({i, j, k});
      std::vector<std::uint64_t> keys;
      for (const auto& [i, j, k] : occupied) keys.push_back(packVertexKey(i, j, k));
      ASSERT_TRUE(std::is_sorted(keys.begin(), keys.end()));
      VertexBitmap bitmap;
      bitmap.build(keys.data(), keys.size(), last);
      for (std::int64_t i = 0; i <= last; ++i)
        for (std::int64_t j = 0; j <= last; ++j)
          for (std::int64_t k = 0; k <= last; ++k) {
            std::vector<std::int32_t> expected, found;
            for (std::size_t s = 0; s < keys.size(); ++s) {
              const VertexIndex v = unpackVertexKey(keys[s]);
              if (std::abs(v.i - i) <= 1 && std::abs(v.j - j) <= 1 && std::abs(v.k - k) <= 1)
                expected.push_back(std::int32_t(s));
            }
            std::uint32_t around = bitmap.around(i, j, k);
            while (around) {
              const unsigned t = unsigned(__builtin_ctz(around));
              around &= around - 1;
              found.push_back(bitmap.slotAround(i, j, k, t));
            }
            ASSERT_EQ(found, expected) << "around (" << i << ", " << j << ", " << k << "), last " << last;
            ASSERT_EQ(bitmap.anyAround(i, j, k), !expected.empty()) << "(" << i << ", " << j << ", " << k << ")";
          }
    }
}
