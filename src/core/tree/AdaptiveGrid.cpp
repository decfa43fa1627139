#include "tree/AdaptiveGrid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "tree/WordPacking.h"

namespace spacetree {

namespace {
std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) { return packVertexKey(i, j, k); }
}  // namespace

AdaptiveGrid::AdaptiveGrid(AdaptiveGridOptions options)
    : options_(options), pairSearch_(SpacetreeOptions{options.epsilon, options.maxLevel}) {
  if (options.shock <= 0) throw std::invalid_argument("adaptive grid: shock must be > 0");
  if (options.coarseningThreshold < 0)
    throw std::invalid_argument("adaptive grid: coarsening threshold must be >= 0");
  if (options.coarseningThreshold >= options.shock)
    throw std::invalid_argument(
        "adaptive grid: coarsening threshold must be below the refinement shock, else fresh "
        "refinements are coarsened at once");
  if (!(options.padding >= 0.0) || !std::isfinite(options.padding))
    throw std::invalid_argument("adaptive grid: padding must be finite and >= 0");
}

double AdaptiveGrid::meshSize(int level) const {
  return meshSizeOfLevel(geometry_.rootSize, level);
}

int AdaptiveGrid::finestFit(double required) const {
  int l = 0;
  while (l < geometry_.depth && meshSize_[std::size_t(l) + 1] >= required) ++l;
  return l;
}

AdaptiveGrid::Index3 AdaptiveGrid::cellOf(int level, const double p[3]) const {
  const double inv = inverseMeshSize_[level];
  const std::int64_t last = cellsPerAxis(level) - 1;
  auto c = [&](int d) {
    return std::clamp(std::int64_t(std::floor((p[d] - geometry_.origin[d]) * inv)), std::int64_t(0), last);
  };
  return {c(0), c(1), c(2)};
}

AdaptiveGrid::Index3 AdaptiveGrid::nearestVertex(int level, const double p[3]) const {
  const double inv = inverseMeshSize_[level];
  auto v = [&](int d) { return nearestVertexCoordinate(p[d], geometry_.origin[d], inv); };
  return {v(0), v(1), v(2)};
}

bool AdaptiveGrid::isRefined(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
  if (level < regularDepth_) return true;
  if (level >= geometry_.depth) return false;
  return refined_[level].contains(key(i, j, k));
}

bool AdaptiveGrid::cellExists(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
  const std::int64_t n = cellsPerAxis(level);
  if (i < 0 || j < 0 || k < 0 || i >= n || j >= n || k >= n) return false;
  return level == 0 || isRefined(level - 1, i / 3, j / 3, k / 3);
}

bool AdaptiveGrid::isHanging(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
  // Cells outside the cube do not count: the padding keeps particles off its boundary.
  // Levels down to the start-off one exist everywhere; below, a cell exists iff its parent is
  // refined, and the 2^d cells around a vertex share parents (one look-up per distinct parent,
  // about 2.4 instead of 8 on average).
  if (level <= regularDepth_) return false;
  const std::int64_t last = cellsPerAxis(level) - 1;
  auto lo = [](std::int64_t v) { return std::max<std::int64_t>(v - 1, 0) / 3; };
  auto hi = [last](std::int64_t v) { return std::min(v, last) / 3; };
  if (i - 1 > last || j - 1 > last || k - 1 > last || i < 0 || j < 0 || k < 0) return false;
  for (std::int64_t a = lo(i); a <= hi(i); ++a)
    for (std::int64_t b = lo(j); b <= hi(j); ++b)
      for (std::int64_t c = lo(k); c <= hi(k); ++c)
        if (!isRefined(level - 1, a, b, c)) return true;
  return false;
}

bool AdaptiveGrid::isRefinedAt(int level, const double p[3]) const {
  if (!haveGeometry_ || level < 0 || level > geometry_.depth) return false;
  const Index3 c = cellOf(level, p);
  return cellExists(level, c.i, c.j, c.k) && isRefined(level, c.i, c.j, c.k);
}

int AdaptiveGrid::computeHost(const double p[3], int admissible) const {
  int descent;
  return hostPath(p, admissible, descent);
}

int AdaptiveGrid::hostPath(const double p[3], int admissible, int& descent) const {
  // Levels above the start-off grid are refined everywhere: no look-up needed there.
  int l = std::max(0, std::min(regularDepth_, admissible));
  while (l < admissible) {
    const Index3 c = cellOf(l, p);
    if (!isRefined(l, c.i, c.j, c.k)) break;
    ++l;
  }
  descent = l;
  while (l > 0) {
    const Index3 v = nearestVertex(l, p);
    if (!isHanging(l, v.i, v.j, v.k)) break;
    --l;  // lift: the vertex does not exist as a full vertex on this level
  }
  return l;
}

void AdaptiveGrid::rehostAll(const double (*x)[3], int n) {
  // Same positions (within one update, and refineForPairs after it) on an unchanged grid:
  // the hosts are already those.
  if (hostsCurrent_ && hostsGridVersion_ == gridVersion_) return;
  for (int i = 0; i < n; ++i) host_[i] = computeHost(x[i], admissible_[i]);
  hostsCurrent_ = true;
  hostsGridVersion_ = gridVersion_;
}

