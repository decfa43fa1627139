/* spacetree-dem: velocity-Verlet integration of triangulated rigid particles (paper §3; core:
   src/core/dynamics/RigidBody). Translation: v += dt/2 f/m, x += dt v, v += dt/2 f/m.
   Rotation: angular momentum L (world) += dt/2 torque around a drift-free orientation update of
   the unit quaternion with the body principal inertia of the atom's type; omega = I_world^-1 L
   is refreshed for the contact model. Atoms of `fixed` template types (obstacles) are skipped.

     fix ID group nve/trimesh

   f_ID = kinetic energy of the integrated bodies, 1/2 m v^2 + 1/2 L.omega, summed over ranks.
   Needs fix trimesh/template. Honours time-step changes (fix adapt/timestep) through reset_dt. */

#ifdef FIX_CLASS

FixStyle(nve/trimesh,FixNVETrimesh)

#else

#ifndef LMP_FIX_NVE_TRIMESH_H
#define LMP_FIX_NVE_TRIMESH_H

#include "fix.h"

namespace LAMMPS_NS {

class FixNVETrimesh : public Fix {
 public:
  FixNVETrimesh(class LAMMPS *, int, char **);
  int setmask();
  void init();
  void initial_integrate(int);
  void final_integrate();
  void reset_dt();
  double compute_scalar();   // kinetic energy (translation + rotation) of the group's bodies

 private:
  void kick_and_drift(bool drift);

  double dtv, dtf;
  class FixTrimeshTemplate *templ;
};

}

#endif
#endif
