/* spacetree-dem: see fix_adapt_timestep.h and docs/fix_adapt_timestep.md */

#include "fix_adapt_timestep.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "error.h"
#include "fix_lookup.h"
#include "force.h"
#include "granular_list_copy.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_spacetree.h"
#include "neighbor.h"
#include "pair_gran.h"
#include "pair_trimesh.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
bool yes_no(Error *error, const char *keyword, const char *value)
{
  if (strcmp(value,"yes") == 0) return true;
  if (strcmp(value,"no") != 0) {
    char msg[256];
    snprintf(msg,sizeof(msg),"Illegal fix adapt/timestep command: %s must be yes or no",keyword);
    error->all(FLERR,msg);
  }
  return false;
}

// a value that must be > 0 (dtcontact, vimpact, tcontact, dtrest, penetration)
double positive(Force *force, Error *error, const char *keyword, const char *value)
{
  const double x = force->numeric(FLERR,value);
  if (!(x > 0.0)) {
    char msg[256];
    snprintf(msg,sizeof(msg),"Illegal fix adapt/timestep command: %s must be > 0",keyword);
    error->all(FLERR,msg);
  }
  return x;
}
}

FixAdaptTimestep::FixAdaptTimestep(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), dtmin_set(false), dtmax_set(false), dtmax_captured(false), eps_set(false), veto_on(true),
  rollback_on(false), contact_ceiling(ContactCeiling::Default), safety(0.8), eps(0.0), list(NULL), history(NULL),
  vetoed_steps(0), floored_steps(0), critical_last(0), rollbacks(0), rollbacks_failed(0),
  rollbacks_rebuilt(0),
  overlap_now(0), overlap_peak(0), contacts_now(0), contact_speed(0), warned_floor(false), warned_exhausted(false),
  warned_refused(false), redoing(false), pair_scan(lmp,this), list_margin(lmp), atom_state(lmp),
  contact_history(lmp)
{
  if (narg < 5 || strcmp(arg[3],"creep") != 0)
    error->all(FLERR,"Illegal fix adapt/timestep command: expected 'creep C' after the style");
  policy.creep = force->numeric(FLERR,arg[4]);
  if (!(policy.creep >= 1.0 && policy.creep <= spacetree::kMaxCreep))
    error->all(FLERR,"Illegal fix adapt/timestep command: creep must be in [1, 2] (the growth "
               "factor per step; a larger one does not creep, the paper uses 1.1)");
  if (find_other_fix_of_style(modify,"adapt/timestep",this))
    error->all(FLERR,"Fix adapt/timestep: only one fix adapt/timestep may exist (each would set "
               "the global time step)");

  bool dtcontact_set = false, penetration_set = false, dtrest_set = false;
  int iarg = 5;
  while (iarg < narg) {
    if (iarg+2 > narg) {
      char msg[256];
      snprintf(msg,sizeof(msg),"Illegal fix adapt/timestep command: keyword '%s' needs a value",arg[iarg]);
      error->all(FLERR,msg);
    }
    if (strcmp(arg[iarg],"dtmin") == 0) {
      policy.dtMin = force->numeric(FLERR,arg[iarg+1]);
      dtmin_set = true;
    } else if (strcmp(arg[iarg],"dtmax") == 0) {
      policy.dtMax = force->numeric(FLERR,arg[iarg+1]);
      dtmax_set = true;
    } else if (strcmp(arg[iarg],"dtcontact") == 0) {
      if (strcmp(arg[iarg+1],"stable") == 0) contact_ceiling = ContactCeiling::Stable;
      else if (strcmp(arg[iarg+1],"none") == 0) contact_ceiling = ContactCeiling::None;
      else {
        policy.dtContact = positive(force,error,"dtcontact",arg[iarg+1]);
        contact_ceiling = ContactCeiling::Value;
        dtcontact_set = true;
      }
    } else if (strcmp(arg[iarg],"vimpact") == 0) {
      policy.impactSpeed = positive(force,error,"vimpact",arg[iarg+1]);
    } else if (strcmp(arg[iarg],"tcontact") == 0) {
      policy.contactTime = positive(force,error,"tcontact",arg[iarg+1]);
    } else if (strcmp(arg[iarg],"dtrest") == 0) {
      policy.dtRest = positive(force,error,"dtrest",arg[iarg+1]);
      dtrest_set = true;
    } else if (strcmp(arg[iarg],"eps") == 0) {
      eps = force->numeric(FLERR,arg[iarg+1]);
      if (!(eps >= 0.0)) error->all(FLERR,"Illegal fix adapt/timestep command: eps must be >= 0");
      eps_set = true;
    } else if (strcmp(arg[iarg],"veto") == 0) {
      veto_on = yes_no(error,"veto",arg[iarg+1]);
    } else if (strcmp(arg[iarg],"safety") == 0) {
      safety = force->numeric(FLERR,arg[iarg+1]);
      if (!(safety > 0.0 && safety <= 1.0))
        error->all(FLERR,"Illegal fix adapt/timestep command: safety must be in (0,1]");
    } else if (strcmp(arg[iarg],"rollback") == 0) {
      rollback_on = yes_no(error,"rollback",arg[iarg+1]);
    } else if (strcmp(arg[iarg],"penetration") == 0) {
      rollback.fraction = positive(force,error,"penetration",arg[iarg+1]);
      penetration_set = true;
    } else if (strcmp(arg[iarg],"retries") == 0) {
      rollback.maxRetries = force->inumeric(FLERR,arg[iarg+1]);
      if (rollback.maxRetries < 1)
        error->all(FLERR,"Illegal fix adapt/timestep command: retries must be >= 1");
    } else if (strcmp(arg[iarg],"file") == 0) {
      if (comm->me == 0) {
        history = fopen(arg[iarg+1],"w");
        if (!history) {
          char msg[512];
          snprintf(msg,sizeof(msg),"Fix adapt/timestep cannot open file '%s'",arg[iarg+1]);
          error->one(FLERR,msg);
        }
        fprintf(history,"# step time dt critical_pairs vetoed floored max_overlap contacts rollbacks list_margin last_build contact_speed limit\n");
      }
    } else {
      char msg[256];
      snprintf(msg,sizeof(msg),"Illegal fix adapt/timestep command: unknown keyword '%s' (known: dtmin "
               "dtmax dtcontact vimpact tcontact dtrest eps veto safety rollback penetration retries file)",arg[iarg]);
      error->all(FLERR,msg);
    }
    iarg += 2;
  }
  if (dtmin_set && !(policy.dtMin > 0.0))
    error->all(FLERR,"Illegal fix adapt/timestep command: dtmin must be > 0");
  if (dtmax_set && !(policy.dtMax > 0.0))
    error->all(FLERR,"Illegal fix adapt/timestep command: dtmax must be > 0");
  if (dtmin_set && dtmax_set && policy.dtMin > policy.dtMax)
    error->all(FLERR,"Illegal fix adapt/timestep command: dtmin exceeds dtmax");
  if (dtcontact_set && dtmin_set && policy.dtContact < policy.dtMin)
    error->all(FLERR,"Illegal fix adapt/timestep command: dtcontact is below dtmin");
  // the state-dependent contact ceiling: dtcontact resolves an impact at vimpact; tcontact gives
  // the contact's angular frequency pi/tcontact; dtrest (default tcontact/10) caps enduring contacts
  if ((policy.impactSpeed > 0.0 || policy.contactTime > 0.0 || dtrest_set) &&
      !(policy.impactSpeed > 0.0 && policy.contactTime > 0.0 && dtcontact_set))
    error->all(FLERR,"Illegal fix adapt/timestep command: vimpact, tcontact and dtrest go together "
               "with dtcontact (vimpact, tcontact and dtcontact are required)");
  if (policy.impactSpeed > 0.0 && !dtrest_set) policy.dtRest = 0.1*policy.contactTime;
  if (dtrest_set && policy.dtRest < policy.dtContact)
    error->all(FLERR,"Illegal fix adapt/timestep command: dtrest is below dtcontact");
  if (penetration_set && !rollback_on)
    error->all(FLERR,"Illegal fix adapt/timestep command: penetration is a rollback setting (add rollback yes)");

  time_depend = 1;   // elapsed time is accumulated with update_time() before each change
  force_reneighbor = 1;   // an early list rebuild keeps every pair that can touch in the list
  next_reneighbor = -1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 11;
  comm_forward = 6;   // accelerations (vimpact) or velocities and angular velocities to ghosts
  global_freq = 1;
  extscalar = 0;
  extvector = 0;
}

