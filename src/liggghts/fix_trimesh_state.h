/* spacetree-dem: per-atom state of triangulated rigid particles, kept next to atom_style
   sphere/granular (x, v, f, radius = bounding radius + eps, rmass, omega, torque):
     quat[i][4]   orientation body -> world (unit quaternion w,x,y,z); all zero = not yet set
     angmom[i][3] angular momentum in the world frame (kg m^2/s)
   The shape of atom i is the template of its type (fix trimesh/template).
   Created by fix trimesh/template as fix "<template-ID>_state"; never defined in a deck, but
   read there as a per-atom array of 7 columns (f_<template-ID>_state[1..7] = quat w x y z,
   angmom x y z: dump custom, compute reduce, variables), and as atom->quaternion (dump custom
   quat1..quat4).
   The values follow atoms across ranks (exchange), reach ghosts (border + forward comm of
   quat, called by the pair style each step) and are written to restart files; a rolled-back step
   of fix adapt/timestep restores them with the atoms (TimestepAtomValues). */

#ifdef FIX_CLASS

FixStyle(trimesh/state,FixTrimeshState)

#else

#ifndef LMP_FIX_TRIMESH_STATE_H
#define LMP_FIX_TRIMESH_STATE_H

#include "fix.h"
#include "timestep_atom_state.h"

namespace LAMMPS_NS {

class FixTrimeshState : public Fix, public TimestepAtomValues {
 public:
  FixTrimeshState(class LAMMPS *, int, char **);
  ~FixTrimeshState();
  int setmask() { return 0; }

  void grow_arrays(int);
  void copy_arrays(int, int, int);
  void set_arrays(int);
  int pack_exchange(int, double *);
  int unpack_exchange(int, double *);
  int pack_border(int, int *, double *);
  int unpack_border(int, int, double *);
  int pack_comm(int, int *, double *, int, int *);
  void unpack_comm(int, int, double *);
  int pack_restart(int, double *);
  void unpack_restart(int, int);
  int size_restart(int) { return 8; }
  int maxsize_restart() { return 8; }
  double memory_usage();

  // TimestepAtomValues: orientation and angular momentum of owned atom i, 7 values
  int count() const { return 7; }
  void pack(int i, double *values) const;
  void unpack(int i, const double *values);

  /* Refresh the orientations of the ghosts (after the owners moved). */
  void forward_orientations();
  /* Refresh orientation, radius and rmass of the ghosts (after owners got their template). */
  void forward_shapes();

  double **quat;     // rows of values_: columns 0..3
  double **angmom;   // rows of values_: columns 4..6

 private:
  void point_rows(int nmax);

  double **values_;   // nmax x 7, the per-atom array of the fix (array_atom)
  bool with_shape_;   // forward comm: quat only, or quat + radius + rmass
};

}

#endif
#endif
