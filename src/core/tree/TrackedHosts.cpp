#include "tree/TrackedHosts.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

namespace spacetree {

double TrackedHosts::hostMargin(const RefinedCells& cells, const double p[3], int admissible, int host,
                                int descent) {
  // Distance to the nearest floor boundary of the scaled coordinate on a descent level
  // (cellOf) or a lift level (nearestVertex), less a bound on the rounding of
  // (p - origin) * (1 / h).
  const GridGeometry& g = cells.geometry();
  const double scale = std::max({std::abs(p[0]), std::abs(p[1]), std::abs(p[2])}) +
                       std::max({std::abs(g.origin[0]), std::abs(g.origin[1]), std::abs(g.origin[2])}) +
                       g.rootSize;
  const double rounding = 64.0 * DBL_EPSILON * scale;
  double margin = std::numeric_limits<double>::infinity();
  auto limit = [&](int level, double shift) {
    const double inv = cells.inverseMeshSize(level);
    for (int d = 0; d < 3; ++d) {
      const double y = (p[d] - g.origin[d]) * inv + shift;
      const double f = y - std::floor(y);
      margin = std::min(margin, (std::min(f, 1.0 - f) - 1e-9) * cells.cachedMeshSize(level));
    }
  };
  const int first = std::max(0, std::min(cells.regularDepth(), admissible));
  for (int l = first; l <= std::min(descent, admissible - 1); ++l) limit(l, 0.0);  // cellOf
  for (int l = host; l <= descent; ++l) limit(l, 0.5);                           // nearestVertex
  return margin - rounding;
}

void TrackedHosts::link(int i, int level) {
  std::int64_t& first = firstAtVertex_[level][hostKey_[i]];
  previousAtVertex_[i] = -1;
  nextAtVertex_[i] = int(first) - 1;
  if (first > 0) previousAtVertex_[first - 1] = i;
  first = i + 1;
}

void TrackedHosts::unlink(int i, int level) {
  const int before = previousAtVertex_[i], after = nextAtVertex_[i];
  if (before >= 0)
    nextAtVertex_[before] = after;
  else
    firstAtVertex_[level][hostKey_[i]] = after + 1;
  if (after >= 0) previousAtVertex_[after] = before;
}

void TrackedHosts::rehost(HostedGrid& g, HeatMarkers& heat, const double (*x)[3], int i) {
  const int regularDepth = g.cells.regularDepth();
  int descent;
  const int host = g.cells.hostPath(x[i], g.admissible[i], descent);
  const Index3 v = g.cells.nearestVertex(host, x[i]);
  const std::uint64_t hostKey = packVertexKey(v.i, v.j, v.k);
  if (host != g.host[i] || hostKey != hostKey_[i]) {
    unlink(i, g.host[i]);
    if (g.host[i] > regularDepth) heat.addParticle(g.host[i], hostKey_[i], -1);
    g.host[i] = host;
    hostKey_[i] = hostKey;
    link(i, host);
    if (host > regularDepth) heat.addParticle(host, hostKey, 1);
  }
  for (int d = 0; d < 3; ++d) referencePosition_[i][d] = x[i][d];
  margin_[i] = hostMargin(g.cells, x[i], g.admissible[i], host, descent);
  if (!(margin_[i] > 0.0)) fragile_.push_back(i);
  ++rehostCount_;
}

void TrackedHosts::rehostQueued(HostedGrid& g, HeatMarkers& heat, const double (*x)[3]) {
  // A particle whose derivation reads a cell only up to rounding (margin <= 0) may not be
  // found through the lists: re-derive it at every grid change.
  // They are listed again by rehost() if still fragile.
  for (int i : fragile_)
    if (!queued_[i]) {
      queued_[i] = 1;
      rehostQueue_.push_back(i);
    }
  fragile_.clear();
  for (int i : rehostQueue_) {
    queued_[i] = 0;
    rehost(g, heat, x, i);
  }
  rehostQueue_.clear();
}

void TrackedHosts::rehostMoved(HostedGrid& g, HeatMarkers& heat, const double (*x)[3], const double* radius,
                               const std::vector<int>& newAdmissible) {
  rehostCount_ = 0;
  fragile_.clear();
  const int n = int(newAdmissible.size());
  for (int i = 0; i < n; ++i) {
    const double moved = std::max({std::abs(x[i][0] - referencePosition_[i][0]),
                                   std::abs(x[i][1] - referencePosition_[i][1]),
                                   std::abs(x[i][2] - referencePosition_[i][2])});
    hostRadius_[i] = radius[i];
    if (newAdmissible[i] == g.admissible[i] && moved < margin_[i]) continue;
    g.admissible[i] = newAdmissible[i];
    rehost(g, heat, x, i);
  }
}

void TrackedHosts::rehostAroundRefined(HostedGrid& g, HeatMarkers& heat, const double (*x)[3],
                                       const std::vector<LevelCell>& refined, std::size_t firstRefined) {
  // Refining cell C of level l changes what the host derivation reads for particles whose
  // descent stopped at C or whose nearest vertex on level l + 1 has C among its parent cells;
  // both are hosted on a level L <= l, at a corner of C's ancestor on level L (they lie within
  // h(l)/6 of C).
  const RefinedCells& cells = g.cells;
  for (std::size_t r = firstRefined; r < refined.size(); ++r) {
    const int l = refined[r].first;
    const VertexIndex c = unpackVertexKey(refined[r].second);
    const std::int64_t last = cells.cellsPerAxis(l + 1) - 1;
    // Readers lie within half a child cell of C: a box test first (0.6 for the rounding).
    const double child = cells.cachedMeshSize(l + 1);
    double lo[3], hi[3];
    const std::int64_t corner[3] = {c.i, c.j, c.k};
    for (int d = 0; d < 3; ++d) {
      lo[d] = cells.geometry().origin[d] + (3.0 * double(corner[d]) - 0.6) * child;
      hi[d] = cells.geometry().origin[d] + (3.0 * double(corner[d]) + 3.6) * child;
    }
    auto reads = [&](const double p[3]) {
      if (p[0] < lo[0] || p[0] > hi[0] || p[1] < lo[1] || p[1] > hi[1] || p[2] < lo[2] || p[2] > hi[2])
        return false;
      const Index3 cell = cells.cellOf(l, p);
      if (cell.i == c.i && cell.j == c.j && cell.k == c.k) return true;
      const Index3 w = cells.nearestVertex(l + 1, p);
      auto parent = [last](std::int64_t wd, std::int64_t cd) {
        return std::max<std::int64_t>(wd - 1, 0) / 3 <= cd && cd <= std::min(wd, last) / 3;
      };
      return parent(w.i, c.i) && parent(w.j, c.j) && parent(w.k, c.k);
    };
    std::int64_t ai = c.i, aj = c.j, ak = c.k;
    for (int level = l; level >= cells.regularDepth(); --level) {
      for (std::int64_t a = ai; a <= ai + 1; ++a)
        for (std::int64_t b = aj; b <= aj + 1; ++b)
          for (std::int64_t e = ak; e <= ak + 1; ++e)
            for (int i = int(firstAtVertex_[level].get(packVertexKey(a, b, e))) - 1; i >= 0; i = nextAtVertex_[i])
              if (!queued_[i] && reads(x[i])) {
                queued_[i] = 1;
                rehostQueue_.push_back(i);
              }
      ai /= 3;
      aj /= 3;
      ak /= 3;
    }
  }
  rehostQueued(g, heat, x);
}

void TrackedHosts::rehostAroundRemoved(HostedGrid& g, HeatMarkers& heat, const double (*x)[3],
                                       std::vector<LevelCell>& removed) {
  // Removing cell C of level l changes hosts only of particles hosted on level l + 1 at a
  // vertex of C's children (that vertex becomes hanging, or the descent stops at C); particles
  // that lifted above C keep their host and read a subset of what they read before.
  for (const LevelCell& cell : removed) {
    const int l = cell.first + 1;
    const VertexIndex c = unpackVertexKey(cell.second);
    for (std::int64_t a = 3 * c.i; a <= 3 * c.i + 3; ++a)
      for (std::int64_t b = 3 * c.j; b <= 3 * c.j + 3; ++b)
        for (std::int64_t e = 3 * c.k; e <= 3 * c.k + 3; ++e)
          for (int i = int(firstAtVertex_[l].get(packVertexKey(a, b, e))) - 1; i >= 0; i = nextAtVertex_[i])
            if (!queued_[i]) {
              queued_[i] = 1;
              rehostQueue_.push_back(i);
            }
  }
  removed.clear();
  rehostQueued(g, heat, x);
}

void TrackedHosts::reset(const HostedGrid& g, const double (*x)[3], const double* radius, int n) {
  const std::size_t levels = std::size_t(g.cells.depth()) + 1;
  hostKey_.resize(std::size_t(n));
  hostRadius_.assign(radius, radius + n);
  referencePosition_.resize(std::size_t(n));
  margin_.resize(std::size_t(n));
  nextAtVertex_.resize(std::size_t(n));
  previousAtVertex_.resize(std::size_t(n));
  queued_.assign(std::size_t(n), 0);
  rehostQueue_.clear();
  fragile_.clear();
  firstAtVertex_.resize(levels);
  for (VertexCounters& m : firstAtVertex_) m.reset(0);
  // Hosts as the full update left them; the margins need the descent levels.
  for (int i = 0; i < n; ++i) {
    int descent;
    g.cells.hostPath(x[i], g.admissible[i], descent);
    const Index3 v = g.cells.nearestVertex(g.host[i], x[i]);
    hostKey_[i] = packVertexKey(v.i, v.j, v.k);
    link(i, g.host[i]);
    for (int d = 0; d < 3; ++d) referencePosition_[i][d] = x[i][d];
    margin_[i] = hostMargin(g.cells, x[i], g.admissible[i], g.host[i], descent);
    if (!(margin_[i] > 0.0)) fragile_.push_back(i);
  }
}

std::size_t TrackedHosts::entries() const {
  std::size_t entries = 0;
  for (const VertexCounters& m : firstAtVertex_) entries += m.size();
  return entries;
}

}  // namespace spacetree