bool AdaptiveGrid::needsNewGeometry(const double (*x)[3], const double* radius, int n) const {
  if (!haveGeometry_) return true;
  // requiredMeshSize() grows with the radius: the extreme radii decide.
  double minRadius = std::numeric_limits<double>::infinity(), maxRadius = -minRadius;
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d)
      if (!(x[i][d] >= geometry_.origin[d] && x[i][d] <= geometry_.origin[d] + geometry_.rootSize))
        return true;
    minRadius = std::min(minRadius, radius[i]);
    maxRadius = std::max(maxRadius, radius[i]);
  }
  if (n > 0 && pairSearch_.requiredMeshSize(maxRadius) > geometry_.rootSize) return true;
  const double minNeed = n > 0 ? pairSearch_.requiredMeshSize(minRadius) : std::numeric_limits<double>::infinity();
  // A smaller particle than the finest level was made for: go deeper.
  return geometry_.depth < options_.maxLevel && minNeed > 0.0 && meshSize(geometry_.depth) / 3.0 >= minNeed;
}

void AdaptiveGrid::cacheMeshSizes() {
  const std::size_t levels = std::size_t(geometry_.depth) + 1;
  inverseMeshSize_.resize(levels);
  meshSize_.resize(levels);
  for (std::size_t l = 0; l < levels; ++l) {
    meshSize_[l] = meshSize(int(l));
    inverseMeshSize_[l] = 1.0 / meshSize(int(l));
  }
}

void AdaptiveGrid::chooseGeometry(const double (*x)[3], const double* radius, int n) {
  double lo[3], hi[3];
  double minNeed = std::numeric_limits<double>::infinity(), maxNeed = 0.0;
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::numeric_limits<double>::infinity();
    hi[d] = -lo[d];
  }
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < 3; ++d) {
      if (!std::isfinite(x[i][d]))
        throw std::invalid_argument("adaptive grid: a particle has a non-finite position");
      lo[d] = std::min(lo[d], x[i][d]);
      hi[d] = std::max(hi[d], x[i][d]);
    }
    if (!(radius[i] >= 0.0) || !std::isfinite(radius[i]))
      throw std::invalid_argument("adaptive grid: a particle has a negative or non-finite radius");
    const double need = pairSearch_.requiredMeshSize(radius[i]);
    minNeed = std::min(minNeed, need);
    maxNeed = std::max(maxNeed, need);
  }
  // Padded cube: particles may move a while before it has to be re-chosen (which resets the
  // refinement). Levels as in Spacetree::build: the finest one fits the smallest particle.
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double margin = options_.padding * std::max(extent, minNeed > 0.0 ? minNeed : 0.0);
  const double rootNeed = std::max(extent + 2.0 * margin, maxNeed);
  chooseRootCube(minNeed, rootNeed, options_.maxLevel, geometry_);
  if (!(geometry_.rootSize > 0.0)) geometry_.rootSize = 1.0;
  const double root = geometry_.rootSize;
  const int depth = geometry_.depth;
  for (int d = 0; d < 3; ++d) geometry_.origin[d] = 0.5 * (lo[d] + hi[d]) - 0.5 * root;
  haveGeometry_ = true;
  cacheMeshSizes();
  ++gridVersion_;
  refined_.assign(std::size_t(depth) + 1, CellSet{});
  for (CellSet& cells : refined_) cells.reset(0);
  heat_.assign(std::size_t(depth) + 1, Markers{});
  for (Markers& markers : heat_) markers.reset(0);
  ++stats_.geometryResets;
  lastRadius_ = -1.0;  // admissible levels depend on the cube
  incrementalValid_ = false;
}

bool AdaptiveGrid::refineCell(int level, std::int64_t i, std::int64_t j, std::int64_t k) {
  if (level >= geometry_.depth || isRefined(level, i, j, k) || !cellExists(level, i, j, k)) return false;
  // Vertices of the new patch that did not exist as full vertices before get the heat shock.
  std::vector<std::uint64_t> created;
  if (options_.type == GridType::Reluctant)
    for (std::int64_t a = 3 * i; a <= 3 * i + 3; ++a)
      for (std::int64_t b = 3 * j; b <= 3 * j + 3; ++b)
        for (std::int64_t c = 3 * k; c <= 3 * k + 3; ++c)
          if (isHanging(level + 1, a, b, c)) created.push_back(key(a, b, c));
  refined_[level].insert(key(i, j, k));
  ++gridVersion_;
  if (trackRefinements_ || reluctantTracking()) newRefined_.emplace_back(level, key(i, j, k));
  for (std::uint64_t v : created) {
    if (reluctantTracking()) {
      addShock(level + 1, v);  // also the marker's parents' inputs, kept counters, dirty sets
      continue;
    }
    std::int64_t& h = heat_[level + 1][v];
    h = std::min(kMaxHeat, h + options_.shock);
  }
  ++stats_.refinements;
  return true;
}

bool AdaptiveGrid::refineAroundVertex(int level, const Index3& v) {
  bool any = false;
  for (std::int64_t a = v.i - 1; a <= v.i; ++a)
    for (std::int64_t b = v.j - 1; b <= v.j; ++b)
      for (std::int64_t c = v.k - 1; c <= v.k; ++c) any |= refineCell(level, a, b, c);
  return any;
}

