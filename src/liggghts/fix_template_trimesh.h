/* spacetree-dem: particle template for inserting triangulated grains (fix insert/pack,
   insert/stream, insert/rate/region ...), the grain's counterpart of particletemplate/sphere:

     fix ID group particletemplate/trimesh SEED atom_type T

   The inserted sphere is the grain's bounding sphere (bounding radius + eps of pair_style
   trimesh), so the insertion's overlap check is conservative, and it carries the grain's mass
   (template density * mesh volume), so mass-based insertion and the INFO lines count grains.
   Type T must have a template in fix trimesh/template (not an obstacle); pair_style trimesh
   must come before this fix (its eps sets the radius). */

#ifdef FIX_CLASS

FixStyle(particletemplate/trimesh,FixTemplateTrimesh)

#else

#ifndef LMP_FIX_TEMPLATE_TRIMESH_H
#define LMP_FIX_TEMPLATE_TRIMESH_H

#include <string>
#include <vector>

#include "fix_template_sphere.h"

namespace LAMMPS_NS {

// The grain's insertion sphere and the arguments FixTemplateSphere parses, made from them:
// a base class so that it is built before FixTemplateSphere's constructor reads them.
struct TrimeshInsertionSphere {
  TrimeshInsertionSphere(class LAMMPS *lmp, int narg, char **arg);
  double radius;     // bounding radius + eps
  double mass;       // the grain's
  std::vector<std::string> words;
  std::vector<char *> argv;
};

class FixTemplateTrimesh : private TrimeshInsertionSphere, public FixTemplateSphere {
 public:
  FixTemplateTrimesh(class LAMMPS *, int, char **);
  double insertion_radius() const { return radius; }
};

}

#endif
#endif
