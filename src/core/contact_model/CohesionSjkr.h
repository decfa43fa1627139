// Cohesion slot `sjkr`: surface-energy cohesion in the manner of LIGGGHTS' `cohesion sjkr`,
// F_coh = k_c A (k_c: cohesionEnergyDensity [J/m^3], A: contact area), adapted to the halo
// contact. sjkr takes A = pi a^2 of the lens where two spheres overlap by delta, a^2 = R* delta.
// Here the halos of depth eps overlap by delta = 2 eps - d; at the overlap 2 eps (rigid surfaces
// touching) that area is A = 2 pi R* eps, and this sub-model applies it over the whole halo band:
//   F_coh = 2 pi R* eps k_c   while the halos overlap (penetration > 0), attractive, 0 outside.
// Why constant: the halo spring is linear in the overlap, so an area that grows linearly with it
// (sjkr on spheres, whose Hertz spring grows faster) would only soften the spring and never hold
// two bodies together. With a constant force per contact point a pair rests at the penetration
// F_coh / S (one point) and comes apart when pulled by more than F_coh per contact point: the
// pull-off force of one contact point is F_coh, whatever the stiffness (JKR-like). R* = r_i r_j /
// (r_i + r_j) of the types' volume-equivalent radii (r of a fixed obstacle: infinite, R* = r_i).
// Coefficients: cohesionEnergyDensity k_c >= 0, characteristicRadius R* > 0, haloDepth eps > 0.
#pragma once

#include "contact_model/ContactParameters.h"
#include "contact_model/SubModel.h"

namespace spacetree::contact_model {

class CohesionSjkr : public CohesionSubModel {
 public:
  explicit CohesionSjkr(const ContactParameters& p);
  double force(const Contact& c) const override { return c.penetration > 0.0 ? pullOff_ : 0.0; }
  // F_coh = 2 pi R* eps k_c [N]: the pull-off force of one contact point.
  double pullOffForce() const override { return pullOff_; }

 private:
  double pullOff_;
};

}  // namespace spacetree::contact_model