void AdaptiveGrid::refineNaively(const double (*x)[3], int n) {
  hostsCurrent_ = false;  // hosts are set here, not by rehostAll
  // Refine the 2^d cells around the host vertex while a drop would sieve the particle to the
  // next finer level; those cells hold every cell its next nearest vertex needs, so each
  // round drops it by one level (the paper cascades within one top-down sweep, too).
  for (int i = 0; i < n; ++i) {
    while (host_[i] < admissible_[i]) {
      const int l = host_[i];
      refineAroundVertex(l, nearestVertex(l, x[i]));
      host_[i] = computeHost(x[i], admissible_[i]);
      if (host_[i] <= l) break;  // defensive: no progress
    }
  }
}

void AdaptiveGrid::searchClosePairs(const double (*x)[3], const double (*v)[3], const double* radius,
                                    int n) {
  // Candidate pairs: bounding spheres (+ eps each) overlap and the particles approach.
  closePairs_.clear();
  pairSearch_.build(x, radius, n, n, geometry_, host_.data());
  pairSearch_.forEachPairWithin([&](int a, int b, double) {
    if (v) {
      double approach = 0.0;
      for (int d = 0; d < 3; ++d) approach += (x[b][d] - x[a][d]) * (v[b][d] - v[a][d]);
      if (!(approach < 0.0)) return;
    }
    closePairs_.emplace_back(a, b);
  });
}

void AdaptiveGrid::refineForPairs(const double (*x)[3], const double (*v)[3], const double* radius,
                                  int n, const int* first, const int* second, std::size_t count) {
  if (options_.type != GridType::Reluctant || !haveGeometry_ || n != int(host_.size())) return;
  closePairs_.clear();
  for (std::size_t k = 0; k < count; ++k) {
    const int a = first[k], b = second[k];
    if (a < 0 || b < 0 || a >= n || b >= n) continue;
    // Refinement only drops particles, so a pair of two particles already on their admissible
    // levels never triggers one (in any round of refineForClosePairs): skip it before the
    // approach test (random loads of x and v).
    if (host_[a] >= admissible_[a] && host_[b] >= admissible_[b]) continue;
    if (v) {
      double approach = 0.0;
      for (int d = 0; d < 3; ++d) approach += (x[b][d] - x[a][d]) * (v[b][d] - v[a][d]);
      if (!(approach < 0.0)) continue;
    }
    closePairs_.emplace_back(a, b);
  }
  refineForClosePairs(x, radius, n);
  beginSpareCheck(x, v, radius, n, first, second, count);
  coarsenReluctant(x, n);
  collectStatistics();
}

bool AdaptiveGrid::linksToCell(int level, const Index3& c, const double q[3], double radius) const {
  const double h = meshSize(level);
  const double reach = radius + 2.0 * options_.epsilon + std::sqrt(3.0) * h;
  for (int corner = 0; corner < 8; ++corner) {
    const double vx = geometry_.origin[0] + double(c.i + (corner & 1)) * h;
    const double vy = geometry_.origin[1] + double(c.j + ((corner >> 1) & 1)) * h;
    const double vz = geometry_.origin[2] + double(c.k + ((corner >> 2) & 1)) * h;
    const double dx = q[0] - vx, dy = q[1] - vy, dz = q[2] - vz;
    if (dx * dx + dy * dy + dz * dz < reach * reach) return true;
  }
  return false;
}

void AdaptiveGrid::refineForClosePairs(const double (*x)[3], const double* radius, int n) {
  // Refine the cell containing particle p if p would drop and q is held by the cell's 2^d
  // vertices (real there, or virtual: coarser and within the link radius of a vertex). The
  // neighbours p's next finer vertex needs are refined with it, so that p really drops.
  // Repeated while drops happen: one sweep may cascade over several levels.
  for (int round = 0; round <= geometry_.depth; ++round) {
    bool refined = false;
    const std::size_t firstRefined = newRefined_.size();
    for (const auto& pair : closePairs_) {
      for (int side = 0; side < 2; ++side) {
        const int p = side ? pair.second : pair.first, q = side ? pair.first : pair.second;
        const int l = host_[p];
        if (l >= admissible_[p] || host_[q] > l) continue;
        const Index3 c = cellOf(l, x[p]);
        bool held = false;
        if (host_[q] == l) {
          const Index3 w = nearestVertex(l, x[q]);
          held = w.i >= c.i && w.i <= c.i + 1 && w.j >= c.j && w.j <= c.j + 1 && w.k >= c.k && w.k <= c.k + 1;
        } else {
          held = linksToCell(l, c, x[q], radius[q]);
        }
        if (!held) continue;
        const Index3 w = nearestVertex(l + 1, x[p]);
        for (std::int64_t a = w.i - 1; a <= w.i; ++a)
          for (std::int64_t b = w.j - 1; b <= w.j; ++b)
            for (std::int64_t e = w.k - 1; e <= w.k; ++e)
              if (a >= 0 && b >= 0 && e >= 0) refined |= refineCell(l, a / 3, b / 3, e / 3);
      }
    }
    if (!refined) break;
    if (reluctantTracking())
      rehostAroundRefined(x, firstRefined);  // only particles that read a refined cell
    else
      rehostAll(x, n);
  }
}

