// Rolling slot `epsd`: rolling resistance by an elastic-plastic spring-dashpot on each contact
// point (the EPSD model of Iwashita & Oda 1998 and Ai et al. 2011, LIGGGHTS' rolling_model epsd).
// A point contact has no resistance to rolling about an axis through it; a real contact has an
// area, and this sub-model stands for the torque that area exerts.
// History: the rolling spring's torque M_r (3 doubles, world frame) of the contact point. Each
// step M_r is turned into the current tangent plane (Contact.h keepInTangentPlane), then
//   M_r += k_r w_r dt,   w_r = the tangential part of omega_j - omega_i (relative rolling),
// and cut back to |M_r| = mu_r R_r F when longer (full mobilisation: the contact rolls on with
// that constant torque). The torque on the first body (the second gets its opposite) is
//   tau = M_r + C_r w_r,  scaled down to mu_r R_r F if longer,
// so |tau| <= mu_r R_r F always: a body rolling at the cap is decelerated by the constant torque
// mu_r R_r F, and below it a torque M is held by the rotation M / k_r. (LIGGGHTS switches the
// dashpot off at the cap; capping the sum instead keeps the torque continuous there, as the
// tangential history model's force, so that round-off cannot switch it.) dt = 0 evaluates the
// stored M_r without changing it.
// Coefficients (per type pair, ContactParameters): rollingFriction mu_r [-] >= 0 (LIGGGHTS
// coefficientRollingFriction), rollingDamping eta_r [-] >= 0, the dashpot's damping ratio
// (LIGGGHTS coefficientRollingViscousDamping), stiffness S [N/m] of the normal halo spring.
//   k_r = 2.25 k_n mu_r^2 R_r^2 [N m/rad],  k_n = S / 2 the normal stiffness per relative
//   approach (the halo overlap per side is half the approach);
//   C_r = 2 eta_r sqrt(I_r k_r) [N m s/rad];
// R_r and I_r: Contact.h (R_r from the two lever arms; I_r about the centres).
#pragma once

#include "contact_model/ContactParameters.h"
#include "contact_model/SubModel.h"

namespace spacetree::contact_model {

class RollingEpsd : public RollingSubModel {
 public:
  static constexpr int kHistorySize = 3;  // M_r
  explicit RollingEpsd(const ContactParameters& p);
  int historySize() const override { return kHistorySize; }
  Eigen::Vector3d torqueOnFirst(const Contact& c, double normalForce, double* history,
                                double dt) const override;
  double stiffness(double rollingRadius) const override {
    return 2.25 * 0.5 * normalStiffness_ * friction_ * friction_ * rollingRadius * rollingRadius;
  }
  double dampingRatio() const override { return damping_; }
  double friction() const { return friction_; }

 private:
  double friction_, damping_, normalStiffness_;
};

}  // namespace spacetree::contact_model
