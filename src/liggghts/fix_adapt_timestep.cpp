/* spacetree-dem: see fix_adapt_timestep.h */

#include "fix_adapt_timestep.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "force.h"
#include "granular_list_copy.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_spacetree.h"
#include "neighbor.h"
#include "pair.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

FixAdaptTimestep::FixAdaptTimestep(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), dtmin_set(false), dtmax_set(false), veto_on(true), safety(0.8),
  list(NULL), history(NULL), vetoed_steps(0), floored_steps(0), critical_last(0)
{
  if (narg < 5 || strcmp(arg[3],"creep") != 0)
    error->all(FLERR,"Illegal fix adapt/timestep command: expected 'creep C' after the style");
  policy.creep = force->numeric(FLERR,arg[4]);
  if (!(policy.creep >= 1.0)) error->all(FLERR,"Illegal fix adapt/timestep command: creep must be >= 1");

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
    } else if (strcmp(arg[iarg],"veto") == 0) {
      if (strcmp(arg[iarg+1],"yes") == 0) veto_on = true;
      else if (strcmp(arg[iarg+1],"no") == 0) veto_on = false;
      else error->all(FLERR,"Illegal fix adapt/timestep command: veto must be yes or no");
    } else if (strcmp(arg[iarg],"safety") == 0) {
      safety = force->numeric(FLERR,arg[iarg+1]);
      if (!(safety > 0.0 && safety <= 1.0))
        error->all(FLERR,"Illegal fix adapt/timestep command: safety must be in (0,1]");
    } else if (strcmp(arg[iarg],"file") == 0) {
      if (comm->me == 0) {
        history = fopen(arg[iarg+1],"w");
        if (!history) {
          char msg[512];
          snprintf(msg,sizeof(msg),"Fix adapt/timestep cannot open file '%s'",arg[iarg+1]);
          error->one(FLERR,msg);
        }
        fprintf(history,"# step time dt critical_pairs vetoed floored\n");
      }
    } else {
      char msg[256];
      snprintf(msg,sizeof(msg),"Illegal fix adapt/timestep command: unknown keyword '%s' "
               "(known: dtmin dtmax veto safety file)",arg[iarg]);
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

  time_depend = 1;   // elapsed time is accumulated with update_time() before each change
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 4;
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
  return END_OF_STEP;
}

void FixAdaptTimestep::init()
{
  if (!atom->radius_flag || !atom->rmass_flag)
    error->all(FLERR,"Fix adapt/timestep requires an atom style with radius and mass (granular)");
  if (!dtmax_set) policy.dtMax = update->dt;    // the deck's timestep is the ceiling
  if (!dtmin_set) policy.dtMin = 1e-3*policy.dtMax;
  if (policy.dtMin > policy.dtMax)
    error->all(FLERR,"Fix adapt/timestep: dtmin exceeds dtmax");
  if (veto_on) {
    if (force->pair == NULL)
      error->all(FLERR,"Fix adapt/timestep veto needs a granular pair style (or use veto no)");
    request_granular_list_copy(neighbor,this,GranularListUser::Fix);
  }
}

void FixAdaptTimestep::init_list(int, NeighList *ptr)
{
  list = ptr;
}

void FixAdaptTimestep::setup(int)
{
  choose_timestep();
}

void FixAdaptTimestep::end_of_step()
{
  choose_timestep();
}

void FixAdaptTimestep::choose_timestep()
{
  double **x = atom->x;
  double **v = atom->v;
  double *radius = atom->radius;
  const int nlocal = atom->nlocal;
  const double dt = update->dt;

  double vmax_local = 0.0;
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit)) continue;
    vmax_local = std::max(vmax_local,v[i][0]*v[i][0] + v[i][1]*v[i][1] + v[i][2]*v[i][2]);
  }
  double vmax;
  MPI_Allreduce(&vmax_local,&vmax,1,MPI_DOUBLE,MPI_MAX,world);
  vmax = std::sqrt(vmax);

  spacetree::TimestepLimits limits;
  limits.maxSpeed = vmax;
  limits.skin = neighbor->skin;
  if (neighbor->spacetree && neighbor->spacetree->tree.statistics().deepestPopulatedLevel >= 0)
    limits.finestCell = neighbor->spacetree->tree.meshSize(
        neighbor->spacetree->tree.statistics().deepestPopulatedLevel);

  // spheres touch at their surfaces: no halo beyond the contact radius
  spacetree::TimestepVeto veto(0.0,safety);
  if (veto_on && list) {
    neighbor->build_one(list->index);
    const double cdf = neighbor->contactDistanceFactor;
    for (int ii = 0; ii < list->inum; ii++) {
      const int i = list->ilist[ii];
      const int *jlist = list->firstneigh[i];
      for (int jj = 0; jj < list->numneigh[i]; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        if (!(atom->mask[i] & groupbit) && !(atom->mask[j] & groupbit)) continue;
        veto.consider(x[i],v[i],radius[i]*cdf,x[j],v[j],radius[j]*cdf,dt);
      }
    }
  }
  double limit_local = veto.limit(), limit;
  MPI_Allreduce(&limit_local,&limit,1,MPI_DOUBLE,MPI_MIN,world);
  double critical_local = double(veto.criticalPairs());
  MPI_Allreduce(&critical_local,&critical_last,1,MPI_DOUBLE,MPI_SUM,world);

  const spacetree::TimestepDecision d = spacetree::nextTimestep(dt,policy,limits,limit);
  if (d.vetoed) vetoed_steps += 1;
  if (d.floored) {
    if (floored_steps == 0 && comm->me == 0)
      error->warning(FLERR,"Fix adapt/timestep hit dtmin: a critical approach or the speed cap "
                     "asked for a smaller step (counted in f_ID[4])");
    floored_steps += 1;
  }
  if (history && comm->me == 0)
    fprintf(history,BIGINT_FORMAT " %.12g %.12g %g %d %d\n",update->ntimestep,
            update->atime + (update->ntimestep - update->atimestep)*dt,d.dt,critical_last,
            int(d.vetoed),int(d.floored));

  if (d.dt == dt) return;
  update->update_time();
  update->dt = d.dt;
  if (force->pair) force->pair->reset_dt();
  for (int i = 0; i < modify->nfix; i++) modify->fix[i]->reset_dt();
}

double FixAdaptTimestep::compute_scalar()
{
  return update->dt;
}

double FixAdaptTimestep::compute_vector(int n)
{
  if (n == 0) return update->dt;
  if (n == 1) return vetoed_steps;
  if (n == 2) return critical_last;
  return floored_steps;
}