void AdaptiveGrid::updateHeatMarkers(const double (*x)[3], int n) {
  // Annealing (reluctant): halve, add the particles of the vertex, add the children's markers.
  // Only levels below the start-off grid can be coarsened, so only they keep markers.
  std::vector<Markers>& next = heatNext_;
  next.resize(heat_.size());
  for (std::size_t l = 0; l < next.size(); ++l) next[l].reset(heat_[l].size());
  for (int i = 0; i < n; ++i) {
    const int l = host_[i];
    if (l <= regularDepth_) continue;
    const Index3 v = nearestVertex(l, x[i]);
    ++next[l][key(v.i, v.j, v.k)];
  }
  for (int l = geometry_.depth; l > regularDepth_; --l) {
    for (std::size_t s = 0; s < heat_[l].size(); ++s) {
      const std::int64_t m = heat_[l].values[s];
      if (m / 2 > 0) next[l][heat_[l].keys[s]] += m / 2;
    }
    if (l < geometry_.depth)
      for (std::size_t s = 0; s < next[l + 1].size(); ++s) {
        const std::int64_t m = next[l + 1].values[s];
        const VertexIndex w = unpackVertexKey(next[l + 1].keys[s]);
        forEachParentVertex(l, w.i, w.j, w.k, [&](std::uint64_t u) {
          std::int64_t& h = next[l][u];
          h = std::min(kMaxHeat, h + m);
        });
      }
  }
  heat_.swap(next);
}

void AdaptiveGrid::coarsen(const double (*x)[3], int n) {
  const int depth = geometry_.depth;
  if (depth <= regularDepth_) return;
  // Analysed tree grammar, bottom-up: a vertex is *not* a coarsening candidate if it is hot
  // (adaptive: holds a particle; reluctant: marker >= threshold) or one of its children is not
  // a candidate.
  // Open-addressing sets (plus key lists) per level: the parent propagation inserts up to
  // 27 keys per kept vertex, which dominated the update with node-based hash sets.
  std::vector<KeySet>& keep = keep_;
  if (keep.size() < std::size_t(depth) + 1) keep.resize(std::size_t(depth) + 1);
  if (options_.type == GridType::Reluctant) {
    for (int l = regularDepth_ + 1; l <= depth; ++l) {
      keep[l].reset(heat_[l].size());
      for (std::size_t s = 0; s < heat_[l].size(); ++s)
        if (heat_[l].values[s] > 0 && heat_[l].values[s] >= options_.coarseningThreshold)
          keep[l].insert(heat_[l].keys[s]);  // (the incremental annealing leaves zeros behind)
    }
  } else {
    std::vector<std::size_t> perLevel(std::size_t(depth) + 1, 0);
    for (int i = 0; i < n; ++i) ++perLevel[host_[i]];
    for (int l = regularDepth_ + 1; l <= depth; ++l) keep[l].reset(perLevel[l]);
    for (int i = 0; i < n; ++i) {
      const int l = host_[i];
      if (l <= regularDepth_) continue;
      const Index3 v = nearestVertex(l, x[i]);
      keep[l].insert(key(v.i, v.j, v.k));
    }
  }
  for (int l = depth - 1; l > regularDepth_; --l) {
    // Grows the table for this level's own hot vertices plus all parents of the finer ones.
    keep[l].reserveMore(27 * keep[l + 1].keys.size());
    // Children 3m+1 and 3m+2 have the same parents: skip a vertex whose parent range equals
    // the previous one's (keys come in spatially coherent order, so this saves many inserts).
    std::int64_t last[3] = {-1, -1, -1};
    for (std::uint64_t k : keep[l + 1].keys) {
      const VertexIndex w = unpackVertexKey(k);
      const std::int64_t range[3] = {w.i % 3 == 0 ? w.i : w.i - w.i % 3 + 1, w.j % 3 == 0 ? w.j : w.j - w.j % 3 + 1,
                                     w.k % 3 == 0 ? w.k : w.k - w.k % 3 + 1};
      if (range[0] == last[0] && range[1] == last[1] && range[2] == last[2]) continue;
      last[0] = range[0];
      last[1] = range[1];
      last[2] = range[2];
      forEachParentVertex(l, w.i, w.j, w.k, [&](std::uint64_t u) { keep[l].insert(u); });
    }
  }
  // Finest first, so whole empty subtrees collapse in one update: remove the 3^d children of
  // a refined cell if none of them is refined and all their non-hanging vertices are
  // candidates. Decisions of one level are taken before its removals change hanging status.
  // Driven from the few blockers, not from the many cells: each refined child and each kept
  // non-hanging child vertex marks the parent cells it blocks (a vertex on a parent boundary
  // blocks up to 2^d of them), instead of 64 vertex tests per refined cell.
  std::vector<std::uint64_t>& removals = removals_;
  for (int l = depth - 1; l >= regularDepth_; --l) {
    removals.clear();
    VertexKeySet& blocked = parentsOfRefined_;
    blocked.reset((l + 1 < depth ? refined_[l + 1].size() : 0) + 2 * keep[l + 1].keys.size());
    if (l + 1 < depth)
      for (std::uint64_t childKey : refined_[l + 1].keys) {
        const VertexIndex c = unpackVertexKey(childKey);
        blocked.insert(key(c.i / 3, c.j / 3, c.k / 3));
      }
    for (std::uint64_t vertexKey : keep[l + 1].keys) {
      const VertexIndex w = unpackVertexKey(vertexKey);
      if (w.i < 0 || w.j < 0 || w.k < 0 || isHanging(l + 1, w.i, w.j, w.k)) continue;
      // Parent cells c with 3c <= w <= 3c + 3 per axis.
      const std::int64_t ai = w.i % 3 == 0 && w.i > 0 ? w.i / 3 - 1 : w.i / 3;
      const std::int64_t aj = w.j % 3 == 0 && w.j > 0 ? w.j / 3 - 1 : w.j / 3;
      const std::int64_t ak = w.k % 3 == 0 && w.k > 0 ? w.k / 3 - 1 : w.k / 3;
      for (std::int64_t a = ai; a <= w.i / 3; ++a)
        for (std::int64_t b = aj; b <= w.j / 3; ++b)
          for (std::int64_t e = ak; e <= w.k / 3; ++e) blocked.insert(key(a, b, e));
    }
    for (std::uint64_t cellKey : refined_[l].keys) {
      if (blocked.contains(cellKey)) continue;
      if (wouldRefineAgain(l, cellKey)) {
        ++stats_.spared;
        continue;
      }
      removals.push_back(cellKey);
    }
    refined_[l].eraseAll(removals);
    if (!removals.empty()) ++gridVersion_;
    stats_.coarsenings += removals.size();
  }
}

