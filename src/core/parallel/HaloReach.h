// The per-size ghost rule (newton off, contact history kept): how far a particle must be sent
// to neighbouring subdomains and periodic images so that every rank holds, as owned atom or
// ghost, every partner its owned particles can touch before the next list rebuild, i.e. every j
// with |x_i - x_j| <= (r_i + r_j) f + skin (f = contact_distance_factor) for an owned i.
//
// Particles are exchanged class by class, coarse first (HaloSizeClasses). A particle of class k
// needs two reaches:
//  * its own: (r + R_k) f + skin, R_k the largest radius of class k. That reaches every rank
//    owning a partner of the same class or a finer one (partner radius <= R_k) - the whole
//    shell of a small particle is thin, only the big ones reach far;
//  * to every coarser partner b it can touch that another subdomain (or periodic image) owns:
//    the L-infinity distance to the box of b's owner. b reached this rank in an earlier pass
//    (its own reach covers the pair), so the rank knows which big ghosts it must serve.
// reach() is the larger of the two. A rank sends a particle across a face when it lies within
// its reach of the face (LIGGGHTS' x, y, z exchange), so it arrives in every subdomain whose
// box lies within that L-infinity distance, the owner of b among them.
//
// Partners with a surface (HaloSurface: fixed obstacles) are touched only near their surface,
// not throughout their bounding sphere.
#pragma once

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "parallel/HaloSurface.h"
#include "parallel/SubdomainGrid.h"

namespace spacetree::parallel {

struct HaloRule {
  double skin = 0.0;           // neighbour skin
  double contactFactor = 1.0;  // pair cut-off (r_i + r_j) * contactFactor + skin
  // Every particle reaches at least its radius plus this (0: no floor): a ghost cut-off the
  // user asked for, or the reach an insertion overlap check needs.
  double minimumShell = 0.0;
  double slack = 0.0;          // absolute rounding allowance added to every reach (length)
};

class HaloReach {
 public:
  HaloReach() = default;
  HaloReach(const HaloRule& rule, const SubdomainGrid& grid) : rule_(rule), grid_(grid) {}

  const HaloRule& rule() const { return rule_; }
  const SubdomainGrid& grid() const { return grid_; }

  // Reach for the partners of the particle's own class and the finer ones.
  double ownReach(double radius, double classLargest) const;

  // The box of this rank's own subdomain (its particles lie inside): partners that cannot reach
  // it are not indexed. Default: unbounded.
  void setOwnBox(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) { ownLo_ = lo; ownHi_ = hi; }

  // Coarse partners: ghosts of coarser classes (their coordinates as this rank holds them).
  void clearPartners();
  // `surface` (may be null) must outlive the queries.
  void addPartner(const Eigen::Vector3d& x, double radius, const HaloSurface* surface = nullptr);
  // Indexes the partners added since the last call, for particles of radius <= finerLargest
  // (skipping those farther from the own box than they reach).
  void indexPartners(double finerLargest);
  std::size_t partnerCount() const { return partners_.size(); }
  std::size_t indexedPartnerCount() const;

  // Can a particle (x, radius) touch the partner before the next rebuild?
  bool canTouch(const Eigen::Vector3d& x, double radius, int partner) const;

  // max(ownReach, distance to the owner box of every indexed partner the particle can touch);
  // `served` (optional) tells whether a partner needed more than the own reach.
  double reach(const Eigen::Vector3d& x, double radius, double classLargest,
               bool* served = nullptr) const;

 private:
  struct Partner {
    Eigen::Vector3d x;
    double radius;
    const HaloSurface* surface;
  };
  // The partners of one indexing call in a dense grid of cells at least as wide as their
  // largest reach (so a particle finds every partner it can touch in the 3 x 3 x 3 cells around
  // it), over their bounding box: a particle outside the box widened by a cell is rejected at
  // once, which is most particles when the partners are a few big ones.
  struct Index {
    double cell = 0.0;
    Eigen::Vector3d lo = Eigen::Vector3d::Zero();       // corner of cell (0, 0, 0)
    std::array<std::int64_t, 3> dims{{0, 0, 0}};
    std::vector<int> start;                             // CSR: cell c holds order[start[c], start[c+1])
    std::vector<int> order;                             // partner indices
  };
  double touchReach(const Partner& b, double radius) const;

  HaloRule rule_;
  SubdomainGrid grid_;
  Eigen::Vector3d ownLo_ = Eigen::Vector3d::Constant(-INFINITY), ownHi_ = Eigen::Vector3d::Constant(INFINITY);
  std::vector<Partner> partners_;
  std::vector<Index> indexes_;
  std::size_t indexed_ = 0;  // partners_[0, indexed_) are in indexes_
};

}  // namespace spacetree::parallel
