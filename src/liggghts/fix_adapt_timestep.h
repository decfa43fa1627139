/* spacetree-dem: adaptive global time step with a veto on critical approaches and an optional
   rollback of steps that penetrate too deep (paper §5.2; core: src/core/dynamics). Before
   every step:
     dt <- min(C dt, dtmax, [dtcontact while pairs overlap], (h_min + 2 eps)/v_max, skin/(2 v_max))
   and, if an approaching pair of the granular neighbour list would penetrate deeper than eps
   within dt, dt <- safety * (gap + eps) / closing speed (smallest over all such pairs), never
   below dtmin. With rollback yes, a step after which some overlap exceeds `penetration` * eps
   is undone and redone with half the step.

     fix ID group adapt/timestep creep C [dtmin X] [dtmax X] [dtcontact X] [eps X] [veto yes|no]
         [vimpact V tcontact T [dtrest X]] [safety S] [rollback yes|no] [penetration F] [retries N] [file F]

   With vimpact, the contact ceiling follows each contact's speed w = sqrt(vn^2 + (pi delta/T)^2):
   dt <= min(dtrest, dtcontact V / w_max) over the pairs in contact or about to touch.

   Output (docs/fix_adapt_timestep.md): f_ID = current dt; f_ID[1..11]. */

#ifdef FIX_CLASS

FixStyle(adapt/timestep,FixAdaptTimestep)

#else

#ifndef LMP_FIX_ADAPT_TIMESTEP_H
#define LMP_FIX_ADAPT_TIMESTEP_H

#include <cstdio>
#include <vector>

#include "dynamics/AdaptiveTimestep.h"
#include "dynamics/TimestepRollback.h"
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
  void pre_force(int);
  void end_of_step();
  double compute_scalar();
  double compute_vector(int);
  int pack_comm(int, int *, double *, int, int *);
  void unpack_comm(int, int, double *);

 private:
  struct PairScan { double maxOverlap; double contacts; bool contactSoon; double contactSpeed; };
  PairScan scan_pairs(spacetree::TimestepVeto *veto);
  void choose_timestep(const PairScan &scan, double critical);
  void set_dt(double dt);
  bool rollback_and_redo(double dt_redo);
  void save_state();
  bool restore_state();
  void save_history();
  void restore_history();
  void redo_step();
  void track_list_build();
  double list_margin();

  spacetree::TimestepPolicy policy;
  spacetree::RollbackPolicy rollback;
  bool dtmin_set, dtmax_set, dtmax_captured, veto_on, rollback_on;
  double safety, eps;
  class NeighList *list;
  FILE *history;

  // counters (f_ID[k])
  double vetoed_steps, floored_steps, critical_last, rollbacks, rollbacks_failed, rollbacks_rebuilt;
  double overlap_now, overlap_peak, contacts_now, contact_speed;
  bool warned_floor, warned_exhausted, warned_refused, redoing;

  // state at the start of the current step (rollback)
  bigint saved_step;
  int nsaved;
  std::vector<int> s_tag;
  std::vector<double> s_x, s_v, s_omega, s_f, s_torque;
  std::vector<tagint> s_image;   // atom->image is a tagint in LIGGGHTS 3.8
  // tangential history of primitive walls (fix wall/gran ... primitive with a history model):
  // per-atom fix property/atom "history_<wall-ID>", saved and restored with the atoms
  std::vector<class FixPropertyAtom*> wall_histories;
  int wall_values = 0;          // sum of their values per atom
  std::vector<double> s_wall;
  void find_wall_histories();
  std::vector<int> h_flag;
  std::vector<double> h_value;
  int h_inum;
  bigint h_step;

  // positions at the last neighbour-list build (Neighbor::xhold is not public)
  std::vector<double> accel;   // f/m of owned and ghost atoms (vimpact: relative normal acceleration)
  std::vector<double> x_build;
  bigint x_build_step;
};

}

#endif
#endif
