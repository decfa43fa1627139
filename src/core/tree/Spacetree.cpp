#include "tree/Spacetree.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace spacetree {

namespace {
// Relative margin on the mesh-size rule h >= 2(r + eps): a pair at exactly the cut-off
// distance must still be strictly closer than h, whatever the rounding of its coordinates.
constexpr double kMeshSizeMargin = 1e-9;
}  // namespace

Spacetree::Spacetree(SpacetreeOptions options) { setOptions(options); }

void Spacetree::setOptions(const SpacetreeOptions& options) {
  if (!(options.epsilon >= 0.0) || !std::isfinite(options.epsilon))
    throw std::invalid_argument("spacetree: epsilon must be finite and >= 0");
  if (options.maxLevel < 0 || options.maxLevel > kMaxSpacetreeLevel)
    throw std::invalid_argument("spacetree: maxLevel must be in [0, " +
                                std::to_string(kMaxSpacetreeLevel) + "]");
  options_ = options;
}

double Spacetree::requiredMeshSize(double radius) const {
  return 2.0 * (radius + options_.epsilon) * (1.0 + kMeshSizeMargin);
}

int Spacetree::hostLevel(double required) const {
  // Finest level whose mesh is still big enough: drop as far as the particle fits. Mesh sizes
  // fall with the level, so that level is the count of levels below the root whose mesh fits
  // (a branch-free count: continuous sizes would mispredict a search, and a logarithm per
  // particle costs more).
  int l = 0;
  for (int k = 1; k < int(levels_.size()); ++k) l += meshSizes_[k] >= required ? 1 : 0;
  return l;
}

void Spacetree::validate(const double (*x)[3], const double* radius, int n, double lo[3],
                         double hi[3], double& minRadius, double& maxRadius) {
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::numeric_limits<double>::infinity();
    hi[d] = -lo[d];
  }
  minRadius = std::numeric_limits<double>::infinity();
  maxRadius = 0.0;
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      if (!std::isfinite(x[i][d]))
        throw std::invalid_argument("spacetree: particle " + std::to_string(i) +
                                    " has a non-finite position");
      lo[d] = std::min(lo[d], x[i][d]);
      hi[d] = std::max(hi[d], x[i][d]);
    }
    if (!(radius[i] >= 0.0) || !std::isfinite(radius[i]))
      throw std::invalid_argument("spacetree: particle " + std::to_string(i) +
                                  " has a negative or non-finite radius");
    minRadius = std::min(minRadius, radius[i]);
    maxRadius = std::max(maxRadius, radius[i]);
  }
}

void Spacetree::resetLevels(const std::array<double, 3>& origin, double rootSize, int depth) {
  rootSize_ = rootSize;
  origin_ = origin;
  levels_.resize(std::size_t(depth) + 1);
  stats_.levels.resize(levels_.size());
  for (int l = 0; l <= depth; ++l) {
    levels_[l].meshSize = meshSizes_[l] = meshSizeOfLevel(rootSize, l);
    inverseMeshSizes_[l] = 1.0 / meshSizes_[l];
    stats_.levels[l].meshSize = levels_[l].meshSize;
  }
}

void Spacetree::clear(int n, int nActive) {
  nActive_ = nActive;
  // Keep the levels' storage (vertex lists, look-up tables) from build to build: freeing and
  // re-allocating it every step costs page faults comparable to the build itself.
  for (Level& level : levels_) {
    level.vertices.clear();
    level.keys.clear();
    level.rows.clear();
    level.slices.clear();
    level.crowds.clear();
    level.radiusSum = level.radiusSquaredSum = 0.0;
    level.occupancyBuilt = false;
  }
  stats_ = SpacetreeStatistics{};
  particleCount_ = std::max(n, 0);
  dense_.forget();
}

void Spacetree::build(const double (*x)[3], const double* radius, int n, int nActive) {
  clear(n, nActive);
  if (n <= 0) return;

  // Bounding box and the smallest and biggest mesh sizes the particles ask for.
  double lo[3], hi[3], minRadius, maxRadius;
  validate(x, radius, n, lo, hi, minRadius, maxRadius);
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double coarsestNeed = requiredMeshSize(maxRadius);
  const double finestNeed = requiredMeshSize(minRadius);
  const double rootNeed = std::max(extent, coarsestNeed);
  GridGeometry geometry;
  chooseRootCube(finestNeed, rootNeed, options_.maxLevel, geometry);
  resetLevels({lo[0], lo[1], lo[2]}, geometry.rootSize, geometry.depth);
  if (!placeDense(x, radius, n, hi, minRadius, maxRadius)) placeParticles(x, radius, n, nullptr);
}

