// Adaptive global time step (paper §5.2): creeping growth dt <- min(C dt, caps), with caps
// from the mesh and the fastest particle (no particle may cross more than a cell, nor leave
// LIGGGHTS' skin between list rebuilds), a user ceiling, and the veto of critical approaches.
#pragma once


namespace spacetree {

// Largest growth factor per step: a step that more than doubles at once does not creep (with
// C = 1e300 the step jumps to its caps after every collapse; a two-sphere hooke collision then
// gains energy instead of keeping restitution 0.5).
inline constexpr double kMaxCreep = 2.0;

struct TimestepPolicy {
  double creep = 1.1;    // growth factor C per step, in [1, kMaxCreep]
  double dtMin = 0.0;    // floor: a veto never cuts below it (reported when hit)
  double dtMax = 0.0;    // ceiling (e.g. a fraction of the contact time); 0 = none
  double dtContact = 0.0;  // ceiling while any pair is in contact (resolves the contact); 0 = none
  // State-dependent contact ceiling (0 = off: dtContact for every contact). dtContact then
  // resolves a contact of speed impactSpeed; a contact of speed w (contactSpeed()) gets
  // dtContact * impactSpeed / w, at most dtRest (stability of an enduring contact).
  double impactSpeed = 0.0;
  double contactTime = 0.0;  // shortest contact time tc of the system: omega = pi / tc
  double dtRest = 0.0;
  // Stability ceiling: while in contact the step is at most TimestepLimits::stableStep, the
  // largest stable step of the contacts present (triangulated grains: of their type pairs).
  bool stableCeiling = false;
};

struct TimestepLimits {
  double finestCell = 0.0;  // h_min of the grid in use (0 = unknown)
  double halo = 0.0;        // 2 eps
  double skin = 0.0;        // neighbour-list skin (0 = no list constraint)
  double maxSpeed = 0.0;    // fastest particle
  bool inContact = false;   // some pair overlaps now (dtContact applies)
  // largest contactSpeed() over the pairs in contact or about to touch (impactSpeed > 0 only)
  double contactSpeed = 0.0;
  // relative approach the current neighbour list still covers: skin - 2 * (largest displacement
  // since the list was built); pairs outside the list are at least this far apart (0 = no limit)
  double listMargin = 0.0;
  // with inContact and TimestepPolicy::stableCeiling: the smallest largest-stable-step of the
  // pairs in contact or about to touch (0 = none known)
  double stableStep = 0.0;
};

// What set the step (the smallest of the bounds; the first of them in this order on a tie).
enum class TimestepLimiter {
  Creep,        // growth C dt: no bound was reached
  Ceiling,      // dtMax
  Contact,      // the contact ceiling (dtContact, or with impactSpeed the contact-speed one)
  Rest,         // dtRest: the contacts are slow, the enduring-contact ceiling applies
  Stable,       // the stability ceiling of the contacts present (stableCeiling)
  Mesh,         // (h_min + halo) / v_max
  Skin,         // skin / (2 v_max)
  ListMargin,   // list margin / (2 v_max)
  Veto,         // a critical approach
  Floor         // dtMin (the rest asked for less)
};
// Short lower-case name ("creep", "dtmax", "contact", "rest", "stable", "mesh", "skin", "margin",
// "veto", "dtmin"): the `limit` column of fix adapt/timestep's file.
const char* limiterName(TimestepLimiter limiter);

struct TimestepDecision {
  double dt = 0.0;
  bool vetoed = false;    // a critical approach cut the step
  bool floored = false;   // the caps or the veto asked for less than dtMin
  TimestepLimiter limiter = TimestepLimiter::Creep;
};

// Speed of a contact's normal oscillation about its current equilibrium, sqrt(vn^2 + (an/omega)^2)
// with vn, an the relative normal velocity and acceleration and omega = pi / tc: a linear contact
// obeys an = -omega^2 (delta - delta_eq), so this is the velocity amplitude of the oscillation.
// For an undamped impact of free particles it is constant through the contact and equals the
// approach speed at entry (no dip at the peak, where vn = 0 but an is largest); for an enduring
// contact under a steady load (a resting column) it is ~0 however deep the static overlap.
double contactSpeed(double normalSpeed, double normalAcceleration, double contactTime);

// The ceiling the contacts allow: dtContact, or with impactSpeed > 0
// min(dtRest, dtContact * impactSpeed / contactSpeed). The per-step normal displacement
// w dt of the fastest contact stays at impactSpeed * dtContact, so its absolute energy and
// peak-overlap errors (both ~ m_eff w^2 (omega dt)^2) stay at those of an impact at impactSpeed.
double contactCeiling(const TimestepPolicy& policy, double contactSpeed);

// The step after one of size dt; vetoLimit is the largest step the critical approaches allow
// (TimestepVeto::limit(), reduced over all ranks; +inf when none).
TimestepDecision nextTimestep(double dt, const TimestepPolicy& policy, const TimestepLimits& limits,
                              double vetoLimit);

}  // namespace spacetree
