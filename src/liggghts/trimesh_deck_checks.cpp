/* spacetree-dem: see trimesh_deck_checks.h */

#include "trimesh_deck_checks.h"

#include <cstdio>

#include "atom.h"
#include "domain.h"
#include "error.h"
#include "fix_trimesh_template.h"
#include "force.h"
#include "lammps.h"
#include "neighbor.h"
#include "pair_hybrid.h"
#include "trimesh_type_template.h"

using namespace LAMMPS_NS;

void LAMMPS_NS::check_template_types_reach_trimesh(LAMMPS *lmp, const FixTrimeshTemplate &templ)
{
  // Without hybrid, Pair::init has already required pair_coeff for every type.
  PairHybrid *hybrid = dynamic_cast<PairHybrid *>(lmp->force->pair);
  if (!hybrid) return;
  const int ntypes = lmp->atom->ntypes;
  char trimesh[] = "trimesh";
  for (int i = 1; i <= ntypes; i++) {
    const TrimeshTypeTemplate *ti = templ.type_template(i);
    if (!ti) continue;
    for (int j = i; j <= ntypes; j++) {
      const TrimeshTypeTemplate *tj = templ.type_template(j);
      if (!tj || (ti->fixed && tj->fixed)) continue;
      if (hybrid->check_ijtype(i,j,trimesh)) continue;
      char msg[512];
      snprintf(msg,sizeof(msg),"Pair style trimesh: atom types %d and %d have trimesh templates "
               "but no 'pair_coeff %d %d trimesh' (pair_style %s): their grains would not meet as "
               "triangle meshes",i,j,i,j,lmp->force->pair_style);
      lmp->error->all(FLERR,msg);
    }
  }
}

void LAMMPS_NS::check_grains_fit_box(LAMMPS *lmp, const FixTrimeshTemplate &templ)
{
  Domain *domain = lmp->domain;
  const double skin = lmp->neighbor->skin;
  const char dimname[3] = {'x','y','z'};
  for (int t = 1; t <= lmp->atom->ntypes; t++) {
    const TrimeshTypeTemplate *tt = templ.type_template(t);
    if (!tt || tt->fixed) continue;
    const double diameter = 2.0*(tt->boundingRadius + templ.halo());
    for (int d = 0; d < domain->dimension; d++) {
      const double length = domain->prd[d];
      char msg[512];
      if (domain->periodicity[d] && diameter + skin > length) {
        snprintf(msg,sizeof(msg),"Pair style trimesh: grains of type %d reach their own periodic "
                 "image: bounding diameter + 2 eps + skin %g exceeds the periodic box length %g "
                 "in %c",t,diameter + skin,length,dimname[d]);
        lmp->error->all(FLERR,msg);
      }
      const bool fixed_walls = domain->boundary[d][0] == 1 && domain->boundary[d][1] == 1;
      if (fixed_walls && diameter > length) {   // shrink-wrapped boxes follow the atoms
        snprintf(msg,sizeof(msg),"Pair style trimesh: grains of type %d do not fit in the box: "
                 "bounding diameter + 2 eps %g exceeds the fixed box length %g in %c",t,diameter,
                 length,dimname[d]);
        lmp->error->all(FLERR,msg);
      }
    }
  }
}