bool Spacetree::placeDense(const double (*x)[3], const double* radius, int n, const double hi[3], double minRadius,
                           double maxRadius) {
  // One populated level: the biggest particle fits the finest level (the smallest always does).
  const int depth = levelCount() - 1;
  if (meshSizes_[depth] < requiredMeshSize(maxRadius)) return false;
  static_assert(DenseLevel::kMaxPerVertex == kSweepAndPruneMinParticles, "crowded means the same on both paths");
  if (!dense_.build(x, radius, n, nActive_, origin_.data(), inverseMeshSizes_[depth], hi, minRadius == maxRadius))
    return false;
  releaseGeneralStorage();
  stats_.levels[depth].realParticles = std::uint64_t(n);
  stats_.levels[depth].vertices = dense_.occupiedVertices();
  stats_.deepestPopulatedLevel = depth;
  countMemory();
  return true;
}

void Spacetree::releaseGeneralStorage() {
  std::vector<std::int8_t>().swap(particleLevel_);
  for (std::vector<double>* v : {&sx_, &sy_, &sz_, &sr_}) std::vector<double>().swap(*v);
  std::vector<std::int32_t>().swap(sortedId_);
  std::vector<KeyedIndex>().swap(sortKeys_);
  std::vector<KeyedIndex>().swap(sortScratch_);
  std::vector<KeyedIndex32>().swap(sortKeys32_);
  std::vector<KeyedIndex32>().swap(sortScratch32_);
  for (Level& level : levels_) {
    const double meshSize = level.meshSize;
    level = Level();
    level.meshSize = meshSize;
  }
}

void Spacetree::build(const double (*x)[3], const double* radius, int n, int nActive,
                      const GridGeometry& geometry, const int* hostLevelOf) {
  clear(n, nActive);
  if (geometry.depth < 0 || geometry.depth > options_.maxLevel)
    throw std::invalid_argument("spacetree: geometry depth must be in [0, maxLevel]");
  if (!(geometry.rootSize > 0.0) || !std::isfinite(geometry.rootSize))
    throw std::invalid_argument("spacetree: geometry root size must be finite and > 0");
  if (n <= 0) return;
  double lo[3], hi[3], minRadius, maxRadius;
  validate(x, radius, n, lo, hi, minRadius, maxRadius);
  for (int d = 0; d < 3; ++d)
    if (lo[d] < geometry.origin[d] || hi[d] > geometry.origin[d] + geometry.rootSize)
      throw std::invalid_argument("spacetree: a particle centre lies outside the given cube");
  resetLevels(geometry.origin, geometry.rootSize, geometry.depth);
  placeParticles(x, radius, n, hostLevelOf);
}

template <class Record>
void Spacetree::keyParticles(const double (*x)[3], const double* radius, int n, const int* hostLevelOf,
                             const SortKeyPacking& packing, std::vector<Record>& records) {
  const int levelCount = int(levels_.size());
  records.resize(std::size_t(n));
  double lastRadius = -1.0;  // radii repeat (monodisperse species): skip the level search
  int lastLevel = 0;
  for (int i = 0; i < n; ++i) {
    // A caller's level may be coarser than the finest admissible one, never finer. Mesh sizes
    // fall with the level, so a level whose mesh still fits the particle is at or above the
    // finest admissible one: taken as it is, without the level search.
    int l;
    const int wanted = hostLevelOf ? hostLevelOf[i] : -1;
    if (wanted >= 0 && wanted < levelCount && levels_[wanted].meshSize >= requiredMeshSize(radius[i])) {
      l = wanted;
    } else {
      if (radius[i] != lastRadius) {
        lastRadius = radius[i];
        lastLevel = hostLevel(requiredMeshSize(radius[i]));
      }
      l = hostLevelOf ? std::clamp(hostLevelOf[i], 0, lastLevel) : lastLevel;
    }
    particleLevel_[i] = std::int8_t(l);
    const double inv = inverseMeshSizes_[l];
    const std::int64_t vi = nearestVertexCoordinate(x[i][0], origin_[0], inv);
    const std::int64_t vj = nearestVertexCoordinate(x[i][1], origin_[1], inv);
    const std::int64_t vk = nearestVertexCoordinate(x[i][2], origin_[2], inv);
    records[std::size_t(i)] = Record{decltype(Record::key)(packing.toSortKey(l, vi, vj, vk)), i};
  }
}