FixAdaptTimestep::~FixAdaptTimestep()
{
  if (history) fclose(history);
}

int FixAdaptTimestep::setmask()
{
  int mask = END_OF_STEP;
  if (rollback_on) mask |= PRE_FORCE;   // the state copied just before the pair forces
  return mask;
}

void FixAdaptTimestep::init()
{
  if (!atom->radius_flag || !atom->rmass_flag)
    error->all(FLERR,"Fix adapt/timestep requires an atom style with radius and mass (granular)");
  // the deck's timestep is the ceiling, taken once: a later run must not inherit the adapted dt
  if (!dtmax_set && !dtmax_captured) policy.dtMax = update->dt;
  dtmax_captured = true;
  if (!dtmin_set) {
    policy.dtMin = 1e-3*policy.dtMax;
    if (policy.dtContact > 0.0) policy.dtMin = std::min(policy.dtMin,1e-2*policy.dtContact);
  }
  if (policy.dtMin > policy.dtMax)
    error->all(FLERR,"Fix adapt/timestep: dtmin exceeds dtmax");
  if (policy.dtContact > policy.dtMax && comm->me == 0)
    error->warning(FLERR,"Fix adapt/timestep: dtcontact exceeds dtmax and has no effect");
  // Overlaps (dtcontact, rollback) are contacts for sphere pair styles (pair gran: the spheres'
  // overlap) and for pair trimesh (the halo penetration eps_h - d/2 of its contact points; the
  // veto and the approach test measure the surface distance, TimestepTrimeshScan). Other styles
  // on a granular list get the veto over the list's spheres only.
  PairTrimesh *trimesh = force->pair ? dynamic_cast<PairTrimesh*>(force->pair) : NULL;
  const bool sphere_contacts = force->pair && dynamic_cast<PairGran*>(force->pair);
  if (!sphere_contacts && !trimesh && (rollback_on || policy.dtContact > 0.0 || eps > 0.0))
    error->all(FLERR,"Fix adapt/timestep eps, rollback and dtcontact need pair_style gran ... or "
               "pair_style trimesh (their overlaps are contacts)");
  if (trimesh) {
    // eps is the halo penetration allowed, at most the halo (beyond it the rigid surfaces meet)
    const double halo = trimesh->contact_options().epsilon;
    if (!eps_set) eps = halo;
    else if (!(eps > 0.0) || eps > halo) {
      char msg[256];
      snprintf(msg,sizeof(msg),"Fix adapt/timestep eps %g with pair_style trimesh: the allowed halo "
               "penetration must be > 0 and at most the pair style's eps %g",eps,halo);
      error->all(FLERR,msg);
    }
  }
  pair_scan.use_trimesh(trimesh,eps,safety);
  // the stability ceiling: the largest stable step pair_style trimesh prints per type pair
  if (contact_ceiling == ContactCeiling::Stable && !trimesh)
    error->all(FLERR,"Fix adapt/timestep dtcontact stable needs pair_style trimesh (the stable time "
               "steps of its type pairs)");
  policy.stableCeiling = trimesh && (contact_ceiling == ContactCeiling::Stable ||
                                     contact_ceiling == ContactCeiling::Default);
  if (rollback_on && !(eps > 0.0))
    error->all(FLERR,"Illegal fix adapt/timestep command: rollback yes needs eps > 0 (the allowed overlap)");
  if (!force->pair && veto_on)
    error->all(FLERR,"Fix adapt/timestep veto needs a pair style with a granular neighbour list "
               "(or use veto no)");
  if (sphere_contacts || trimesh || (force->pair && veto_on))
    request_granular_list_copy(neighbor,this,GranularListUser::Fix);
  if (update->whichflag == 1 && strncmp(update->integrate_style,"verlet",6) != 0)
    error->all(FLERR,"Fix adapt/timestep needs run_style verlet");
  // the skin/2 cap only keeps the lists valid when they are rebuilt as soon as they may be stale
  if ((neighbor->every > 1 || neighbor->delay > 0 || !neighbor->dist_check) && comm->me == 0)
    error->warning(FLERR,"Fix adapt/timestep: with neigh_modify every > 1, delay > 0 or check no the "
                   "skin/2-per-step cap does not keep the neighbour lists valid");
  if (rollback_on) {
    for (int i = 0; i < modify->nfix; i++)
      if (modify->fix[i]->time_depend && modify->fix[i] != this) {
        // such fixes (fix move/trimesh, fix dt/reset, ...) keep their own clock, which a
        // rolled-back step would not rewind
        char msg[512];
        snprintf(msg,sizeof(msg),"Fix adapt/timestep rollback cannot be combined with fix %s (%s): "
                 "it depends on the elapsed time, which a rolled-back step does not rewind for it",
                 modify->fix[i]->id,modify->fix[i]->style);
        error->all(FLERR,msg);
      }
    collect_state_sources();
  }
}

