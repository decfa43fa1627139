// The reluctant grid's incremental host derivation. A host is derived from the cells
// containing the particle (descent) and its nearest vertices (lifts) on a few levels. Each
// particle remembers the position of its last derivation and the distance to the nearest cell
// face or vertex rounding plane it read there (its margin): while it moves less, it reads the
// same cells and vertices, so only a grid change there can change its host. Grid changes
// re-derive just the particles that read the changed cell, found through per-vertex particle
// lists (a refined cell's readers are hosted on the corners of its ancestors, a removed cell's
// on its children's vertices). Hosts that change move their particle's count between heat
// markers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "tree/HeatMarkers.h"
#include "tree/HostedGrid.h"
#include "tree/VertexCounters.h"

namespace spacetree {

class TrackedHosts {
 public:
  // Tracking starts from the hosts as the full update left them.
  void reset(const HostedGrid& g, const double (*x)[3], const double* radius, int n);
  // Whether the particle's admissible level was derived for this radius.
  bool sameRadius(int i, double radius) const { return radius == hostRadius_[i]; }
  // Re-derives, on the cells of the last update, the particles that moved past their margin or
  // whose admissible level changes to newAdmissible (also taken over into g.admissible).
  void rehostMoved(HostedGrid& g, HeatMarkers& heat, const double (*x)[3], const double* radius,
                   const std::vector<int>& newAdmissible);
  // After refining the cells refined[firstRefined...]: re-derives the particles that read them.
  void rehostAroundRefined(HostedGrid& g, HeatMarkers& heat, const double (*x)[3],
                           const std::vector<LevelCell>& refined, std::size_t firstRefined);
  // After removing the cells `removed`: re-derives the particles hosted below them (and
  // empties the list).
  void rehostAroundRemoved(HostedGrid& g, HeatMarkers& heat, const double (*x)[3], std::vector<LevelCell>& removed);

  // Host vertex key per particle, and the particles per host vertex (per level: vertex -> first
  // particle + 1; then next particle, -1 ends).
  const std::vector<std::uint64_t>& hostKeys() const { return hostKey_; }
  const std::vector<VertexCounters>& firstAtVertex() const { return firstAtVertex_; }
  const std::vector<int>& nextAtVertex() const { return nextAtVertex_; }
  // Particles re-derived since rehostMoved() began this update.
  std::size_t rehostCount() const { return rehostCount_; }
  // Entries of the per-vertex table, zeros included.
  std::size_t entries() const;

 private:
  std::vector<std::uint64_t> hostKey_;
  std::vector<std::array<double, 3>> referencePosition_;
  std::vector<double> margin_;
  std::vector<double> hostRadius_;  // radius of the last admissible level derivation
  std::vector<int> fragile_;        // margin <= 0: re-derived at every grid change
  std::vector<int> nextAtVertex_, previousAtVertex_;
  std::vector<VertexCounters> firstAtVertex_;
  std::vector<int> rehostQueue_;
  std::vector<char> queued_;
  std::size_t rehostCount_ = 0;

  // How far p may move (per axis) before its derivation could read another cell or vertex.
  static double hostMargin(const RefinedCells& cells, const double p[3], int admissible, int host, int descent);
  void link(int i, int level);
  void unlink(int i, int level);
  void rehost(HostedGrid& g, HeatMarkers& heat, const double (*x)[3], int i);
  void rehostQueued(HostedGrid& g, HeatMarkers& heat, const double (*x)[3]);
};

}  // namespace spacetree