void Spacetree::placeParticles(const double (*x)[3], const double* radius, int n,
                               const int* hostLevelOf) {
  // Drop every particle to its level and key it by its nearest vertex there. Keys of a tree of
  // few levels fit into 32 bits: records of 8 bytes instead of 16 (half the sort's traffic and
  // memory); only the record vectors of the width in use hold storage.
  // Sized, not cleared: every entry is written below (clearing would zero-fill them all again
  // on every build).
  dense_.release();
  const std::size_t size = std::size_t(n);
  particleLevel_.resize(size);
  sx_.resize(size);
  sy_.resize(size);
  sz_.resize(size);
  sr_.resize(size);
  sortedId_.resize(size);
  const int levelCount = int(levels_.size());
  const SortKeyPacking packing(levelCount - 1);
  if (packing.keyBits <= 32) {
    std::vector<KeyedIndex>().swap(sortKeys_);
    std::vector<KeyedIndex>().swap(sortScratch_);
    keyParticles(x, radius, n, hostLevelOf, packing, sortKeys32_);
    radixSortByKey(sortKeys32_, sortScratch32_);
    placeSorted(sortKeys32_, packing, x, radius, n);
  } else {
    std::vector<KeyedIndex32>().swap(sortKeys32_);
    std::vector<KeyedIndex32>().swap(sortScratch32_);
    keyParticles(x, radius, n, hostLevelOf, packing, sortKeys_);
    radixSortByKey(sortKeys_, sortScratch_);
    placeSorted(sortKeys_, packing, x, radius, n);
  }
  countMemory();
}

template <class Record>
void Spacetree::placeSorted(const std::vector<Record>& sorted, const SortKeyPacking& packing, const double (*x)[3],
                            const double* radius, int n) {
  for (int s = 0; s < n; ++s) {  // the arrays have size n (clear)
    const int id = sorted[std::size_t(s)].index;
    sx_[s] = x[id][0];
    sy_[s] = x[id][1];
    sz_[s] = x[id][2];
    sr_[s] = radius[id];
    sortedId_[s] = id;
  }

  // Vertices per level, and their look-up tables (reserved at their size: no copies on growth).
  for (int s = 0; s < n;) {
    const int l = packing.levelOf(sorted[std::size_t(s)].key);
    Level& level = levels_[l];
    // The level's particles (sorted by level first); they fill at most as many vertices. The
    // storage is kept from build to build: the vertices are counted (for an exact reserve)
    // only when it might be too small.
    const int levelEnd = int(std::partition_point(sorted.begin() + s, sorted.begin() + n,
                                                  [&](const Record& r) { return packing.levelOf(r.key) == l; }) -
                             sorted.begin());
    if (level.vertices.capacity() < std::size_t(levelEnd - s)) {
      std::size_t vertexCount = 0;
      for (int e = s; e < levelEnd; ++e)
        vertexCount += (e == s || sorted[std::size_t(e)].key != sorted[std::size_t(e - 1)].key) ? 1 : 0;
      level.vertices.reserve(vertexCount);
      level.keys.reserve(vertexCount);
    }
    int e = s;
    while (e < levelEnd) {
      const auto sortKey = sorted[std::size_t(e)].key;
      const std::uint64_t key = packing.fromSortKey(sortKey);
      // Filled in place (a record built on the stack and copied in reads back fields just
      // written piecewise: a stalled store-to-load forward per vertex).
      const std::int32_t slot = std::int32_t(level.vertices.size()), begin = e;
      std::int32_t active = 0;
      for (; e < levelEnd && sorted[std::size_t(e)].key == sortKey; ++e) active += sorted[std::size_t(e)].index < nActive_ ? 1 : 0;
      Vertex& v = level.vertices.emplace_back();
      v.begin = begin;
      v.end = e;
      v.active = active;
      v.bigBegin = e;
      v.box = -1;
      if (v.end - v.begin >= kSweepAndPruneMinParticles && worthPruning(v.begin, v.end, level.meshSize)) {
        v.bigBegin = orderCrowdedVertex(v.begin, v.end, x, radius);
        Crowd crowd{boxOf(v.begin, v.bigBegin), 0.0};
        for (std::int32_t q = v.begin; q < v.bigBegin; ++q) crowd.maxSmallRadius = std::max(crowd.maxSmallRadius, sr_[q]);
        v.box = std::int32_t(level.crowds.size());
        level.crowds.push_back(crowd);
      }
      // Rows of equal (i, j), slices of equal i.
      const VertexIndex index = unpackVertexKey(key);
      const VertexIndex previous = slot > 0 ? indexOf(level, std::size_t(slot - 1)) : VertexIndex{-1, -1, -1};
      const bool newSlice = slot == 0 || index.i != previous.i;
      if (newSlice || index.j != previous.j) {
        if (newSlice) level.slices.push_back(Slice{index.i, std::int32_t(level.rows.size())});
        level.rows.push_back(Row{index.j, slot, slot});
      }
      level.rows.back().end = slot + 1;
      level.keys.push_back(key & ((std::uint64_t(1) << kLevelShift) - 1));
    }
    level.slices.push_back(Slice{0, std::int32_t(level.rows.size())});  // past the end
    for (int q = s; q < e; ++q) {
      level.radiusSum += sr_[q];
      level.radiusSquaredSum += sr_[q] * sr_[q];
    }
    stats_.levels[l].realParticles = std::uint64_t(e - s);
    stats_.levels[l].vertices = level.vertices.size();
    stats_.deepestPopulatedLevel = l;
    s = e;
  }
}

