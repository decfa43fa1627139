/* spacetree-dem: see fix_template_trimesh.h */

#include "fix_template_trimesh.h"

#include <cmath>
#include <cstdio>
#include <cstring>

#include "error.h"
#include "fix_trimesh_template.h"
#include "force.h"
#include "lammps.h"
#include "pair.h"
#include "probability_distribution.h"

using namespace LAMMPS_NS;
using namespace LMP_PROBABILITY_NS;

namespace {

double sphereVolume(double r) { return 4.0 * M_PI / 3.0 * r * r * r; }

}

TrimeshInsertionSphere::TrimeshInsertionSphere(LAMMPS *lmp, int narg, char **arg) :
  radius(0.0), mass(0.0)
{
  Error *error = lmp->error;
  char msg[512];
  if (narg != 6 || strcmp(arg[4],"atom_type") != 0)
    error->all(FLERR,"Illegal fix particletemplate/trimesh command: expected "
               "'fix ID group particletemplate/trimesh SEED atom_type T'");
  const int type = lmp->force->inumeric(FLERR,arg[5]);

  FixTrimeshTemplate *templ = FixTrimeshTemplate::find(lmp,"Fix particletemplate/trimesh");
  if (!templ)
    error->all(FLERR,"Fix particletemplate/trimesh needs fix trimesh/template defined before it");
  const TrimeshTypeTemplate *tt = templ->type_template(type);
  if (!tt) {
    snprintf(msg,sizeof(msg),"Fix particletemplate/trimesh: atom type %d has no template in fix "
             "trimesh/template %s",type,templ->id);
    error->all(FLERR,msg);
  }
  if (tt->fixed) {
    snprintf(msg,sizeof(msg),"Fix particletemplate/trimesh: atom type %d is a fixed obstacle, "
             "which is not inserted",type);
    error->all(FLERR,msg);
  }
  Pair *pair = lmp->force->pair_match("trimesh",1);
  int dim = 0;
  const double *eps = pair ? static_cast<const double *>(pair->extract("eps",dim)) : NULL;
  if (!eps)
    error->all(FLERR,"Fix particletemplate/trimesh needs pair_style trimesh defined before it "
               "(its eps sets the insertion radius)");
  radius = tt->boundingRadius + *eps;
  mass = tt->mass;
  // FixTemplateSphere reads the seed, the type and a (constant) density: the one that gives
  // the insertion sphere the grain's mass.
  char density[64];
  snprintf(density,sizeof(density),"%.17g",mass / sphereVolume(radius));
  words = {arg[0],arg[1],arg[2],arg[3],"atom_type",arg[5],"density","constant",density};
  for (std::string &w : words) argv.push_back(&w[0]);
}

FixTemplateTrimesh::FixTemplateTrimesh(LAMMPS *lmp, int narg, char **arg) :
  TrimeshInsertionSphere(lmp,narg,arg),
  FixTemplateSphere(lmp,static_cast<int>(argv.size()),argv.data())
{
  // FixTemplateSphere leaves the radius and the expectations to derived styles
  pdf_radius = new PDF(error);
  pdf_radius->set_params<RANDOM_CONSTANT>(radius);
  volume_expect = sphereVolume(radius);
  mass_expect = mass;
}