int AdaptiveGrid::admissibleFor(double radius) {
  if (radius != lastRadius_) {  // radii repeat (species): skip the level search
    lastRadius_ = radius;
    lastAdmissible_ = finestFit(pairSearch_.requiredMeshSize(radius));
  }
  return lastAdmissible_;
}

void AdaptiveGrid::update(const double (*x)[3], const double (*v)[3], const double* radius, int n) {
  stats_.refinements = 0;
  stats_.coarsenings = 0;
  stats_.spared = 0;
  n = std::max(n, 0);
  if (options_.type != GridType::Regular && options_.incremental && incrementalValid_ && n > 0 &&
      n == int(host_.size()) && !needsNewGeometry(x, radius, n) &&
      (options_.type == GridType::Adaptive ? updateIncrementally(x, radius, n)
                                           : updateReluctantIncrementally(x, v, radius, n))) {
    collectStatistics();
    return;
  }
  incrementalValid_ = false;
  stats_.incremental = false;
  stats_.rehosted = std::uint64_t(n);
  hostsCurrent_ = false;  // particles moved
  host_.assign(std::size_t(n), 0);
  admissible_.resize(std::size_t(n));
  if (n == 0) {
    collectStatistics();
    return;
  }
  if (needsNewGeometry(x, radius, n)) chooseGeometry(x, radius, n);
  int coarsestFit = geometry_.depth, finestFitAll = 0;
  for (int i = 0; i < n; ++i) {
    admissible_[i] = admissibleFor(radius[i]);
    coarsestFit = std::min(coarsestFit, admissible_[i]);
    finestFitAll = std::max(finestFitAll, admissible_[i]);
  }
  regularDepth_ = options_.type == GridType::Regular ? finestFitAll : coarsestFit;
  // Stored refinements now inside the everywhere-refined levels are redundant.
  for (int l = 0; l < regularDepth_ && l < int(refined_.size()); ++l)
    if (refined_[l].size()) refined_[l].reset(0);
  ++gridVersion_;  // the start-off depth may have changed

  rehostAll(x, n);  // particles moved: drops and lifts on the current grid
  switch (options_.type) {
    case GridType::Regular: break;
    case GridType::Adaptive: refineNaively(x, n); break;
    case GridType::Reluctant:
      updateHeatMarkers(x, n);
      if (!options_.pairsFromCaller) {
        searchClosePairs(x, v, radius, n);
        refineForClosePairs(x, radius, n);
      }
      break;
  }
  // Naive refinement re-hosts each particle it refines for; refinements elsewhere only add
  // cells, so they cannot make a host vertex hanging.
  if (options_.type == GridType::Reluctant) rehostAll(x, n);
  // Adaptive: every host vertex is kept, so the cells around it and (having refined children)
  // all their ancestors stay: no host changes, no re-host needed.
  if (options_.type == GridType::Adaptive) coarsen(x, n);
  // Reluctant: coarsening follows the refinement pass (here, or refineForPairs after the
  // caller's sweep), with its pairs; particles under removed cells lift.
  if (options_.type == GridType::Reluctant && !options_.pairsFromCaller) {
    beginSpareCheck(x, v, radius, n, nullptr, nullptr, 0);
    coarsenReluctant(x, n);
  }
  if (options_.type == GridType::Adaptive && options_.incremental) resetIncrementalState(x, n);
  if (options_.type == GridType::Reluctant && options_.incremental) resetReluctantState(x, radius, n);
  collectStatistics();
}