void Spacetree::countMemory() {
  std::uint64_t bytes = (sx_.capacity() + sy_.capacity() + sz_.capacity() + sr_.capacity()) * sizeof(double) +
                        sortedId_.capacity() * sizeof(std::int32_t) + particleLevel_.capacity() +
                        (sortKeys_.capacity() + sortScratch_.capacity()) * sizeof(KeyedIndex) +
                        (sortKeys32_.capacity() + sortScratch32_.capacity()) * sizeof(KeyedIndex32);
  bytes += dense_.memoryBytes();
  for (const Level& level : levels_)
    bytes += level.vertices.capacity() * sizeof(Vertex) + level.keys.capacity() * sizeof(std::uint64_t) +
             level.rows.capacity() * sizeof(Row) + level.slices.capacity() * sizeof(Slice) +
             level.crowds.capacity() * sizeof(Crowd) + level.occupancy.bytes();
  stats_.memoryBytes = bytes;
}

bool Spacetree::linkFromFineVertices(int m, int l, const VertexBitmap*& around) {
  // Costs in about CPU cycles, measured on the power-law clouds of bench/neighbor_vs_lammps
  // (the links themselves cost the same either way). A link ball pays a slice search per slice
  // and a little per row it crosses: ball radius rho = r + 2 eps + h (1 + sqrt(3)) / 2 in fine
  // mesh sizes, rows padded by one. A fine vertex pays one bit read; one with a coarse vertex
  // around it (probability 1 - (1 - nu)^27, nu the coarse level's occupied fraction) its 3-bit
  // reads, and each coarse vertex and particle found. The bitmap costs its words (dilation,
  // rank) and a bit per coarse vertex, once per build.
  constexpr double kSliceCost = 80.0, kRowCost = 30.0, kFineVertexCost = 25.0, kAroundCost = 60.0,
                   kCoarseVertexCost = 30.0, kLinkTestCost = 15.0, kBitmapWordCost = 10.0, kBitmapVertexCost = 5.0,
                   kSearchCost = 400.0;
  // A bitmap holds at most this many bits of its cube per particle of the tree (3.5 bits each).
  constexpr std::uint64_t kBitmapBitsPerParticle = 32;
  around = nullptr;
  Level& coarse = levels_[m];
  const Level& fine = levels_[l];
  const double coarseParticles = double(stats_.levels[m].realParticles);
  const double coarseVertices = double(coarse.vertices.size());
  const double fineVertices = double(fine.vertices.size());
  // Few fine vertices (a level holding a handful of the smallest particles): a search each.
  const bool fewFine = fineVertices < coarseParticles;
  const std::int64_t last = kPowersOfThree[m];
  const std::uint64_t bits = VertexBitmap::bitsFor(last);
  if (bits > kBitmapBitsPerParticle * std::uint64_t(particleCount())) return fewFine;
  const double h = fine.meshSize, a = 2.0 * options_.epsilon + kLinkMeshFactor * h + h;
  const double sumRadius = coarse.radiusSum, sumSquares = coarse.radiusSquaredSum;
  const double ballCost =
      kSliceCost * ((2.0 * (sumRadius + coarseParticles * a)) / h + 3.0 * coarseParticles) +
      kRowCost * 3.14159 * (sumSquares + 2.0 * a * sumRadius + coarseParticles * a * a) / (h * h);
  const double cells = double(last + 1) * double(last + 1) * double(last + 1);
  const double anyAround = 1.0 - std::pow(1.0 - coarseVertices / cells, 27.0);
  const double fineCost =
      fineVertices * (kFineVertexCost + anyAround * kAroundCost +
                      27.0 / cells * (coarseVertices * kCoarseVertexCost + coarseParticles * kLinkTestCost)) +
      (coarse.occupancyBuilt ? 0.0 : double(bits) / 64.0 * kBitmapWordCost + coarseVertices * kBitmapVertexCost);
  if (fineCost < std::min(ballCost, fewFine ? fineVertices * kSearchCost : ballCost)) {
    if (!coarse.occupancyBuilt) {
      coarse.occupancy.build(coarse.keys.data(), coarse.keys.size(), last);
      coarse.occupancyBuilt = true;
      countMemory();
    }
    around = &coarse.occupancy;
    return true;
  }
  return fewFine;
}

