// Damping slot `approach`: the "pseudo-elastic" damping of paper eq. (1), acting only while the
// bodies approach (v_n < 0): F_d = 2 D sqrt(m_eff) (-v_n), 0 while they separate (m_eff: the
// contact point's mass along the normal, rotation included, Contact.h). Written with
// the sign that dissipates energy (the paper's sign follows its own orientation of v_ij). With
// the halo spring S, one contact point has the damping ratio zeta = D sqrt(2 / S) whatever the
// masses, and the coefficient of restitution springDashpotRestitution(zeta) (derivation in
// docs/triangulated_particles_core.md). Coefficient: damping D [sqrt(kg)/s] >= 0.
#pragma once

#include <cmath>

#include "contact_model/ContactParameters.h"
#include "contact_model/SubModel.h"

namespace spacetree::contact_model {

class DampingApproach : public DampingSubModel {
 public:
  explicit DampingApproach(const ContactParameters& p);
  double force(const Contact& c) const override {
    if (!(c.normalVelocity < 0.0)) return 0.0;
    return -(2.0 * damping_ * std::sqrt(c.effectiveMass) * c.normalVelocity);
  }
  double dampingRatio(double stiffness) const override { return damping_ * std::sqrt(2.0 / stiffness); }
  double damping() const { return damping_; }

 private:
  double damping_;
};

// Coefficient of restitution of the approach-damped linear spring with damping ratio zeta >= 0:
//   zeta < 1: exp(-zeta / sqrt(1 - zeta^2) * atan(sqrt(1 - zeta^2) / zeta)),
//   zeta = 1: exp(-1),  zeta > 1: exp(-zeta / sqrt(zeta^2 - 1) * atanh(sqrt(zeta^2 - 1) / zeta)).
double springDashpotRestitution(double zeta);
// D giving the restitution e in (0, 1] with the halo spring S (inverse of the above with
// zeta = D sqrt(2 / S)); std::invalid_argument for e outside (0, 1] or S <= 0.
double dampingForRestitution(double stiffness, double restitution);

}  // namespace spacetree::contact_model
