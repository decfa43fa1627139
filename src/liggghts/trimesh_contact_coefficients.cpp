/* spacetree-dem: see trimesh_contact_coefficients.h */

#include "trimesh_contact_coefficients.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "atom.h"
#include "comm.h"
#include "contact_model/DampingApproach.h"
#include "contact_model/MaterialMapping.h"
#include "error.h"
#include "fix_property_global.h"
#include "fix_trimesh_template.h"
#include "modify.h"
#include "update.h"

using namespace LAMMPS_NS;
namespace cm = spacetree::contact_model;

namespace {

const double kInf = std::numeric_limits<double>::infinity();

std::string pair_name(int i, int j)
{
  return "type pair " + std::to_string(i) + " " + std::to_string(j);
}

// k_t / S without poissonsRatio: the classic 2/7 (a solid sphere's tangential effective mass is
// 2/7 of its mass, so normal and tangential oscillations then have one period)
const double kDefaultTangentialRatio = 2.0 / 7.0;

}

FixPropertyGlobal *TrimeshContactCoefficients::material(const char *name, bool pair, const char *why)
{
  Fix *f = modify->find_fix_property(name,"property/global",pair ? "peratomtypepair" : "peratomtype",
                                     0,0,"pair_style trimesh",false);
  if (!f) {
    // `why` names the pair_style keyword that can stand for the material, where there is one
    const std::string msg = std::string("Pair style trimesh: ") + why + " needs fix property/global " +
                            name + (pair ? " peratomtypepair" : " peratomtype");
    error->all(FLERR,msg.c_str());
  }
  FixPropertyGlobal *g = static_cast<FixPropertyGlobal *>(f);
  const int n = atom->ntypes;
  const bool short_ = pair ? (g->size_array_rows < n || g->size_array_cols < n) : g->size_vector < n;
  if (short_) {
    const std::string msg = std::string("Pair style trimesh: fix property/global ") + name +
                            " has no value for every type pair of the " + std::to_string(n) +
                            " atom types (" + why + ")";
    error->all(FLERR,msg.c_str());
  }
  return g;
}

double TrimeshContactCoefficients::per_type(const char *name, int t, const char *why)
{
  return material(name,false,why)->compute_vector(t - 1);
}

double TrimeshContactCoefficients::per_pair(const char *name, int i, int j, const char *why)
{
  return material(name,true,why)->compute_array(i - 1,j - 1);
}