void Spacetree::sortByXThenId(std::vector<XAndId>& records) {
  // Ties in x by id: the order the radix sort leaves them in. (x, id) is a total order, so the
  // result does not depend on the method: a bucket pass along x (the particles of a vertex
  // spread over its cell) and an insertion sort of the nearly ordered result, or std::sort
  // where one bucket is crowded (a cluster inside the vertex).
  auto less = [](const XAndId& a, const XAndId& b) { return a.x < b.x || (a.x == b.x && a.id < b.id); };
  const std::size_t count = records.size();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const XAndId& r : records) {
    lo = std::min(lo, r.x);
    hi = std::max(hi, r.x);
  }
  const double toBucket = hi > lo ? double(count) / (hi - lo) * (1.0 - 1e-12) : 0.0;
  bucketFirst_.assign(count + 1, 0);
  for (const XAndId& r : records) ++bucketFirst_[std::min(count - 1, std::size_t((r.x - lo) * toBucket))];
  std::int32_t sum = 0, largest = 0;
  for (std::int32_t& f : bucketFirst_) {
    const std::int32_t c = f;
    largest = std::max(largest, c);
    f = sum;
    sum += c;
  }
  if (largest > kLargestBucket) {
    std::sort(records.begin(), records.end(), less);
    return;
  }
  byXScratch_.resize(count);
  for (const XAndId& r : records) byXScratch_[std::size_t(bucketFirst_[std::min(count - 1, std::size_t((r.x - lo) * toBucket))]++)] = r;
  for (std::size_t t = 1; t < count; ++t) {
    const XAndId r = byXScratch_[t];
    std::size_t u = t;
    for (; u > 0 && less(r, byXScratch_[u - 1]); --u) byXScratch_[u] = byXScratch_[u - 1];
    byXScratch_[u] = r;
  }
  records.swap(byXScratch_);
}

