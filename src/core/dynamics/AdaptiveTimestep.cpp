#include "dynamics/AdaptiveTimestep.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace spacetree {

double contactSpeed(double normalSpeed, double normalAcceleration, double contactTime) {
  if (!(contactTime > 0.0)) throw std::invalid_argument("contactSpeed: contact time must be > 0");
  const double spring = normalAcceleration * contactTime / M_PI;
  return std::sqrt(normalSpeed * normalSpeed + spring * spring);
}

double contactCeiling(const TimestepPolicy& policy, double contactSpeed) {
  if (!(policy.impactSpeed > 0.0)) return policy.dtContact;
  if (!(policy.dtRest > 0.0)) throw std::invalid_argument("contactCeiling: dtRest must be > 0");
  if (!(contactSpeed > 0.0)) return policy.dtRest;
  return std::min(policy.dtRest, policy.dtContact * policy.impactSpeed / contactSpeed);
}

TimestepDecision nextTimestep(double dt, const TimestepPolicy& policy, const TimestepLimits& limits,
                              double vetoLimit) {
  if (!(policy.creep >= 1.0 && policy.creep <= kMaxCreep))
    throw std::invalid_argument("nextTimestep: creep factor must be in [1, 2]");
  if (!(dt > 0.0)) throw std::invalid_argument("nextTimestep: dt must be > 0");
  double next = policy.creep * dt;
  if (policy.dtMax > 0.0) next = std::min(next, policy.dtMax);
  if (limits.inContact && policy.dtContact > 0.0) next = std::min(next, contactCeiling(policy, limits.contactSpeed));
  if (limits.maxSpeed > 0.0) {
    if (limits.finestCell > 0.0) next = std::min(next, (limits.finestCell + limits.halo) / limits.maxSpeed);
    // LIGGGHTS rebuilds its lists when a particle moved skin/2: never move further in one step
    if (limits.skin > 0.0) next = std::min(next, 0.5 * limits.skin / limits.maxSpeed);
    // no pair outside the list may touch within the step (two particles close in at 2 v_max)
    if (limits.listMargin > 0.0) next = std::min(next, 0.5 * limits.listMargin / limits.maxSpeed);
  }
  TimestepDecision decision;
  if (vetoLimit < next) {
    next = vetoLimit;
    decision.vetoed = true;
  }
  if (next < policy.dtMin) {
    decision.floored = true;
    next = policy.dtMin;
  }
  decision.dt = next;
  return decision;
}

}  // namespace spacetree
