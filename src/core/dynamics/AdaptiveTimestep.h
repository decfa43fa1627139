// Adaptive global time step (paper §5.2): creeping growth dt <- min(C dt, caps), with caps
// from the mesh and the fastest particle (no particle may cross more than a cell, nor leave
// LIGGGHTS' skin between list rebuilds), a user ceiling, and the veto of critical approaches.
#pragma once


namespace spacetree {

struct TimestepPolicy {
  double creep = 1.1;    // growth factor C > 1 per step
  double dtMin = 0.0;    // floor: a veto never cuts below it (reported when hit)
  double dtMax = 0.0;    // ceiling (e.g. a fraction of the contact time); 0 = none
  double dtContact = 0.0;  // ceiling while any pair is in contact (resolves the contact); 0 = none
};

struct TimestepLimits {
  double finestCell = 0.0;  // h_min of the grid in use (0 = unknown)
  double halo = 0.0;        // 2 eps
  double skin = 0.0;        // neighbour-list skin (0 = no list constraint)
  double maxSpeed = 0.0;    // fastest particle
  bool inContact = false;   // some pair overlaps now (dtContact applies)
  // relative approach the current neighbour list still covers: skin - 2 * (largest displacement
  // since the list was built); pairs outside the list are at least this far apart (0 = no limit)
  double listMargin = 0.0;
};

struct TimestepDecision {
  double dt = 0.0;
  bool vetoed = false;    // a critical approach cut the step
  bool floored = false;   // the caps or the veto asked for less than dtMin
};

// The step after one of size dt; vetoLimit is the largest step the critical approaches allow
// (TimestepVeto::limit(), reduced over all ranks; +inf when none).
TimestepDecision nextTimestep(double dt, const TimestepPolicy& policy, const TimestepLimits& limits,
                              double vetoLimit);

}  // namespace spacetree
