// Tangential slot `history`: static friction by a tangential spring with a Coulomb cap on each
// contact point (the linear history model of DEM codes, e.g. LAMMPS GRANULAR linear_history).
// History: the tangential displacement xi (3 doubles, world frame) of the contact point. Each
// step, before the increment, xi is rotated into the current tangent plane (its normal
// component removed, its length kept: the contact plane of a rolling or tilting pair turns);
// then xi += v_t dt, and if the spring exceeds the Coulomb limit, k_t |xi| > mu F (F the
// repulsive normal force), the contact slides: xi is cut back to |xi| = mu F / k_t (the rule of
// LIGGGHTS' tangential history model; LAMMPS' linear_history cuts spring plus dashpot, which
// turns xi against the sliding when the dashpot alone exceeds mu F, and the spring then pushes
// the body on when the sliding slows). The force
//   f_t = k_t xi + 2 D_t sqrt(m_t) v_t,  scaled down to mu F if longer,
// acts on the first body (j gets -f_t): the first body is pulled along with the second's
// relative displacement. So |f_t| <= mu F always, and at rest (v_t = 0) the spring holds up to
// mu F: static friction. dt = 0 evaluates the stored xi without changing it (the force
// computation of a run's setup repeats the last step's force: LIGGGHTS' shearupdate = 0).
// A new contact starts with xi = 0; a contact that opens loses it (the caller drops its slot).
// Coefficients: friction mu >= 0, tangentialStiffness k_t [N/m] > 0, tangentialDamping D_t
// [sqrt(kg)/s] >= 0 (m_t: the contact point's mass along the sliding, Contact.h; damping ratio
// D_t / sqrt(k_t) of the tangential oscillation m_t xi'' = -k_t xi).
#pragma once

#include "contact_model/ContactParameters.h"
#include "contact_model/SubModel.h"

namespace spacetree::contact_model {

class TangentialHistory : public TangentialSubModel {
 public:
  static constexpr int kHistorySize = 3;  // xi
  explicit TangentialHistory(const ContactParameters& p);
  int historySize() const override { return kHistorySize; }
  Eigen::Vector3d forceOnFirst(const Contact& c, double normalForce, double* history,
                               double dt) const override;
  double stiffness() const override { return stiffness_; }
  double damping() const override { return damping_; }

 private:
  double friction_, stiffness_, damping_;
};

}  // namespace spacetree::contact_model
