#include "dynamics/TimestepRollback.h"

#include <algorithm>
#include <stdexcept>

namespace spacetree {

RollbackDecision judgeStep(const RollbackPolicy& policy, double eps, double overlapBefore,
                           double overlapAfter, double dt, double dtMin, int retries) {
  if (!(policy.fraction > 0.0) || !(policy.shrink > 0.0 && policy.shrink < 1.0) || policy.maxRetries < 0)
    throw std::invalid_argument("judgeStep: fraction > 0, 0 < shrink < 1, maxRetries >= 0 required");
  if (!(eps > 0.0)) throw std::invalid_argument("judgeStep: eps must be > 0");
  RollbackDecision d;
  const double bound = policy.fraction * eps;
  // within the bound, or already beyond it before the step: a smaller step cannot help
  if (!(overlapAfter > bound) || overlapBefore > bound) return d;
  if (retries >= policy.maxRetries || !(dt > dtMin)) {
    d.exhausted = true;
    return d;
  }
  d.redo = true;
  d.dt = std::max(policy.shrink * dt, dtMin);
  return d;
}

}  // namespace spacetree