cm::ContactParameters TrimeshContactCoefficients::parameters(int i, int j,
                                                             const TrimeshContactSettings &s,
                                                             FixTrimeshTemplate *templ,
                                                             const std::vector<double> &sphere_radius)
{
  const cm::ContactModelSpec &spec = s.spec;
  // volume-equivalent radii (a fixed obstacle or a wall: infinite; a sphere: its radius)
  const auto radius = [&](int t) {
    const TrimeshTypeTemplate *tt = templ->type_template(t);
    if (!tt) return sphere_radius[t] > 0.0 ? sphere_radius[t] : kInf;
    return tt->fixed ? kInf : std::cbrt(3.0 * tt->shape.volume / (4.0 * M_PI));
  };
  const double rstar = cm::effectiveRadius(radius(i),radius(j));
  const std::string where = pair_name(i,j);
  const auto check = [&](const char *property, double v, bool ok, const char *range) {
    if (!ok || !std::isfinite(v)) {
      char msg[300];
      snprintf(msg,sizeof(msg),"Pair style trimesh: %s = %g for %s must be %s",property,v,where.c_str(),range);
      error->all(FLERR,msg);
    }
  };
  // Young's modulus and Poisson's ratio: for the stiffness unless given, and for Mindlin's
  // tangential stiffness (history without tangential_stiffness) when poissonsRatio exists
  const bool stiffness_from_materials = std::isnan(s.stiffness);
  const bool mindlin = spec.tangential == "history" && std::isnan(s.tangential_stiffness) &&
      modify->find_fix_property("poissonsRatio","property/global","peratomtype",0,0,"pair_style trimesh",false);
  double youngs_i = 0, youngs_j = 0, poisson_i = 0, poisson_j = 0;
  if (stiffness_from_materials || mindlin) {
    const char *why = stiffness_from_materials ? "the stiffness (no pair_style keyword stiffness)"
                                               : "the tangential stiffness (no pair_style keyword tangential_stiffness)";
    youngs_i = per_type("youngsModulus",i,why);
    youngs_j = per_type("youngsModulus",j,why);
    poisson_i = per_type("poissonsRatio",i,why);
    poisson_j = per_type("poissonsRatio",j,why);
    check("youngsModulus",youngs_i,youngs_i > 0,"> 0 (Pa)");
    check("youngsModulus",youngs_j,youngs_j > 0,"> 0 (Pa)");
    check("poissonsRatio",poisson_i,poisson_i >= 0 && poisson_i < 0.5,"in [0, 0.5)");
    check("poissonsRatio",poisson_j,poisson_j >= 0 && poisson_j < 0.5,"in [0, 0.5)");
  }
  const bool have_poisson = stiffness_from_materials || mindlin;

  cm::ContactParameters p;
  p.set("haloDepth",s.eps);
  p.set("characteristicRadius",rstar);
  const double stiffness = std::isnan(s.stiffness)
      ? cm::haloStiffness(cm::effectiveModulus(youngs_i,poisson_i,youngs_j,poisson_j),rstar)
      : s.stiffness;
  p.set("stiffness",stiffness);
  if (spec.damping != "none") {
    double damping = s.damping;
    if (std::isnan(damping)) {
      const double e = per_pair("coefficientRestitution",i,j,"the damping (no pair_style keyword damping)");
      check("coefficientRestitution",e,e > 0 && e <= 1,"in (0, 1]");
      damping = cm::dampingForRestitution(stiffness,e);
    }
    p.set("damping",damping);
  }
  if (spec.tangential != "none") {
    double mu = s.friction;
    if (std::isnan(mu)) {
      mu = per_pair("coefficientFriction",i,j,"the friction (no pair_style keyword friction)");
      check("coefficientFriction",mu,mu >= 0,">= 0");
    }
    p.set("friction",mu);
    if (!std::isnan(s.sliding_damping)) p.set("slidingDamping",s.sliding_damping);
    double kt = s.tangential_stiffness;
    if (std::isnan(kt))
      kt = stiffness * (have_poisson ? cm::mindlinStiffnessRatio(youngs_i,poisson_i,youngs_j,poisson_j)
                                     : kDefaultTangentialRatio);
    p.set("tangentialStiffness",kt);
    // the tangential dashpot gives the tangential oscillation the normal restitution
    p.set("tangentialDamping",spec.damping != "none"
          ? cm::tangentialDampingFor(stiffness,p.values().at("damping"),kt) : 0.0);
  }
  if (spec.rolling != "none") {
    const double mur = per_pair("coefficientRollingFriction",i,j,"rolling_friction epsd");
    check("coefficientRollingFriction",mur,mur >= 0,">= 0");
    p.set("rollingFriction",mur);
    // the dashpot's damping ratio; without coefficientRollingViscousDamping the one of the
    // tangential dashpot (the normal restitution for an oscillation damped throughout)
    double eta = 0.0;
    if (modify->find_fix_property("coefficientRollingViscousDamping","property/global","peratomtypepair",
                                  0,0,"pair_style trimesh",false)) {
      eta = per_pair("coefficientRollingViscousDamping",i,j,"rolling_friction epsd");
      check("coefficientRollingViscousDamping",eta,eta >= 0,">= 0");
    } else if (spec.damping != "none") {
      eta = cm::tangentialDampingFor(stiffness,p.values().at("damping"),1.0);
    }
    p.set("rollingDamping",eta);
  }
  if (spec.cohesion != "none") {
    const double ced = per_pair("cohesionEnergyDensity",i,j,"cohesion sjkr");
    check("cohesionEnergyDensity",ced,ced >= 0,">= 0 (J/m^3)");
    p.set("cohesionEnergyDensity",ced);
  }
  return p;
}

cm::ContactModelTable TrimeshContactCoefficients::build(const TrimeshContactSettings &s,
                                                       FixTrimeshTemplate *templ,
                                                       const std::vector<double> &sphere_radius)
{
  const int n = atom->ntypes;
  const auto active = [templ](int i, int j) {
    const TrimeshTypeTemplate *ti = templ->type_template(i), *tj = templ->type_template(j);
    return (ti || tj) && !(ti && tj && ti->fixed && tj->fixed);
  };
  try {
    return cm::ContactModelTable(n,s.spec,[&](int i, int j) { return parameters(i,j,s,templ,sphere_radius); },
                                 active);
  } catch (const std::exception &e) {
    error->all(FLERR,(std::string("Pair style trimesh: ") + e.what()).c_str());
  }
  return cm::ContactModelTable();
}

/* D of the normal dashpot [sqrt(kg)/s] for the halo spring S: the damping ratio the damping
   sub-model gives at S over sqrt(S/2) (k_n = S/2 per relative approach); 0 without damping. */

static double dashpot_coefficient(const cm::ContactModel &m, double S)
{
  return m.damping() ? m.damping()->dampingRatio(S) * std::sqrt(S / 2.0) : 0.0;
}

/* Contact time and largest stable step of one contact point of a type pair of grains and
   obstacles (both types with a template); the lightest contact point: translation plus rotation
   about the smallest moment, lever = bounding radius (rotation no: translation only). */