// ---------------------------------------------------------------------------------------------
// Incremental adaptive update. After a (full or incremental) adaptive update every particle is
// hosted on its admissible level, on a non-hanging vertex that the coarsening keeps. So a
// particle whose admissible level and nearest vertex there are unchanged keeps its host without
// a single look-up, and its refinement needs nothing. Only the others (`moved_`) are re-hosted
// and refined for, in index order, exactly as the full update treats them. Coarsening can only
// remove cells that lost a blocker: around vertices that stopped being kept, cells refined in
// this update, and parents of removed cells (cascading up). Kept vertices are counted
// (particles hosted + kept children), so the tree grammar is updated along the changed paths
// instead of being re-derived from every particle.
// ---------------------------------------------------------------------------------------------

void AdaptiveGrid::addKept(int level, std::uint64_t vertexKey, int delta) {
  std::int64_t& count = keepCount_[level][vertexKey];
  const bool before = count > 0;
  count += delta;
  const bool after = count > 0;
  if (before == after) return;
  if (!after) lostKept_[level].push_back(vertexKey);
  if (level - 1 > regularDepth_) {
    const VertexIndex w = unpackVertexKey(vertexKey);
    forEachParentVertex(level - 1, w.i, w.j, w.k,
                        [&](std::uint64_t u) { addKept(level - 1, u, after ? 1 : -1); });
  }
}

void AdaptiveGrid::resetIncrementalState(const double (*x)[3], int n) {
  const std::size_t levels = std::size_t(geometry_.depth) + 1;
  hostKey_.resize(std::size_t(n));
  keepCount_.resize(levels);
  for (Markers& counts : keepCount_) counts.reset(0);
  lostKept_.assign(levels, {});
  candidates_.resize(levels);
  for (int i = 0; i < n; ++i) {
    const Index3 v = nearestVertex(host_[i], x[i]);
    hostKey_[i] = key(v.i, v.j, v.k);
    if (host_[i] > regularDepth_) addKept(host_[i], hostKey_[i], 1);
  }
  keepEntries_ = 0;
  for (const Markers& counts : keepCount_) keepEntries_ += counts.size();
  incrementalValid_ = true;
}

bool AdaptiveGrid::updateIncrementally(const double (*x)[3], const double* radius, int n) {
  // Counters of vertices that are no longer kept stay as zeros: rebuild when they pile up.
  std::size_t entries = 0;
  for (const Markers& counts : keepCount_) entries += counts.size();
  if (entries > 2 * keepEntries_ + 4096) return false;
  int coarsestFit = geometry_.depth;
  moved_.clear();
  for (int i = 0; i < n; ++i) {
    const int admissible = admissibleFor(radius[i]);
    coarsestFit = std::min(coarsestFit, admissible);
    bool moved = admissible != admissible_[i] || host_[i] != admissible;
    admissible_[i] = admissible;
    if (!moved) {
      const Index3 v = nearestVertex(admissible, x[i]);
      moved = key(v.i, v.j, v.k) != hostKey_[i];
    }
    if (moved) moved_.push_back(i);
  }
  if (coarsestFit != regularDepth_) return false;  // the start-off grid changes: full update

  for (auto& lost : lostKept_) lost.clear();
  newRefined_.clear();
  // Re-host the moved particles on the grid of the last update, then refine for them.
  for (int i : moved_) {
    if (host_[i] > regularDepth_) addKept(host_[i], hostKey_[i], -1);
    host_[i] = computeHost(x[i], admissible_[i]);
  }
  trackRefinements_ = true;
  for (int i : moved_) {
    while (host_[i] < admissible_[i]) {
      const int l = host_[i];
      refineAroundVertex(l, nearestVertex(l, x[i]));
      host_[i] = computeHost(x[i], admissible_[i]);
      if (host_[i] <= l) break;  // defensive: no progress (re-examined next update)
    }
  }
  trackRefinements_ = false;
  for (int i : moved_) {
    const Index3 v = nearestVertex(host_[i], x[i]);
    hostKey_[i] = key(v.i, v.j, v.k);
    if (host_[i] > regularDepth_) addKept(host_[i], hostKey_[i], 1);
  }
  coarsenAroundLostVertices();
  stats_.incremental = true;
  stats_.rehosted = moved_.size();
  hostsCurrent_ = false;
  return true;
}

bool AdaptiveGrid::isBlocked(int level, std::int64_t i, std::int64_t j, std::int64_t k) const {
  // As in coarsen(): a refined child, or a kept non-hanging vertex of the children's patch.
  if (level + 1 < geometry_.depth)
    for (std::int64_t a = 3 * i; a < 3 * i + 3; ++a)
      for (std::int64_t b = 3 * j; b < 3 * j + 3; ++b)
        for (std::int64_t c = 3 * k; c < 3 * k + 3; ++c)
          if (refined_[level + 1].contains(key(a, b, c))) return true;
  for (std::int64_t a = 3 * i; a <= 3 * i + 3; ++a)
    for (std::int64_t b = 3 * j; b <= 3 * j + 3; ++b)
      for (std::int64_t c = 3 * k; c <= 3 * k + 3; ++c)
        if (isKept(level + 1, key(a, b, c)) && !isHanging(level + 1, a, b, c)) return true;
  return false;
}