/* What a rollback restores: the atoms (with the primitive walls' tangential histories and the
   per-atom values of fixes that implement TimestepAtomValues, e.g. the orientation and angular
   momentum of triangulated particles, in their records), the pair style's contact history, and
   the state of the pair style and of any fix that keeps state of its own and says so by
   implementing spacetree::TimestepStateSource. */

void FixAdaptTimestep::collect_state_sources()
{
  wall_histories = TimestepWallHistory::collect(lmp);
  atom_state.clear_values();
  for (const auto &w : wall_histories) atom_state.add_values(w.get());
  // per-atom state of fixes (fix trimesh/state: orientation and angular momentum) in the records
  for (int i = 0; i < modify->nfix; i++)
    if (TimestepAtomValues *v = dynamic_cast<TimestepAtomValues*>(modify->fix[i])) atom_state.add_values(v);
  snapshot.clear();
  snapshot.add(&atom_state);
  snapshot.add(&contact_history);
  if (spacetree::TimestepStateSource *s = dynamic_cast<spacetree::TimestepStateSource*>(force->pair))
    snapshot.add(s);
  for (int i = 0; i < modify->nfix; i++)
    if (spacetree::TimestepStateSource *s = dynamic_cast<spacetree::TimestepStateSource*>(modify->fix[i]))
      snapshot.add(s);
}

