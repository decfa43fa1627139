#include "dynamics/TimestepVeto.h"

#include <cmath>
#include <stdexcept>

namespace spacetree {

TimestepVeto::TimestepVeto(double halo, double safety, double allowedOverlap)
    : halo_(halo), safety_(safety), allowedOverlap_(allowedOverlap) {
  if (!(halo >= 0.0) || !std::isfinite(halo)) throw std::invalid_argument("TimestepVeto: halo must be >= 0");
  if (!(safety > 0.0 && safety <= 1.0)) throw std::invalid_argument("TimestepVeto: safety must be in (0, 1]");
  if (!(allowedOverlap >= 0.0) || !std::isfinite(allowedOverlap))
    throw std::invalid_argument("TimestepVeto: allowed overlap must be >= 0");
}

void TimestepVeto::reset() {
  limit_ = std::numeric_limits<double>::infinity();
  critical_ = 0;
}

bool TimestepVeto::consider(const double xi[3], const double vi[3], double ri, const double xj[3],
                            const double vj[3], double rj, double dt) {
  const double d[3] = {xj[0] - xi[0], xj[1] - xi[1], xj[2] - xi[2]};
  const double distance = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  if (!(distance > 0.0)) return false;
  // closing speed along the centre line: positive when the pair approaches
  const double approach =
      -((vj[0] - vi[0]) * d[0] + (vj[1] - vi[1]) * d[1] + (vj[2] - vi[2]) * d[2]) / distance;
  if (!(approach > 0.0)) return false;
  // distance left before the pair penetrates deeper than allowed
  return considerGap(distance - ri - rj - halo_ + allowedOverlap_, approach, dt);
}

bool TimestepVeto::considerGap(double gap, double closingSpeed, double dt) {
  if (!(closingSpeed > 0.0)) return false;
  if (!(gap > 0.0)) return false;            // already deeper: a smaller step cannot undo it
  const double safe = safety_ * gap / closingSpeed;
  if (dt <= safe) return false;              // the step stays within the safe fraction of the gap
  ++critical_;
  if (safe < limit_) limit_ = safe;
  return true;
}

double haloGap(double distance, double halo, double allowedPenetration) {
  return distance - 2.0 * halo + 2.0 * allowedPenetration;
}

}  // namespace spacetree