spacetree::contact_model::ContactTiming
TrimeshContactCoefficients::timing(const cm::ContactModel &m, const TrimeshContactSettings &s,
                                   const TrimeshTypeTemplate *ti, const TrimeshTypeTemplate *tj)
{
  const double inv_m = (ti->fixed ? 0.0 : 1.0 / ti->mass) + (tj->fixed ? 0.0 : 1.0 / tj->mass);
  const auto inv_point = [&s](const TrimeshTypeTemplate *t) {
    if (t->fixed) return 0.0;
    return 1.0 / t->mass + (s.rotation ? t->boundingRadius * t->boundingRadius / t->inertia.minCoeff() : 0.0);
  };
  const double S = m.normal().stiffness();
  const double D = dashpot_coefficient(m,S);
  const double kt = m.tangential() ? m.tangential()->stiffness() : 0.0;
  const double Dt = m.tangential() ? m.tangential()->damping() : 0.0;
  cm::ContactTiming t = cm::contactTiming(S,D,1.0 / inv_m,kt,Dt,1.0 / (inv_point(ti) + inv_point(tj)));
  if (m.rolling() && s.rotation) {
    // the rolling spring on a couple about the smallest moments, lever = bounding radius
    const double rr = cm::effectiveRadius(ti->fixed ? kInf : ti->boundingRadius,
                                          tj->fixed ? kInf : tj->boundingRadius);
    const double inv_inertia = (ti->fixed ? 0.0 : 1.0 / ti->inertia.minCoeff()) +
                               (tj->fixed ? 0.0 : 1.0 / tj->inertia.minCoeff());
    const double kr = m.rolling()->stiffness(rr);
    if (kr > 0.0)
      t.stableStep = std::min(t.stableStep,cm::dampedStableStep(std::sqrt(kr * inv_inertia),
                                                               m.rolling()->dampingRatio()));
  }
  return t;
}

std::vector<double> TrimeshContactCoefficients::stable_steps(const cm::ContactModelTable &table,
                                                             const TrimeshContactSettings &s,
                                                             FixTrimeshTemplate *templ)
{
  const int n = table.types();
  std::vector<double> steps((n+1)*(n+1),kInf);
  for (int i = 1; i <= n; i++)
    for (int j = 1; j <= n; j++) {
      const TrimeshTypeTemplate *ti = templ->type_template(i), *tj = templ->type_template(j);
      if (table.has(i,j) && ti && tj) steps[i*(n+1)+j] = timing(table.at(i,j),s,ti,tj).stableStep;
    }
  return steps;
}

void TrimeshContactCoefficients::report(const cm::ContactModelTable &table,
                                        const TrimeshContactSettings &s, FixTrimeshTemplate *templ)
{
  double smallest = kInf;
  std::string text = "pair_style trimesh: " + s.spec.describe() + "; per contact point:\n";
  for (int i = 1; i <= table.types(); i++)
    for (int j = i; j <= table.types(); j++) {
      if (!table.has(i,j)) continue;
      const cm::ContactModel &m = table.at(i,j);
      const TrimeshTypeTemplate *ti = templ->type_template(i), *tj = templ->type_template(j);
      const double S = m.normal().stiffness();
      const double D = dashpot_coefficient(m,S);
      if (!ti || !tj) {
        // a sphere or a wall type: its mass is not the type's, the coefficients only
        char line[300];
        snprintf(line,sizeof(line),"  type pair %d %d (%s): stiffness %.4g N/m, damping %.4g sqrt(kg)/s, "
                 "tangential stiffness %.4g N/m\n",i,j,"with spheres or a wall's material",S,D,
                 m.tangential() ? m.tangential()->stiffness() : 0.0);
        text += line;
        continue;
      }
      const double kt = m.tangential() ? m.tangential()->stiffness() : 0.0;
      const cm::ContactTiming t = timing(m,s,ti,tj);
      smallest = std::min(smallest,t.stableStep);
      if (m.cohesion() && m.cohesion()->pullOffForce() > S * s.eps) {
        char msg[300];
        snprintf(msg,sizeof(msg),"Pair style trimesh: type pair %d %d: cohesion %g N per contact point "
                 "exceeds the halo spring's S eps = %g N: it pulls the rigid surfaces together",i,j,
                 m.cohesion()->pullOffForce(),S * s.eps);
        error->warning(FLERR,msg);
      }
      char line[400];
      snprintf(line,sizeof(line),"  type pair %d %d: stiffness %.4g N/m, damping %.4g sqrt(kg)/s "
               "(restitution %.4g), tangential stiffness %.4g N/m; contact time %.4g s, largest "
               "stable time step %.4g s\n",i,j,S,D,cm::springDashpotRestitution(t.dampingRatio),kt,
               t.contactTime,t.stableStep);
      text += line;
    }
  if (comm->me == 0) {
    if (screen) fputs(text.c_str(),screen);
    if (logfile) fputs(text.c_str(),logfile);
  }
  if (update->dt > smallest) {
    char msg[300];
    snprintf(msg,sizeof(msg),"Pair style trimesh: time step %g s exceeds the largest stable time "
             "step %g s of one contact point",update->dt,smallest);
    error->warning(FLERR,msg);
  }
}
