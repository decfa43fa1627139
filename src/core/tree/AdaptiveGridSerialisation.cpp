// AdaptiveGrid::serialise and its inverses: the restart words of a grid. Apart from the grid
// types' code because it reads and restores the state of all of them (cells, heat markers,
// cumulative counters) and defines a file format that old restart files rely on: the layout
// below must stay word for word (a change needs a new kSerialVersion).
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tree/AdaptiveGrid.h"
#include "tree/WordPacking.h"

namespace spacetree {

namespace {
// Layout of serialise(): header words, then per level the refined cells, then per level the
// heat markers (key, value pairs).
constexpr std::int64_t kSerialMagic = 0x53544147;  // "STAG"
constexpr std::int64_t kSerialVersion = 1;
enum SerialHeader {
  kMagic, kVersion, kType, kEpsilon, kMaxLevel, kShock, kThreshold, kPadding, kPairsFromCaller,
  kHaveGeometry, kOrigin0, kOrigin1, kOrigin2, kRootSize, kDepth, kRegularDepth, kResets,
  kRefinements, kCoarsenings, kHeaderWords
};

[[noreturn]] void badData(const char* what) {
  throw std::invalid_argument(std::string("adaptive grid restart data: ") + what);
}

// Sequential reader with bounds checks.
struct WordReader {
  const std::int64_t* words;
  std::size_t count, at;
  std::int64_t next() {
    if (at >= count) badData("truncated");
    return words[at++];
  }
  std::size_t length() {
    const std::int64_t n = next();
    if (n < 0 || std::size_t(n) > count - at) badData("truncated or bad length");
    return std::size_t(n);
  }
};
}  // namespace

std::vector<std::int64_t> AdaptiveGrid::serialise() const {
  const RefinedCells& cells = grid_.cells;
  const AdaptiveGridStatistics& stats = grid_.stats;
  std::vector<std::int64_t> w(kHeaderWords, 0);
  w[kMagic] = kSerialMagic;
  w[kVersion] = kSerialVersion;
  w[kType] = std::int64_t(options_.type);
  w[kEpsilon] = wordOfDouble(options_.epsilon);
  w[kMaxLevel] = options_.maxLevel;
  w[kShock] = options_.shock;
  w[kThreshold] = options_.coarseningThreshold;
  w[kPadding] = wordOfDouble(options_.padding);
  w[kPairsFromCaller] = options_.pairsFromCaller ? 1 : 0;
  w[kHaveGeometry] = cells.hasCube() ? 1 : 0;
  for (int d = 0; d < 3; ++d) w[kOrigin0 + d] = wordOfDouble(cells.geometry().origin[d]);
  w[kRootSize] = wordOfDouble(cells.geometry().rootSize);
  w[kDepth] = cells.depth();
  w[kRegularDepth] = cells.regularDepth();
  w[kResets] = std::int64_t(stats.geometryResets);
  w[kRefinements] = std::int64_t(stats.refinements);
  w[kCoarsenings] = std::int64_t(stats.coarsenings);
  // Sets in ascending key order: the words depend on the grid's content only, not on the order
  // in which an (incremental or full) update happened to insert and erase the keys; what the
  // updates compute depends on the content only.
  std::vector<std::uint64_t> sorted;
  const std::size_t levels = cells.levels();
  w.push_back(std::int64_t(levels));
  for (std::size_t l = 0; l < levels; ++l) {
    const VertexKeySet& refined = cells.refinedOn(int(l));
    sorted.assign(refined.keys.begin(), refined.keys.end());
    std::sort(sorted.begin(), sorted.end());
    w.push_back(std::int64_t(sorted.size()));
    for (std::uint64_t k : sorted) w.push_back(std::int64_t(k));
  }
  // Heat markers on as many levels (grid types without markers: none on every level).
  const HeatMarkers* heat = std::visit([](const auto& policy) { return policy.heatMarkers(); }, policy_);
  std::vector<std::size_t> order;
  w.push_back(std::int64_t(levels));
  for (std::size_t l = 0; l < levels; ++l) {
    if (!heat) {
      w.push_back(0);
      continue;
    }
    const VertexCounters& markers = heat->markers()[l];
    order.resize(markers.keys.size());
    for (std::size_t s = 0; s < order.size(); ++s) order[s] = s;
    std::sort(order.begin(), order.end(),
              [&markers](std::size_t a, std::size_t b) { return markers.keys[a] < markers.keys[b]; });
    // Markers of value 0 (left behind by the incremental annealing; the full one drops them)
    // are no markers.
    std::size_t nonZero = 0;
    for (std::int64_t value : markers.values) nonZero += value != 0;
    w.push_back(2 * std::int64_t(nonZero));  // words: (key, value) pairs
    for (std::size_t s : order) {
      if (markers.values[s] == 0) continue;
      w.push_back(std::int64_t(markers.keys[s]));
      w.push_back(markers.values[s]);
    }
  }
  return w;
}

AdaptiveGridOptions AdaptiveGrid::serialisedOptions(const std::int64_t* words, std::size_t count) {
  if (!words || count < std::size_t(kHeaderWords)) badData("shorter than its header");
  if (words[kMagic] != kSerialMagic) badData("not adaptive grid data (bad magic word)");
  if (words[kVersion] != kSerialVersion) badData("unknown version");
  AdaptiveGridOptions o;
  const std::int64_t type = words[kType];
  if (type != std::int64_t(GridType::Regular) && type != std::int64_t(GridType::Adaptive) &&
      type != std::int64_t(GridType::Reluctant))
    badData("unknown grid type");
  o.type = GridType(type);
  o.epsilon = doubleOfWord(words[kEpsilon]);
  if (words[kMaxLevel] < 0 || words[kMaxLevel] > kMaxSpacetreeLevel) badData("bad maxlevel");
  o.maxLevel = int(words[kMaxLevel]);
  if (words[kShock] < 0 || words[kShock] > std::numeric_limits<int>::max() || words[kThreshold] < 0 ||
      words[kThreshold] > std::numeric_limits<int>::max())
    badData("bad shock or threshold");
  o.shock = int(words[kShock]);
  o.coarseningThreshold = int(words[kThreshold]);
  o.padding = doubleOfWord(words[kPadding]);
  o.pairsFromCaller = words[kPairsFromCaller] != 0;
  return o;
}

AdaptiveGrid AdaptiveGrid::deserialise(const std::int64_t* words, std::size_t count) {
  return deserialise(words, count, serialisedOptions(words, count));
}

AdaptiveGrid AdaptiveGrid::deserialise(const std::int64_t* words, std::size_t count,
                                       const AdaptiveGridOptions& options) {
  const AdaptiveGridOptions stored = serialisedOptions(words, count);
  if (options.type != stored.type)
    throw std::invalid_argument(std::string("adaptive grid restart data: stored grid type ") +
                                gridTypeName(stored.type) + ", wanted " + gridTypeName(options.type));
  if (options.epsilon != stored.epsilon)
    throw std::invalid_argument("adaptive grid restart data: stored for another halo (epsilon)");
  if (words[kDepth] > options.maxLevel)
    throw std::invalid_argument("adaptive grid restart data: stored grid is deeper than maxlevel");
  AdaptiveGrid grid(options);  // the constructor checks the options
  const bool haveGeometry = words[kHaveGeometry] != 0;
  const std::int64_t depth = words[kDepth], regularDepth = words[kRegularDepth];
  if (depth < 0 || depth > grid.options_.maxLevel || regularDepth < 0 || regularDepth > depth) badData("bad depth");
  GridGeometry geometry;
  for (int d = 0; d < 3; ++d) geometry.origin[d] = doubleOfWord(words[kOrigin0 + d]);
  geometry.rootSize = doubleOfWord(words[kRootSize]);
  geometry.depth = int(depth);
  if (haveGeometry && !(geometry.rootSize > 0.0 && std::isfinite(geometry.rootSize))) badData("bad root cube");
  if (words[kResets] < 0 || words[kRefinements] < 0 || words[kCoarsenings] < 0) badData("bad counters");
  AdaptiveGridStatistics& stats = grid.grid_.stats;
  stats.geometryResets = std::uint64_t(words[kResets]);
  stats.refinements = std::uint64_t(words[kRefinements]);
  stats.coarsenings = std::uint64_t(words[kCoarsenings]);
  WordReader in{words, count, std::size_t(kHeaderWords)};
  // A cube sizes both per-level lists depth + 1; before it they are empty.
  const std::size_t levels = haveGeometry ? std::size_t(depth) + 1 : 0;
  if (in.length() != levels) badData("refined cell levels do not match the depth");
  std::vector<VertexKeySet> refined(levels);
  for (std::size_t l = 0; l < levels; ++l) {
    const std::size_t n = in.length();
    VertexKeySet& cells = refined[l];
    cells.reset(n);
    for (std::size_t s = 0; s < n; ++s) cells.insert(std::uint64_t(in.next()));
    if (cells.size() != n) badData("duplicate refined cell");
    if (n && l >= std::size_t(depth)) badData("refined cell on the finest level");
  }
  if (in.length() != levels) badData("heat marker levels do not match the depth");
  HeatMarkers* heat = std::visit([](auto& policy) { return policy.heatMarkers(); }, grid.policy_);
  std::vector<VertexCounters> heatMarkers(levels);
  for (std::size_t l = 0; l < levels; ++l) {
    const std::size_t n = in.length();
    if (n % 2) badData("odd heat marker list");
    if (n && !heat) badData("heat markers for a grid type without them");
    VertexCounters& markers = heatMarkers[l];
    markers.reset(n / 2);
    for (std::size_t s = 0; s < n / 2; ++s) {
      const std::uint64_t k = std::uint64_t(in.next());
      const std::int64_t value = in.next();
      markers[k] = value;
      if (markers.size() != s + 1) badData("duplicate heat marker");
    }
  }
  if (in.at != count) badData("trailing words");
  // Hosts and the incremental state are rebuilt by the next update() (a full one: the policy
  // does not track yet).
  grid.grid_.cells.restore(haveGeometry, geometry, int(regularDepth), std::move(refined));
  if (heat) heat->restore(std::move(heatMarkers));
  grid.grid_.collectStatistics();
  return grid;
}

}  // namespace spacetree
