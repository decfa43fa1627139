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

const char* limiterName(TimestepLimiter limiter) {
  switch (limiter) {
    case TimestepLimiter::Creep: return "creep";
    case TimestepLimiter::Ceiling: return "dtmax";
    case TimestepLimiter::Contact: return "contact";
    case TimestepLimiter::Rest: return "rest";
    case TimestepLimiter::Stable: return "stable";
    case TimestepLimiter::Mesh: return "mesh";
    case TimestepLimiter::Skin: return "skin";
    case TimestepLimiter::ListMargin: return "margin";
    case TimestepLimiter::Veto: return "veto";
    case TimestepLimiter::Floor: return "dtmin";
  }
  return "?";
}

TimestepDecision nextTimestep(double dt, const TimestepPolicy& policy, const TimestepLimits& limits,
                              double vetoLimit) {
  if (!(policy.creep >= 1.0 && policy.creep <= kMaxCreep))
    throw std::invalid_argument("nextTimestep: creep factor must be in [1, 2]");
  if (!(dt > 0.0)) throw std::invalid_argument("nextTimestep: dt must be > 0");
  TimestepDecision decision;
  double next = policy.creep * dt;
  // a bound below the step so far sets it (ties keep the earlier bound)
  auto bound = [&](double value, TimestepLimiter why) {
    if (value < next) {
      next = value;
      decision.limiter = why;
    }
  };
  if (policy.dtMax > 0.0) bound(policy.dtMax, TimestepLimiter::Ceiling);
  if (limits.inContact && policy.dtContact > 0.0) {
    const double ceiling = contactCeiling(policy, limits.contactSpeed);
    bound(ceiling, policy.impactSpeed > 0.0 && ceiling == policy.dtRest ? TimestepLimiter::Rest
                                                                         : TimestepLimiter::Contact);
  }
  if (limits.inContact && policy.stableCeiling && limits.stableStep > 0.0)
    bound(limits.stableStep, TimestepLimiter::Stable);
  if (limits.maxSpeed > 0.0) {
    if (limits.finestCell > 0.0) bound((limits.finestCell + limits.halo) / limits.maxSpeed, TimestepLimiter::Mesh);
    // LIGGGHTS rebuilds its lists when a particle moved skin/2: never move further in one step
    if (limits.skin > 0.0) bound(0.5 * limits.skin / limits.maxSpeed, TimestepLimiter::Skin);
    // no pair outside the list may touch within the step (two particles close in at 2 v_max)
    if (limits.listMargin > 0.0) bound(0.5 * limits.listMargin / limits.maxSpeed, TimestepLimiter::ListMargin);
  }
  if (vetoLimit < next) {
    next = vetoLimit;
    decision.vetoed = true;
    decision.limiter = TimestepLimiter::Veto;
  }
  if (next < policy.dtMin) {
    decision.floored = true;
    decision.limiter = TimestepLimiter::Floor;
    next = policy.dtMin;
  }
  decision.dt = next;
  return decision;
}

}  // namespace spacetree
