/* spacetree-dem: prescribed motion of obstacles of triangulated particles (core:
   src/core/dynamics/PrescribedMotion): a rotating drum, a moving plate, a mixer blade.

     fix ID group move/trimesh type T [T ...] keyword values ...
       rotate origin Px Py Pz axis Ax Ay Az (period P | omega W)
       linear Vx Vy Vz

   The obstacles (atoms of the fixed template types T of fix trimesh/template) turn about the
   axis through P (which moves with the linear velocity) and translate; their pose is computed
   from the time elapsed since the first run after the fix was defined, never integrated (no
   drift over long runs), and their velocity and angular velocity enter the contact law as the
   surface velocity. f_ID[1] = elapsed time (s), f_ID[2] = rotation angle omega t (rad, not
   reduced). The start poses and the elapsed time are written to restart files. */

#ifdef FIX_CLASS

FixStyle(move/trimesh,FixMoveTrimesh)

#else

#ifndef LMP_FIX_MOVE_TRIMESH_H
#define LMP_FIX_MOVE_TRIMESH_H

#include <map>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "dynamics/PrescribedMotion.h"
#include "fix.h"

namespace LAMMPS_NS {

class FixMoveTrimesh : public Fix {
 public:
  FixMoveTrimesh(class LAMMPS *, int, char **);
  ~FixMoveTrimesh();
  int setmask();
  void init();
  void setup_pre_exchange();
  void initial_integrate(int);
  double compute_vector(int);
  void write_restart(FILE *);
  void restart(char *);

 private:
  struct StartPose {
    Eigen::Vector3d position;
    Eigen::Quaterniond orientation;
  };
  // Pose, velocity and angular velocity of the owned obstacles at elapsed time t.
  void place(double t);
  void capture_start_poses();
  double elapsed() const;

  spacetree::dynamics::PrescribedMotion motion_;
  std::vector<int> types_;
  class FixTrimeshTemplate *templ_;
  bool started_;
  double time_origin_;
  double restored_elapsed_;                // from a restart file, until the next setup (< 0: none)
  std::map<long long, StartPose> start_;   // by atom ID, on every rank
};

}

#endif
#endif