void FixAdaptTimestep::init_list(int, NeighList *ptr)
{
  list = ptr;
}

void FixAdaptTimestep::setup(int)
{
  list_margin.track_build();
  spacetree::TimestepVeto veto(0.0,safety,eps);
  const TimestepPairScan::Result scan = scan_pairs(veto);
  overlap_now = scan.maxOverlap;
  overlap_peak = std::max(overlap_peak,overlap_now);
  contacts_now = scan.contacts;
  choose_timestep(scan,veto.limit());
  if (rollback_on) snapshot.save(spacetree::TimestepStateSource::Moment::StepStart);
}

/* The veto is tested against the largest step creep can give. */

TimestepPairScan::Result FixAdaptTimestep::scan_pairs(spacetree::TimestepVeto &veto)
{
  const TimestepPairScan::Result scan = pair_scan.scan(list,policy,policy.creep*update->dt,
                                                       veto_on ? &veto : NULL);
  critical_last = scan.criticalPairs;
  return scan;
}

void FixAdaptTimestep::choose_timestep(const TimestepPairScan::Result &scan, double veto_limit_local)
{
  double **v = atom->v;
  const int nlocal = atom->nlocal;
  const double dt = update->dt;

  double vmax_local = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    vmax_local = std::max(vmax_local,v[i][0]*v[i][0] + v[i][1]*v[i][1] + v[i][2]*v[i][2]);
  }
  double vmax, veto_limit;
  MPI_Allreduce(&vmax_local,&vmax,1,MPI_DOUBLE,MPI_MAX,world);
  MPI_Allreduce(&veto_limit_local,&veto_limit,1,MPI_DOUBLE,MPI_MIN,world);
  vmax = std::sqrt(vmax);

  spacetree::TimestepLimits limits;
  limits.maxSpeed = vmax;
  limits.skin = neighbor->skin;
  limits.halo = 2.0*eps;
  limits.inContact = scan.contactSoon;
  limits.contactSpeed = scan.contactSpeed;
  limits.stableStep = scan.stableStep;
  contact_speed = scan.contactSpeed;
  limits.listMargin = list_margin.margin();
  // keep at least half the skin as look-ahead: rebuild the lists in the next step when less is left
  if (limits.listMargin < 0.5*neighbor->skin) next_reneighbor = update->ntimestep + 1;
  if (neighbor->spacetree) limits.finestCell = neighbor->spacetree->finest_cell();

  const spacetree::TimestepDecision d = spacetree::nextTimestep(dt,policy,limits,veto_limit);
  if (d.vetoed) vetoed_steps += 1;
  if (d.floored) {
    if (!warned_floor && comm->me == 0)
      error->warning(FLERR,"Fix adapt/timestep hit dtmin: a critical approach or the speed cap "
                     "asked for a smaller step (counted in f_ID[4])");
    warned_floor = true;
    floored_steps += 1;
  }
  if (history && comm->me == 0)
    fprintf(history,BIGINT_FORMAT " %.12g %.12g %g %d %d %.6g %g %g %.6g " BIGINT_FORMAT " %.6g %s\n",update->ntimestep,
            update->atime + (update->ntimestep - update->atimestep)*dt,d.dt,critical_last,
            int(d.vetoed),int(d.floored),scan.maxOverlap,scan.contacts,rollbacks,limits.listMargin,
            neighbor->lastcall,scan.contactSpeed,spacetree::limiterName(d.limiter));
  if (d.dt != dt) set_dt(d.dt);
}