void AdaptiveGrid::coarsenAroundLostVertices() {
  const int depth = geometry_.depth;
  if (depth <= regularDepth_) return;
  for (int m = regularDepth_; m < depth; ++m) candidates_[m].reset(0);
  for (int l = regularDepth_ + 1; l <= depth; ++l)
    for (std::uint64_t vertexKey : lostKept_[l]) {
      if (isKept(l, vertexKey)) continue;  // lost and regained within this update
      const VertexIndex w = unpackVertexKey(vertexKey);
      // Parent cells c with 3c <= w <= 3c + 3 per axis (the cells this vertex blocked).
      const std::int64_t ai = w.i % 3 == 0 && w.i > 0 ? w.i / 3 - 1 : w.i / 3;
      const std::int64_t aj = w.j % 3 == 0 && w.j > 0 ? w.j / 3 - 1 : w.j / 3;
      const std::int64_t ak = w.k % 3 == 0 && w.k > 0 ? w.k / 3 - 1 : w.k / 3;
      for (std::int64_t a = ai; a <= w.i / 3; ++a)
        for (std::int64_t b = aj; b <= w.j / 3; ++b)
          for (std::int64_t e = ak; e <= w.k / 3; ++e)
            if (refined_[l - 1].contains(key(a, b, e))) candidates_[l - 1].insert(key(a, b, e));
    }
  for (const auto& cell : newRefined_)
    if (cell.first >= regularDepth_ && cell.first < depth) candidates_[cell.first].insert(cell.second);
  for (const auto& cell : spared_)  // spared last time: the criterion may no longer hold
    if (cell.first >= regularDepth_ && cell.first < depth) candidates_[cell.first].insert(cell.second);
  spared_.clear();
  std::vector<std::uint64_t>& removals = removals_;
  for (int m = depth - 1; m >= regularDepth_; --m) {
    removals.clear();
    for (std::uint64_t cellKey : candidates_[m].keys) {  // decide the whole level first
      if (!refined_[m].contains(cellKey)) continue;
      const VertexIndex c = unpackVertexKey(cellKey);
      if (isBlocked(m, c.i, c.j, c.k)) continue;
      if (wouldRefineAgain(m, cellKey)) {
        spared_.emplace_back(m, cellKey);
        ++stats_.spared;
        continue;
      }
      removals.push_back(cellKey);
    }
    if (removals.empty()) continue;
    refined_[m].eraseAll(removals);
    ++gridVersion_;
    stats_.coarsenings += removals.size();
    if (reluctantTracking())
      for (std::uint64_t cellKey : removals) removedCells_.emplace_back(m, cellKey);
    if (m - 1 >= regularDepth_)
      for (std::uint64_t cellKey : removals) {  // the parent lost a refined child
        const VertexIndex c = unpackVertexKey(cellKey);
        candidates_[m - 1].insert(key(c.i / 3, c.j / 3, c.k / 3));
      }
  }
}

void AdaptiveGrid::buildSpacetree(Spacetree& tree, const double (*x)[3], const double* radius, int n,
                                  int nActive) const {
  if (n <= 0 || !haveGeometry_) {
    tree.build(x, radius, n, nActive);  // nothing to place (e.g. an MPI rank without atoms)
    return;
  }
  tree.build(x, radius, n, nActive, geometry_, host_.data());
}

std::vector<std::uint64_t> AdaptiveGrid::verticesPerLevel() const {
  // Non-hanging vertices (all 2^d adjacent cells exist). Costs up to 64 hanging tests per
  // refined cell, so it is counted on request (output), not in every update.
  std::vector<std::uint64_t> count(haveGeometry_ ? std::size_t(geometry_.depth) + 1 : 0, 0);
  for (int l = 0; l < int(count.size()); ++l) {
    if (l <= regularDepth_) {
      const std::uint64_t c = std::uint64_t(cellsPerAxis(l));
      count[l] = (c + 1) * (c + 1) * (c + 1);
      continue;
    }
    // A vertex shared by several refined parents is counted by the first of them (lowest
    // index per axis); the 8 interior ones of a patch are never hanging.
    for (std::uint64_t cellKey : refined_[l - 1].keys) {
      const VertexIndex c = unpackVertexKey(cellKey);
      for (std::int64_t a = 3 * c.i; a <= 3 * c.i + 3; ++a)
        for (std::int64_t b = 3 * c.j; b <= 3 * c.j + 3; ++b)
          for (std::int64_t e = 3 * c.k; e <= 3 * c.k + 3; ++e) {
            if (a % 3 != 0 && b % 3 != 0 && e % 3 != 0) {
              ++count[l];
              continue;
            }
            if (isHanging(l, a, b, e)) continue;
            // Non-hanging: every parent cell around it is refined; the owner has the lowest.
            const bool owner = (a != 3 * c.i || a == 0) && (b != 3 * c.j || b == 0) &&
                               (e != 3 * c.k || e == 0);
            if (owner) ++count[l];
          }
    }
  }
  return count;
}

std::uint64_t AdaptiveGrid::leafCellCount() const {
  if (!haveGeometry_) return 0;
  // Every cell at or below the start-off level is a leaf unless it is refined.
  const std::uint64_t n = std::uint64_t(cellsPerAxis(regularDepth_));
  std::uint64_t leaves = n * n * n;
  for (int l = regularDepth_; l < geometry_.depth; ++l) {
    leaves -= refined_[l].size();
    leaves += 27 * refined_[l].size();
  }
  return leaves;
}

