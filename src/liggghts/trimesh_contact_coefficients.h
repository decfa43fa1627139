/* spacetree-dem: the contact model of pair_style trimesh for every type pair, from the
   pair_style keywords and the LIGGGHTS materials (fix property/global youngsModulus,
   poissonsRatio [peratomtype], coefficientRestitution, coefficientFriction,
   coefficientRollingFriction, coefficientRollingViscousDamping, cohesionEnergyDensity
   [peratomtypepair]); explicit keywords override the materials for every
   type pair. The mapping of materials to halo coefficients is the core's
   (contact_model/MaterialMapping.h); this file looks them up, checks them and says which one is
   missing or out of range, and prints per type pair the coefficients, the contact time and the
   largest stable time step. */

#ifndef LMP_TRIMESH_CONTACT_COEFFICIENTS_H
#define LMP_TRIMESH_CONTACT_COEFFICIENTS_H

#include <limits>
#include <vector>

#include "contact_model/ContactModel.h"
#include "contact_model/MaterialMapping.h"
#include "pointers.h"

namespace LAMMPS_NS {

struct TrimeshTypeTemplate;

struct TrimeshContactSettings {
  spacetree::contact_model::ContactModelSpec spec;
  double eps = 0.0;
  // explicit coefficients for every type pair; NaN: not given (from the materials)
  double stiffness = std::numeric_limits<double>::quiet_NaN();             // N/m
  double damping = std::numeric_limits<double>::quiet_NaN();               // sqrt(kg)/s
  double friction = std::numeric_limits<double>::quiet_NaN();              // -
  double sliding_damping = std::numeric_limits<double>::quiet_NaN();       // N s/m
  double tangential_stiffness = std::numeric_limits<double>::quiet_NaN();  // N/m
  bool rotation = true;   // pair_style keyword rotation (the stable step's contact point masses)
};

class TrimeshContactCoefficients : protected Pointers {
 public:
  explicit TrimeshContactCoefficients(class LAMMPS *lmp) : Pointers(lmp) {}
  // One model per type pair that can touch: grains and obstacles (template types, not both
  // fixed), and a template type with a type without template (spheres, or the material type of
  // a fix wall/gran wall); error->all naming the keyword or material property and the type pair
  // otherwise. sphere_radius[t] (t without template): the largest radius of its atoms (its
  // characteristic radius), 0 for none (a wall's material: a plane, infinite radius).
  spacetree::contact_model::ContactModelTable build(const TrimeshContactSettings &settings,
                                                   class FixTrimeshTemplate *templ,
                                                   const std::vector<double> &sphere_radius);
  // Rank 0 prints, per type pair: S, D, restitution, friction, k_t, contact time, largest stable
  // time step (pairs of grains and obstacles; with a sphere or wall type, the coefficients);
  // warns when the time step exceeds the smallest.
  void report(const spacetree::contact_model::ContactModelTable &table,
              const TrimeshContactSettings &settings, class FixTrimeshTemplate *templ);
  // Largest stable time step of one contact point per type pair, at [i*(ntypes+1)+j]: pairs of
  // grains and obstacles (the lightest contact point, as report() prints it); +inf otherwise.
  std::vector<double> stable_steps(const spacetree::contact_model::ContactModelTable &table,
                                   const TrimeshContactSettings &settings, class FixTrimeshTemplate *templ);

 private:
  spacetree::contact_model::ContactParameters parameters(int i, int j,
                                                         const TrimeshContactSettings &settings,
                                                         class FixTrimeshTemplate *templ,
                                                         const std::vector<double> &sphere_radius);
  spacetree::contact_model::ContactTiming timing(const spacetree::contact_model::ContactModel &model,
                                                 const TrimeshContactSettings &settings,
                                                 const TrimeshTypeTemplate *ti,
                                                 const TrimeshTypeTemplate *tj);
  class FixPropertyGlobal *material(const char *name, bool pair, const char *why);
  double per_type(const char *name, int t, const char *why);
  double per_pair(const char *name, int i, int j, const char *why);
};

}

#endif
