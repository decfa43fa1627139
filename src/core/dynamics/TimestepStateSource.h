// One part of the simulation state that a rolled-back step puts back (TimestepRollback.h decides
// when). The time-step fix collects the sources (the atoms, the contact histories, and any pair
// style or fix that keeps state of its own and implements this interface) in a
// TimestepStateSnapshot; each source copies and restores only its own state.
#pragma once

namespace spacetree {

class TimestepStateSource {
 public:
  // When save() is called in every step (never while a rejected step is redone).
  enum class Moment {
    // At the start of the step (the end of the one before): what the integrator starts from.
    // Atoms may be sorted or change rank before the rollback: keep the copy by atom ID.
    StepStart,
    // After the step's re-neighbouring, just before the forces: nothing moves an atom to another
    // rank or place until the rollback, so the copy may follow the local order (per-contact state).
    BeforeForces
  };

  virtual ~TimestepStateSource() = default;

  virtual Moment moment() const = 0;
  virtual void save() = 0;
  // Whether restore() can put the copy back now, changing nothing (e.g. false when atoms were
  // added or deleted since save()). Called on every rank, so it may communicate.
  virtual bool restorable() { return true; }
  // Puts the copy back; only called after every source on every rank said restorable().
  virtual void restore() = 0;
};

}  // namespace spacetree