void AdaptiveGrid::collectStatistics() {
  const int depth = haveGeometry_ ? geometry_.depth : 0;
  stats_.levels.assign(std::size_t(depth) + 1, AdaptiveLevelStatistics{});
  stats_.cells = 0;
  stats_.regularDepth = regularDepth_;
  stats_.deepestLevel = 0;
  if (!haveGeometry_) return;
  for (int l = 0; l <= depth; ++l) {
    AdaptiveLevelStatistics& s = stats_.levels[l];
    s.meshSize = meshSize(l);
    if (l <= regularDepth_) {
      const std::uint64_t c = std::uint64_t(cellsPerAxis(l));
      s.cells = c * c * c;
    } else {
      s.cells = 27 * refined_[l - 1].size();
    }
    stats_.cells += s.cells;
  }
  for (int h : host_) {
    ++stats_.levels[h].realParticles;
    stats_.deepestLevel = std::max(stats_.deepestLevel, h);
  }
}

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
  w[kHaveGeometry] = haveGeometry_ ? 1 : 0;
  for (int d = 0; d < 3; ++d) w[kOrigin0 + d] = wordOfDouble(geometry_.origin[d]);
  w[kRootSize] = wordOfDouble(geometry_.rootSize);
  w[kDepth] = geometry_.depth;
  w[kRegularDepth] = regularDepth_;
  w[kResets] = std::int64_t(stats_.geometryResets);
  w[kRefinements] = std::int64_t(stats_.refinements);
  w[kCoarsenings] = std::int64_t(stats_.coarsenings);
  // Sets in ascending key order: the words depend on the grid's content only, not on the order
  // in which an (incremental or full) update happened to insert and erase the keys; what the
  // updates compute depends on the content only.
  std::vector<std::uint64_t> sorted;
  w.push_back(std::int64_t(refined_.size()));
  for (const CellSet& cells : refined_) {
    sorted.assign(cells.keys.begin(), cells.keys.end());
    std::sort(sorted.begin(), sorted.end());
    w.push_back(std::int64_t(sorted.size()));
    for (std::uint64_t k : sorted) w.push_back(std::int64_t(k));
  }
  std::vector<std::size_t> order;
  w.push_back(std::int64_t(heat_.size()));
  for (const Markers& markers : heat_) {
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
  if (depth < 0 || depth > grid.options_.maxLevel || regularDepth < 0 || regularDepth > depth)
    badData("bad depth");
  grid.haveGeometry_ = haveGeometry;
  for (int d = 0; d < 3; ++d) grid.geometry_.origin[d] = doubleOfWord(words[kOrigin0 + d]);
  grid.geometry_.rootSize = doubleOfWord(words[kRootSize]);
  grid.geometry_.depth = int(depth);
  if (haveGeometry && !(grid.geometry_.rootSize > 0.0 && std::isfinite(grid.geometry_.rootSize)))
    badData("bad root cube");
  grid.regularDepth_ = int(regularDepth);
  if (words[kResets] < 0 || words[kRefinements] < 0 || words[kCoarsenings] < 0) badData("bad counters");
  grid.stats_.geometryResets = std::uint64_t(words[kResets]);
  grid.stats_.refinements = std::uint64_t(words[kRefinements]);
  grid.stats_.coarsenings = std::uint64_t(words[kCoarsenings]);
  WordReader in{words, count, std::size_t(kHeaderWords)};
  // chooseGeometry() sizes both per-level lists depth + 1; before it they are empty.
  const std::size_t levels = haveGeometry ? std::size_t(depth) + 1 : 0;
  if (in.length() != levels) badData("refined cell levels do not match the depth");
  grid.refined_.assign(levels, CellSet{});
  for (std::size_t l = 0; l < levels; ++l) {
    const std::size_t n = in.length();
    CellSet& cells = grid.refined_[l];
    cells.reset(n);
    for (std::size_t s = 0; s < n; ++s) cells.insert(std::uint64_t(in.next()));
    if (cells.size() != n) badData("duplicate refined cell");
    if (n && l >= std::size_t(depth)) badData("refined cell on the finest level");
  }
  if (in.length() != levels) badData("heat marker levels do not match the depth");
  grid.heat_.assign(levels, Markers{});
  for (std::size_t l = 0; l < levels; ++l) {
    const std::size_t n = in.length();
    if (n % 2) badData("odd heat marker list");
    Markers& markers = grid.heat_[l];
    markers.reset(n / 2);
    for (std::size_t s = 0; s < n / 2; ++s) {
      const std::uint64_t k = std::uint64_t(in.next());
      const std::int64_t value = in.next();
      markers[k] = value;
      if (markers.size() != s + 1) badData("duplicate heat marker");
    }
  }
  if (in.at != count) badData("trailing words");
  // derived state: the mesh-size caches of the cube; hosts and the incremental state are
  // rebuilt by the next update() (a full one: incrementalValid_ is false)
  if (haveGeometry) grid.cacheMeshSizes();
  ++grid.gridVersion_;
  grid.collectStatistics();
  return grid;
}

}  // namespace spacetree
