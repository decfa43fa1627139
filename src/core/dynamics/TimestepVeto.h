// Veto on critical approaches (paper §5.2): for every approaching pair the neighbour search
// visits, project both velocities on the centre line; if the relative approach within one
// time step would close the remaining gap between the particles' halos, the pair is critical
// and the time step is cut to a safe fraction of the time that gap takes to close.
// The smallest cut over all critical pairs wins.
#pragma once

#include <cstdint>
#include <limits>

namespace spacetree {

class TimestepVeto {
 public:
  // halo: distance beyond the sum of radii at which contact starts (2 eps for triangulated
  //       particles, 0 for spheres whose surfaces touch);
  // safety: fraction of the gap-closing time granted to a critical pair (0 < safety <= 1).
  TimestepVeto(double halo, double safety);

  // Forget the pairs of the last step.
  void reset();

  // One pair with centres xi, xj, velocities vi, vj and radii ri, rj, against step dt.
  // Receding pairs and pairs already within the halo (in contact) are not critical.
  void consider(const double xi[3], const double vi[3], double ri, const double xj[3],
                const double vj[3], double rj, double dt);

  // The largest time step all critical pairs allow (+inf when none was critical).
  double limit() const { return limit_; }
  std::uint64_t criticalPairs() const { return critical_; }

 private:
  double halo_, safety_;
  double limit_ = std::numeric_limits<double>::infinity();
  std::uint64_t critical_ = 0;
};

}  // namespace spacetree
