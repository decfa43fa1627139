// Veto on critical approaches (paper §5.2): for every approaching pair the neighbour search
// visits, project both velocities on the centre line; if the relative approach within one
// time step would close the remaining gap between the particles' halos, the pair is critical
// and the time step is cut to a safe fraction of the time that gap takes to close.
// The smallest cut over all critical pairs wins.
//
// Spheres (soft contact from touching surfaces on): the gap may be closed by up to an allowed
// overlap eps, i.e. the veto keeps the kinematically extrapolated penetration
// delta + v_n dt of every approaching pair within eps. Pairs already deeper than eps are not
// critical: shrinking the next step cannot undo that penetration (the rollback handles it).
//
// Triangulated particles (halo eps_h, contact while the surfaces are closer than 2 eps_h): the
// caller measures the surface distance d and the closing speed along the shortest segment, and
// haloGap() turns them into the distance left before the halo penetration eps_h - d/2 exceeds
// the allowed one; considerGap() then decides as for spheres.
#pragma once

#include <cstdint>
#include <limits>

namespace spacetree {

class TimestepVeto {
 public:
  // halo: distance beyond the sum of radii at which contact starts (2 eps for triangulated
  //       particles, 0 for spheres whose surfaces touch);
  // safety: fraction of the gap-closing time granted to a critical pair (0 < safety <= 1).
  // allowedOverlap: penetration eps a pair may reach before it counts as violated (>= 0).
  TimestepVeto(double halo, double safety, double allowedOverlap = 0.0);

  // Forget the pairs of the last step.
  void reset();

  // One pair with centres xi, xj, velocities vi, vj and radii ri, rj, against step dt.
  // Critical when the step dt exceeds the safe step (safety times the time the closing speed
  // takes to use up the gap, plus the allowed overlap); returns whether it was.
  // Receding pairs and pairs already deeper than allowed are not critical.
  bool consider(const double xi[3], const double vi[3], double ri, const double xj[3],
                const double vj[3], double rj, double dt);

  // One pair given by the distance `gap` it may still close before it counts as violated (<= 0:
  // already deeper, not critical) and its closing speed (<= 0: not approaching), against step dt.
  // Same decision as consider(); the halo and allowed overlap of the constructor are not used.
  bool considerGap(double gap, double closingSpeed, double dt);

  // The largest time step all critical pairs allow (+inf when none was critical).
  double limit() const { return limit_; }
  std::uint64_t criticalPairs() const { return critical_; }

 private:
  double halo_, safety_, allowedOverlap_;
  double limit_ = std::numeric_limits<double>::infinity();
  std::uint64_t critical_ = 0;
};

// Triangulated particles: the distance two surfaces `distance` apart may still close before the
// halo penetration halo - distance/2 of the pair exceeds allowedPenetration (<= halo):
// distance - 2 halo + 2 allowedPenetration.
double haloGap(double distance, double halo, double allowedPenetration);

}  // namespace spacetree
