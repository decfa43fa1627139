// The geometry of a domain decomposition into a grid of boxes (LIGGGHTS' processor grid): the
// box [lo, hi] cut in each dimension at lo + (hi - lo) * split[i] (split ascending from 0 to 1,
// one more entry than boxes in that dimension), periodic or not per dimension.
//
// A rank that holds a particle q (its own or a ghost, in the coordinates of the periodic image
// it holds) asks which subdomain owns q and how far, in the L-infinity norm, a point p is from
// that subdomain's box (shifted to q's image). That is how far p must be sent through the
// Cartesian exchange (x, then y, then z) to arrive where q is owned.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

namespace spacetree::parallel {

class SubdomainGrid {
 public:
  SubdomainGrid() = default;
  // std::invalid_argument for hi <= lo, or splits that are not ascending from 0 to 1.
  SubdomainGrid(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                const std::array<bool, 3>& periodic,
                const std::array<std::vector<double>, 3>& splits);

  // Upper bound of the L-infinity distance from p to the box (shifted to q's periodic image)
  // of the subdomain that owns q. Exact where q lies clearly inside one box; where q lies
  // within rounding (kRelativeTolerance of the box size) of a cut or of a periodic face, both
  // boxes are candidates and the larger distance is returned. Outside a non-periodic dimension
  // the nearest box owns.
  double distanceToOwner(const Eigen::Vector3d& p, const Eigen::Vector3d& q) const;

  // L-infinity distance from p to box (i, j, k) of the grid in the image `shift` (multiples of
  // the box lengths); used by tests and for reports.
  double distanceToBox(const Eigen::Vector3d& p, const std::array<int, 3>& box,
                       const std::array<int, 3>& shift = {0, 0, 0}) const;

  int boxes(int d) const { return int(splits_[std::size_t(d)].size()) - 1; }
  const Eigen::Vector3d& lo() const { return lo_; }
  const Eigen::Vector3d& hi() const { return hi_; }
  bool periodic(int d) const { return periodic_[std::size_t(d)]; }
  // The cut i of dimension d, computed as LIGGGHTS computes its subdomain bounds.
  double cut(int d, int i) const;

  static constexpr double kRelativeTolerance = 1e-10;

 private:
  double axisDistance(int d, double p, double q) const;

  Eigen::Vector3d lo_ = Eigen::Vector3d::Zero(), hi_ = Eigen::Vector3d::Ones();
  std::array<bool, 3> periodic_{{false, false, false}};
  std::array<std::vector<double>, 3> splits_{{{0.0, 1.0}, {0.0, 1.0}, {0.0, 1.0}}};
};

}  // namespace spacetree::parallel
