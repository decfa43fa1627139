/* spacetree-dem: adaptive global time step with a veto on critical approaches
   (paper §5.2; core: src/core/dynamics). Before every step:
     dt <- min(C dt, dtmax, (h_min + halo)/v_max, skin/(2 v_max))
   and, if an approaching pair of the granular neighbour list would close its gap within dt,
   dt <- safety * gap / closing speed (smallest over all such pairs), never below dtmin.

     fix ID group adapt/timestep creep C [dtmin X] [dtmax X] [veto yes|no] [safety S] [file F]

   Defaults: dtmax = the `timestep` of the deck, dtmin = dtmax/1000, veto yes, safety 0.8.
   Output: f_ID = current dt; f_ID[1] dt, f_ID[2] steps cut by the veto, f_ID[3] critical
   pairs of the last step, f_ID[4] steps that hit dtmin. */

#ifdef FIX_CLASS

FixStyle(adapt/timestep,FixAdaptTimestep)

#else

#ifndef LMP_FIX_ADAPT_TIMESTEP_H
#define LMP_FIX_ADAPT_TIMESTEP_H

#include <cstdio>

#include "dynamics/AdaptiveTimestep.h"
#include "dynamics/TimestepVeto.h"
#include "fix.h"

namespace LAMMPS_NS {

class FixAdaptTimestep : public Fix {
 public:
  FixAdaptTimestep(class LAMMPS *, int, char **);
  ~FixAdaptTimestep();
  int setmask();
  void init();
  void init_list(int, class NeighList *);
  void setup(int);
  void end_of_step();
  double compute_scalar();
  double compute_vector(int);

 private:
  void choose_timestep();

  spacetree::TimestepPolicy policy;
  bool dtmin_set, dtmax_set, veto_on;
  double safety;
  class NeighList *list;
  FILE *history;

  double vetoed_steps, floored_steps, critical_last;
};

}

#endif
#endif
