// Rollback of a step that penetrated too deep (beyond paper §5.2, which names it as missing):
// after a step, if the deepest overlap exceeds a set fraction of the allowed overlap eps and
// the step itself caused that (the overlap before the step was within the bound), the caller
// restores the state of the step's start and redoes it with a smaller time step.
#pragma once

namespace spacetree {

struct RollbackPolicy {
  double fraction = 0.5;  // redo when the deepest overlap exceeds fraction * eps
  double shrink = 0.5;    // each redo uses shrink * dt (never below dtMin)
  int maxRetries = 20;    // redos of one step before it is accepted anyway
};

struct RollbackDecision {
  bool redo = false;       // restore and redo the step with dt
  double dt = 0.0;         // step to redo with (when redo)
  bool exhausted = false;  // too deep, but dtMin or maxRetries reached: accepted anyway
};

// overlapBefore / overlapAfter: deepest overlap at the step's start / end (0 = no contact);
// retries: redos of this step so far.
RollbackDecision judgeStep(const RollbackPolicy& policy, double eps, double overlapBefore,
                           double overlapAfter, double dt, double dtMin, int retries);

}  // namespace spacetree