std::int32_t Spacetree::orderCrowdedVertex(std::int32_t begin, std::int32_t end, const double (*x)[3],
                                           const double* radius) {
  // A crowded vertex (a lifted cloud) keeps its particles ordered along x, so the sweep can
  // prune its pairs by their x distance instead of testing all of them. Particles much bigger
  // than the vertex's median go last, in their order: they would widen every pruning window.
  // Sorting (x, id) records directly, not indices through the arrays, then refilling this
  // vertex's slice of the particle arrays from the caller's arrays.
  const std::size_t count = std::size_t(end - begin);
  scratchValues_.resize(count);
  double smallest = std::numeric_limits<double>::infinity(), largest = 0.0;
  for (std::size_t t = 0; t < count; ++t) {
    const double r = sr_[std::size_t(begin) + t];
    scratchValues_[t] = r;
    smallest = std::min(smallest, r);
    largest = std::max(largest, r);
  }
  // No particle exceeds 4 x the median when none exceeds 4 x the smallest: skip the median.
  double bigRadius = kBigRadiusOverMedian * smallest;
  if (largest > bigRadius) {
    std::nth_element(scratchValues_.begin(), scratchValues_.begin() + count / 2, scratchValues_.end());
    bigRadius = kBigRadiusOverMedian * scratchValues_[count / 2];
  }
  byX_.clear();
  bigIds_.clear();
  for (std::size_t t = 0; t < count; ++t) {
    const std::int32_t id = sortedId_[std::size_t(begin) + t];
    if (radius[id] > bigRadius)
      bigIds_.push_back(id);
    else
      byX_.push_back({x[id][0], id});
  }
  sortByXThenId(byX_);
  std::size_t t = std::size_t(begin);
  auto place = [&](std::int32_t id) {
    sx_[t] = x[id][0];
    sy_[t] = x[id][1];
    sz_[t] = x[id][2];
    sr_[t] = radius[id];
    sortedId_[t] = id;
    ++t;
  };
  for (const XAndId& p : byX_) place(p.id);
  for (const std::int32_t id : bigIds_) place(id);
  return begin + std::int32_t(byX_.size());
}

Spacetree::Box Spacetree::boxOf(std::int32_t begin, std::int32_t end) const {
  Box box;
  for (int d = 0; d < 3; ++d) {
    box.lo[d] = std::numeric_limits<double>::infinity();
    box.hi[d] = -box.lo[d];
  }
  for (std::int32_t q = begin; q < end; ++q) {
    box.lo[0] = std::min(box.lo[0], sx_[q]);
    box.hi[0] = std::max(box.hi[0], sx_[q]);
    box.lo[1] = std::min(box.lo[1], sy_[q]);
    box.hi[1] = std::max(box.hi[1], sy_[q]);
    box.lo[2] = std::min(box.lo[2], sz_[q]);
    box.hi[2] = std::max(box.hi[2], sz_[q]);
  }
  return box;
}

Spacetree::Box Spacetree::smallBox(const Level& level, const Vertex& v) const {
  return v.box >= 0 ? level.crowds[std::size_t(v.box)].box : boxOf(v.begin, v.bigBegin);
}

void Spacetree::particlesNearBox(std::int32_t begin, std::int32_t end, bool sorted, const Box& box,
                                 double reach, std::vector<std::int32_t>& out, Box& near) const {
  out.clear();
  for (int d = 0; d < 3; ++d) {
    near.lo[d] = std::numeric_limits<double>::infinity();
    near.hi[d] = -near.lo[d];
  }
  // In x order the slab along x is one contiguous run.
  if (sorted) {
    begin = firstWithinX(begin, end, box.lo[0], reach);
    end = endWithinX(begin, end, box.hi[0], reach);
  }
  // Branch-free selection (most of a crowded vertex lies beyond the thin slab), then the box.
  if (end <= begin) return;
  out.resize(std::size_t(end - begin));
  std::size_t count = 0;
  for (std::int32_t q = begin; q < end; ++q) {
    const double x = sx_[q], y = sy_[q], z = sz_[q];
    // Differences, as the visitor computes them (see firstWithinX).
    const bool beyond = (box.lo[0] - x > reach) | (x - box.hi[0] > reach) | (box.lo[1] - y > reach) |
                        (y - box.hi[1] > reach) | (box.lo[2] - z > reach) | (z - box.hi[2] > reach);
    out[count] = q;
    count += beyond ? 0 : 1;
  }
  out.resize(count);
  for (std::int32_t q : out) {
    const double x = sx_[q], y = sy_[q], z = sz_[q];
    near.lo[0] = std::min(near.lo[0], x);
    near.hi[0] = std::max(near.hi[0], x);
    near.lo[1] = std::min(near.lo[1], y);
    near.hi[1] = std::max(near.hi[1], y);
    near.lo[2] = std::min(near.lo[2], z);
    near.hi[2] = std::max(near.hi[2], z);
  }
}

}  // namespace spacetree