void FixAdaptTimestep::set_dt(double dt)
{
  update->update_time();
  update->dt = dt;
  if (force->pair) force->pair->reset_dt();
  for (int i = 0; i < modify->nfix; i++) modify->fix[i]->reset_dt();
}

void FixAdaptTimestep::pre_force(int)
{
  if (!redoing) snapshot.save(spacetree::TimestepStateSource::Moment::BeforeForces);
}

void FixAdaptTimestep::end_of_step()
{
  list_margin.track_build();
  spacetree::TimestepVeto veto(0.0,safety,eps);
  TimestepPairScan::Result scan = scan_pairs(veto);

  if (rollback_on) {
    for (int retries = 0; ; retries++) {
      const spacetree::RollbackDecision d = spacetree::judgeStep(rollback,eps,overlap_now,
          scan.maxOverlap,update->dt,policy.dtMin,retries);
      if (d.exhausted) {
        rollbacks_failed += 1;
        if (!warned_exhausted && comm->me == 0)
          error->warning(FLERR,"Fix adapt/timestep rollback: an overlap stays deeper than penetration*eps "
                         "at dtmin or after the last retry; step accepted (counted in f_ID[6])");
        warned_exhausted = true;
      }
      if (!d.redo) break;
      if (!restore_state()) {
        rollbacks_failed += 1;
        if (!warned_refused && comm->me == 0)
          error->warning(FLERR,"Fix adapt/timestep rollback refused: atoms were added or deleted during "
                         "the step (or no atom map); step accepted (counted in f_ID[6])");
        warned_refused = true;
        break;
      }
      // the steps before this one keep their dt in the elapsed time; this one gets d.dt
      const bigint now = update->ntimestep;
      update->ntimestep = now - 1;
      set_dt(d.dt);
      update->ntimestep = now;
      if (neighbor->lastcall > atom_state.saved_step()) rollbacks_rebuilt += 1;
      redo_step();
      rollbacks += 1;
      veto.reset();
      scan = scan_pairs(veto);
    }
  }

  overlap_now = scan.maxOverlap;
  overlap_peak = std::max(overlap_peak,overlap_now);
  contacts_now = scan.contacts;
  choose_timestep(scan,veto.limit());
  if (rollback_on) snapshot.save(spacetree::TimestepStateSource::Moment::StepStart);
}

