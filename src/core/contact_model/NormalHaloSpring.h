// Normal slot `halo`: the spring of paper eq. (1) on the halo overlap, F = S (eps - d/2) =
// S penetration, repulsive. For one contact point the overlap of the halos x = 2 eps - d obeys
// m_eff x'' = -(S/2) x: angular frequency sqrt(S / (2 m_eff)) (docs/triangulated_particles_core.md).
// Coefficient: stiffness S [N/m] > 0.
#pragma once

#include "contact_model/ContactParameters.h"
#include "contact_model/SubModel.h"

namespace spacetree::contact_model {

class NormalHaloSpring : public NormalSubModel {
 public:
  explicit NormalHaloSpring(const ContactParameters& p);
  double force(const Contact& c) const override { return spring_ * c.penetration; }
  double stiffness() const override { return spring_; }

 private:
  double spring_;
};

}  // namespace spacetree::contact_model
