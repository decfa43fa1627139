/* spacetree-dem: adaptive global time step with a veto on critical approaches and an optional
   rollback of steps that penetrate too deep (paper §5.2; core: src/core/dynamics). Before
   every step:
     dt <- min(C dt, dtmax, [dtcontact while pairs overlap], (h_min + 2 eps)/v_max, skin/(2 v_max))
   and, if an approaching pair of the granular neighbour list would penetrate deeper than eps
   within dt, dt <- safety * (gap + eps) / closing speed (smallest over all such pairs), never
   below dtmin. With rollback yes, a step after which some overlap exceeds `penetration` * eps
   is undone and redone with half the step. With pair_style trimesh the pairs are judged by the
   gap between their surfaces and eps is the allowed halo penetration (timestep_trimesh_scan.h).

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
#include <memory>
#include <vector>

#include "dynamics/AdaptiveTimestep.h"
#include "dynamics/TimestepRollback.h"
#include "dynamics/TimestepStateSnapshot.h"
#include "dynamics/TimestepVeto.h"
#include "fix.h"
#include "timestep_atom_state.h"
#include "timestep_contact_history.h"
#include "timestep_list_margin.h"
#include "timestep_pair_scan.h"
#include "timestep_wall_history.h"

namespace LAMMPS_NS {

/* The fix orchestrates: the contacts come from TimestepPairScan, the list look-ahead from
   TimestepListMargin, the decisions from the core (nextTimestep, judgeStep), and a rollback
   restores the TimestepStateSnapshot of the step's start. */

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
  TimestepPairScan::Result scan_pairs(spacetree::TimestepVeto &veto);
  void choose_timestep(const TimestepPairScan::Result &scan, double veto_limit_local);
  void set_dt(double dt);
  void collect_state_sources();
  bool restore_state();
  void redo_step();

  spacetree::TimestepPolicy policy;
  spacetree::RollbackPolicy rollback;
  bool dtmin_set, dtmax_set, dtmax_captured, eps_set, veto_on, rollback_on;
  // dtcontact: a value, `stable` (the stability ceiling of the contacts' type pairs), `none`, or
  // not given (pair_style trimesh: stable; other pair styles: none)
  enum class ContactCeiling { Default, Value, Stable, None } contact_ceiling;
  double safety, eps;
  class NeighList *list;
  FILE *history;

  // counters (f_ID[k])
  double vetoed_steps, floored_steps, critical_last, rollbacks, rollbacks_failed, rollbacks_rebuilt;
  double overlap_now, overlap_peak, contacts_now, contact_speed;
  bool warned_floor, warned_exhausted, warned_refused, redoing;

  TimestepPairScan pair_scan;
  TimestepListMargin list_margin;

  // rollback: the state the step started from, from every source that keeps a part of it
  spacetree::TimestepStateSnapshot snapshot;
  TimestepAtomState atom_state;
  TimestepContactHistory contact_history;
  std::vector<std::unique_ptr<TimestepWallHistory>> wall_histories;
};

}

#endif
#endif
