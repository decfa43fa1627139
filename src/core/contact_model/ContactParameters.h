// The coefficients of one type pair, by name, from which the sub-models of a ContactModel take
// the ones they need (a sub-model that is not named never asks). Filled by the caller from
// explicit keywords and materials (MaterialMapping.h); a name missing or a value that is not a
// finite number >= 0 is reported by the sub-model that asks, naming the coefficient.
//
// Names used by the sub-models of this directory (units SI):
//   stiffness [N/m]              normal halo spring S
//   damping [sqrt(kg)/s]         approach damping D (force 2 D sqrt(m_eff) |v_n|; masses: Contact.h)
//   friction [-]                 Coulomb coefficient mu
//   slidingDamping [N s/m]       viscous sliding coefficient gamma
//   tangentialStiffness [N/m]    tangential spring k_t
//   tangentialDamping [sqrt(kg)/s]  tangential dashpot D_t (force 2 D_t sqrt(m_t) v_t)
//   rollingFriction [-]          rolling friction mu_r (rolling epsd: cap mu_r R_r F)
//   rollingDamping [-]           damping ratio eta_r of the rolling dashpot
//   cohesionEnergyDensity [J/m^3]   k_c of the sjkr-like cohesion
//   characteristicRadius [m]     R* = r_i r_j / (r_i + r_j) of the volume-equivalent radii
//   haloDepth [m]                eps
#pragma once

#include <map>
#include <string>

namespace spacetree::contact_model {

class ContactParameters {
 public:
  void set(const std::string& name, double value) { values_[name] = value; }
  bool has(const std::string& name) const { return values_.count(name) != 0; }
  // The value of `name`; std::invalid_argument "<who>: <name> missing" when absent and
  // "<who>: <name> = <v> must be >= 0" (or "> 0" with positive) when not a finite number in range.
  double require(const std::string& name, const char* who, bool positive = false) const;
  const std::map<std::string, double>& values() const { return values_; }

 private:
  std::map<std::string, double> values_;
};

}  // namespace spacetree::contact_model
