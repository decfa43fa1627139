// A contact model composed from sub-models (SubModel.h), one per slot: normal, damping,
// tangential, rolling, cohesion. Only the named ones are built and evaluated. One ContactModel
// holds the coefficients of one type pair; ContactModelTable holds one per type pair of a scene
// (all with the same sub-models, hence the same history layout).
//
// Evaluation of one contact (Contact.h conventions):
//   F   = max(0, normal(c) + damping(c))                     repulsive, never attractive
//   f_i = -F n + cohesion(c) n + tangential(c, F, history)    force on the first body
//   tau_i = rolling(c, F, history)                           extra torque on the first body
// The second body gets -f_i and -tau_i; the torques of f_i about the centres are the caller's
// (dynamics/ContactForce.h applyContactForce). The tangential sub-model sees the repulsive F
// (cohesion does not raise the Coulomb limit beyond what the spring carries).
//
// History: each sub-model that keeps per-contact history gets its part of the contact's slot
// of historySize() doubles (zeros for a new contact); the caller stores the slot per contact
// (contact_model/ContactHistory.h matches contacts across steps).
#pragma once

#include <Eigen/Core>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "contact_model/Contact.h"
#include "contact_model/ContactParameters.h"
#include "contact_model/SubModel.h"

namespace spacetree::contact_model {

// Which sub-model fills each slot (registry keywords; "none" leaves a slot empty).
struct ContactModelSpec {
  std::string normal = "halo";
  std::string damping = "approach";
  std::string tangential = "none";
  std::string rolling = "none";
  std::string cohesion = "none";

  std::string& operator[](Slot slot);
  const std::string& operator[](Slot slot) const;
  // Throws std::invalid_argument for a keyword the registry does not know.
  void validate() const;
  // "normal halo damping approach tangential history" (the slots not `none`)
  std::string describe() const;
};

constexpr Slot kAllSlots[] = {Slot::Normal, Slot::Damping, Slot::Tangential, Slot::Rolling,
                              Slot::Cohesion};

struct ContactForces {
  Eigen::Vector3d forceOnFirst = Eigen::Vector3d::Zero();
  Eigen::Vector3d torqueOnFirst = Eigen::Vector3d::Zero();  // rolling only
  double normalForce = 0.0;                                 // F >= 0 (repulsive part)
};

class ContactModel {
 public:
  // Throws std::invalid_argument for an unknown keyword or a coefficient the named sub-models
  // need that is missing, negative or not finite (the message names slot and coefficient).
  ContactModel(const ContactModelSpec& spec, const ContactParameters& parameters);
  ContactModel(const ContactModel&) = delete;
  ContactModel& operator=(const ContactModel&) = delete;

  const ContactModelSpec& spec() const { return spec_; }
  int historySize() const { return historySize_; }

  // `history`: historySize() doubles (may be nullptr when 0); dt: time step [s] over which the
  // history advances; dt = 0 leaves it as it is (a repeated force computation, e.g. a run's setup).
  ContactForces evaluate(const Contact& c, double* history, double dt) const {
    ContactForces out;
    double f = normal_->force(c);
    if (damping_) f += damping_->force(c);
    const double fn = f > 0.0 ? f : 0.0;
    out.normalForce = fn;
    out.forceOnFirst = -fn * c.normal;
    if (cohesion_) out.forceOnFirst += cohesion_->force(c) * c.normal;
    if (tangential_)
      out.forceOnFirst += tangential_->forceOnFirst(c, fn, history + tangential_->historyOffset(), dt);
    if (rolling_) out.torqueOnFirst = rolling_->torqueOnFirst(c, fn, history + rolling_->historyOffset(), dt);
    return out;
  }

  const NormalSubModel& normal() const { return *normal_; }
  const DampingSubModel* damping() const { return damping_.get(); }
  const TangentialSubModel* tangential() const { return tangential_.get(); }
  const RollingSubModel* rolling() const { return rolling_.get(); }
  const CohesionSubModel* cohesion() const { return cohesion_.get(); }

 private:
  ContactModelSpec spec_;
  std::unique_ptr<NormalSubModel> normal_;
  std::unique_ptr<DampingSubModel> damping_;
  std::unique_ptr<TangentialSubModel> tangential_;
  std::unique_ptr<RollingSubModel> rolling_;
  std::unique_ptr<CohesionSubModel> cohesion_;
  int historySize_ = 0;
};

// One ContactModel per unordered type pair of types 1..n.
class ContactModelTable {
 public:
  ContactModelTable() = default;
  // parametersOf(i, j) for 1 <= i <= j <= n gives the coefficients of that pair; throws as
  // ContactModel, the message prefixed with "type pair i j: ". Pairs for which active(i, j) is
  // false (types that never touch) get no model (has() false) and need no coefficients.
  ContactModelTable(int types, const ContactModelSpec& spec,
                    const std::function<ContactParameters(int, int)>& parametersOf,
                    const std::function<bool(int, int)>& active = nullptr);

  int types() const { return types_; }
  bool empty() const { return types_ == 0; }
  const ContactModelSpec& spec() const { return spec_; }
  int historySize() const { return historySize_; }
  bool has(int i, int j) const {
    return models_[std::size_t(i - 1) * std::size_t(types_) + std::size_t(j - 1)] != nullptr;
  }
  // Types 1..types() in either order; the pair must have a model.
  const ContactModel& at(int i, int j) const {
    return *models_[std::size_t(i - 1) * std::size_t(types_) + std::size_t(j - 1)];
  }

 private:

  int types_ = 0;
  int historySize_ = 0;
  ContactModelSpec spec_;
  std::vector<std::shared_ptr<const ContactModel>> models_;  // n x n, (i, j) and (j, i) shared
};

}  // namespace spacetree::contact_model
