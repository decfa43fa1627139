// The slots of a contact model (the form of modern LAMMPS GRANULAR: one class per physical
// effect, composed at input time). Each sub-model takes its coefficients for one type pair from
// ContactParameters when it is built and declares how many doubles of per-contact history it
// keeps (a class with history: static constexpr int kHistorySize, returned by historySize(), so
// that the registry knows it before any coefficient); ContactModel gives it the offset of its
// part of a contact's history slot.
// A sub-model holds no mutable state: evaluate-calls on different contacts may run concurrently.
//
// Sign conventions: Contact.h. Normal and damping forces are magnitudes along the repulsive
// sense (pushing i along -n, j along +n), cohesion a magnitude along the attractive sense; the
// tangential sub-model returns the force on the first body; the rolling sub-model a torque on
// the first body (the second gets the opposite).
#pragma once

#include <Eigen/Core>

#include "contact_model/Contact.h"

namespace spacetree::contact_model {

enum class Slot { Normal, Damping, Tangential, Rolling, Cohesion };

// "normal", "damping", "tangential", "rolling", "cohesion"
const char* slotName(Slot slot);

class SubModel {
 public:
  virtual ~SubModel() = default;
  virtual Slot slot() const = 0;
  // Doubles of per-contact history this sub-model keeps (0: none); zero for a new contact.
  virtual int historySize() const { return 0; }
  void setHistoryOffset(int offset) { historyOffset_ = offset; }
  int historyOffset() const { return historyOffset_; }

 private:
  int historyOffset_ = 0;
};

class NormalSubModel : public SubModel {
 public:
  Slot slot() const override { return Slot::Normal; }
  // Elastic normal force (repulsive magnitude) [N].
  virtual double force(const Contact& c) const = 0;
  // Stiffness d force / d penetration at small penetration [N/m] (time-step estimates).
  virtual double stiffness() const = 0;
};

class DampingSubModel : public SubModel {
 public:
  Slot slot() const override { return Slot::Damping; }
  // Dissipative normal force added to the elastic one (repulsive sense) [N].
  virtual double force(const Contact& c) const = 0;
  // Damping ratio of one contact point with normal stiffness `stiffness` (time-step estimates).
  virtual double dampingRatio(double stiffness) const = 0;
};

class TangentialSubModel : public SubModel {
 public:
  Slot slot() const override { return Slot::Tangential; }
  // Force on the first body for a (repulsive) normal force normalForce >= 0; `history` is this
  // sub-model's part of the contact's history slot, updated over the time step dt [s]; dt = 0:
  // the force of the stored history, which is left as it is.
  virtual Eigen::Vector3d forceOnFirst(const Contact& c, double normalForce, double* history,
                                       double dt) const = 0;
  // Stiffness of the tangential spring [N/m], 0 without one (time-step estimates).
  virtual double stiffness() const { return 0.0; }
  // D_t of its dashpot [sqrt(kg)/s], 0 without one (time-step estimates).
  virtual double damping() const { return 0.0; }
};

class RollingSubModel : public SubModel {
 public:
  Slot slot() const override { return Slot::Rolling; }
  // Torque on the first body (the second gets its opposite) for a (repulsive) normal force
  // normalForce >= 0; `history` and dt as for the tangential slot.
  virtual Eigen::Vector3d torqueOnFirst(const Contact& c, double normalForce, double* history,
                                        double dt) const = 0;
  // Stiffness of the rolling spring at rolling radius R_r [N m/rad], 0 without one, and the
  // damping ratio of its dashpot (time-step estimates).
  virtual double stiffness(double /*rollingRadius*/) const { return 0.0; }
  virtual double dampingRatio() const { return 0.0; }
};

class CohesionSubModel : public SubModel {
 public:
  Slot slot() const override { return Slot::Cohesion; }
  // Attractive normal force (magnitude) [N].
  virtual double force(const Contact& c) const = 0;
  // The force that pulls one contact point apart [N] (warnings, time-step estimates).
  virtual double pullOffForce() const = 0;
};

}  // namespace spacetree::contact_model