/* All sources or none, on every rank alike: a rank that cannot restore keeps every rank's step. */

bool FixAdaptTimestep::restore_state()
{
  return snapshot.restore([this](bool ok) {
    int mine = ok ? 1 : 0, all;
    MPI_Allreduce(&mine,&all,1,MPI_INT,MPI_MIN,world);
    return all == 1;
  });
}

/* One velocity-Verlet step as Verlet::run does it, without re-neighbouring (the lists of this
   step stay valid: the redo moves every particle less than the rejected step did). */

void FixAdaptTimestep::redo_step()
{
  redoing = true;
  if (modify->n_pre_initial_integrate) modify->pre_initial_integrate();
  modify->initial_integrate(0);
  if (modify->n_post_integrate) modify->post_integrate();
  comm->forward_comm();

  const size_t nall = atom->nlocal + atom->nghost;
  if (nall) {
    memset(&atom->f[0][0],0,3*nall*sizeof(double));
    if (atom->torque_flag) memset(&atom->torque[0][0],0,3*nall*sizeof(double));
  }
  // energy and virial as Integrate::ev_set asks for them on this step, so that thermo output of
  // a redone step (pressure, pe) reports the accepted step, not the rejected one
  int eflag = 0, vflag = 0;
  const int virial_style = force->newton_pair ? 2 : 1;
  for (int i = 0; i < modify->ncompute; i++) {
    Compute *c = modify->compute[i];
    if (!(c->peflag || c->peatomflag || c->pressflag || c->pressatomflag)) continue;
    if (!c->matchstep(update->ntimestep)) continue;
    if (c->peflag) eflag |= 1;
    if (c->peatomflag) eflag |= 2;
    if (c->pressflag) vflag |= virial_style;
    if (c->pressatomflag) vflag |= 4;
  }
  if (modify->n_pre_force) modify->pre_force(vflag);
  force->pair->compute(eflag,vflag);
  if (force->newton) comm->reverse_comm();
  if (modify->n_post_force) modify->post_force(vflag);
  if (modify->n_pre_final_integrate) modify->pre_final_integrate();
  modify->final_integrate();
  redoing = false;
}

// the accelerations of the pair scan (vimpact)
int FixAdaptTimestep::pack_comm(int n, int *list_, double *buf, int, int *)
{
  return pair_scan.pack_comm(n,list_,buf);
}

void FixAdaptTimestep::unpack_comm(int n, int first, double *buf)
{
  pair_scan.unpack_comm(n,first,buf);
}

double FixAdaptTimestep::compute_scalar()
{
  return update->dt;
}

double FixAdaptTimestep::compute_vector(int n)
{
  switch (n) {
    case 0: return update->dt;
    case 1: return vetoed_steps;
    case 2: return critical_last;
    case 3: return floored_steps;
    case 4: return rollbacks;
    case 5: return rollbacks_failed;
    case 6: return overlap_now;
    case 7: return overlap_peak;
    case 8: return contacts_now;
    case 9: return rollbacks_rebuilt;
    default: return contact_speed;
  }
}
