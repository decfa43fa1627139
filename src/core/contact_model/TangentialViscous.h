// Tangential slot `viscous`: viscous sliding friction capped by Coulomb's law,
//   f_t = min(gamma |v_t|, mu F) v_t / |v_t|  on body i (j gets -f_t), v_t = v_ij - v_n n,
// so i is dragged along with j's sliding and the relative sliding is damped. No spring and no
// history: at rest it exerts no force (a grain on a slope creeps; use `history` for static
// friction). Coefficients: friction mu >= 0, slidingDamping gamma [N s/m] >= 0.
#pragma once

#include "contact_model/ContactParameters.h"
#include "contact_model/SubModel.h"

namespace spacetree::contact_model {

class TangentialViscous : public TangentialSubModel {
 public:
  explicit TangentialViscous(const ContactParameters& p);
  Eigen::Vector3d forceOnFirst(const Contact& c, double normalForce, double* history,
                               double dt) const override;

 private:
  double friction_, slidingDamping_;
};

}  // namespace spacetree::contact_model
