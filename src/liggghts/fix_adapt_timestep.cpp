/* spacetree-dem: see fix_adapt_timestep.h and docs/fix_adapt_timestep.md */

#include "fix_adapt_timestep.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "atom.h"
#include "comm.h"
#include "compute.h"
#include "domain.h"
#include "error.h"
#include "fix_mesh_surface.h"
#include "fix_neighlist_mesh.h"
#include "fix_property_atom.h"
#include "fix_wall_gran.h"
#include "force.h"
#include "granular_list_copy.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_spacetree.h"
#include "neighbor.h"
#include "pair_gran.h"
#include "primitive_wall.h"
#include "tri_mesh.h"
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
  Fix(lmp, narg, arg), dtmin_set(false), dtmax_set(false), dtmax_captured(false), veto_on(true),
  rollback_on(false), safety(0.8), eps(0.0), list(NULL), history(NULL),
  vetoed_steps(0), floored_steps(0), critical_last(0), rollbacks(0), rollbacks_failed(0),
  rollbacks_rebuilt(0),
  overlap_now(0), overlap_peak(0), contacts_now(0), contact_speed(0), warned_floor(false), warned_exhausted(false),
  warned_refused(false), redoing(false), saved_step(-1), nsaved(0), h_inum(-1), h_step(-1),
  x_build_step(-1)
{
  if (narg < 5 || strcmp(arg[3],"creep") != 0)
    error->all(FLERR,"Illegal fix adapt/timestep command: expected 'creep C' after the style");
  policy.creep = force->numeric(FLERR,arg[4]);
  if (!(policy.creep >= 1.0)) error->all(FLERR,"Illegal fix adapt/timestep command: creep must be >= 1");

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
      policy.dtContact = positive(force,error,"dtcontact",arg[iarg+1]);
      dtcontact_set = true;
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
        fprintf(history,"# step time dt critical_pairs vetoed floored max_overlap contacts rollbacks list_margin last_build contact_speed\n");
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
  if (rollback_on && !(eps > 0.0))
    error->all(FLERR,"Illegal fix adapt/timestep command: rollback yes needs eps > 0 (the allowed overlap)");
  if (penetration_set && !rollback_on)
    error->all(FLERR,"Illegal fix adapt/timestep command: penetration is a rollback setting (add rollback yes)");

  time_depend = 1;   // elapsed time is accumulated with update_time() before each change
  force_reneighbor = 1;   // an early list rebuild keeps every pair that can touch in the list
  next_reneighbor = -1;
  scalar_flag = 1;
  vector_flag = 1;
  size_vector = 11;
  comm_forward = 3;   // accelerations to ghosts (vimpact)
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
  if (rollback_on) mask |= PRE_FORCE;   // snapshot of the contact history before the pair forces
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
  // Overlaps (dtcontact, rollback) are contacts only for sphere pair styles (pair gran). Other
  // styles on a granular list (pair trimesh: radius = bounding radius + halo) get the veto over
  // their bounding spheres, which is conservative: it acts before the bounding spheres meet.
  const bool sphere_contacts = force->pair && dynamic_cast<PairGran*>(force->pair);
  if (!sphere_contacts && (rollback_on || policy.dtContact > 0.0 || eps > 0.0))
    error->all(FLERR,"Fix adapt/timestep eps, rollback and dtcontact need a granular sphere pair style "
               "(pair_style gran ...)");
  if (!force->pair && veto_on)
    error->all(FLERR,"Fix adapt/timestep veto needs a pair style with a granular neighbour list "
               "(or use veto no)");
  if (sphere_contacts || (force->pair && veto_on))
    request_granular_list_copy(neighbor,this,GranularListUser::Fix);
  if (update->whichflag == 1 && strncmp(update->integrate_style,"verlet",6) != 0)
    error->all(FLERR,"Fix adapt/timestep needs run_style verlet");
  // the skin/2 cap only keeps the lists valid when they are rebuilt as soon as they may be stale
  if ((neighbor->every > 1 || neighbor->delay > 0 || !neighbor->dist_check) && comm->me == 0)
    error->warning(FLERR,"Fix adapt/timestep: with neigh_modify every > 1, delay > 0 or check no the "
                   "skin/2-per-step cap does not keep the neighbour lists valid");
  if (rollback_on) {
    for (int i = 0; i < modify->nfix; i++)
      if (modify->fix[i]->time_depend && modify->fix[i] != this)
        error->all(FLERR,"Fix adapt/timestep rollback cannot be combined with another fix that "
                   "changes the time step");
    find_wall_histories();
  }
}

/* Primitive walls keep their tangential history in a fix property/atom named history_<wall-ID>
   (created in FixWallGran::post_create); it is part of the state a rollback restores.
   Mesh walls keep theirs in per-atom contact lists that this fix cannot restore: warned. */

void FixAdaptTimestep::find_wall_histories()
{
  wall_histories.clear();
  wall_values = 0;
  for (int f = 0; f < modify->nfix; f++) {
    if (strcmp(modify->fix[f]->style,"wall/gran") != 0) continue;
    FixWallGran *wall = static_cast<FixWallGran*>(modify->fix[f]);
    if (wall->dnum() <= 0) continue;
    if (wall->is_mesh_wall()) {
      if (comm->me == 0)
        error->warning(FLERR,"Fix adapt/timestep rollback: the tangential history of mesh wall "
                       "(fix wall/gran mesh) is not restored by a rollback; use a model without "
                       "tangential history on that wall or accept one extra increment per rollback");
      continue;
    }
    const std::string name = std::string("history_") + wall->id;
    const int ifix = modify->find_fix(name.c_str());
    if (ifix < 0) continue;   // created in the wall's post_create; absent before the first run
    FixPropertyAtom *hist = static_cast<FixPropertyAtom*>(modify->fix[ifix]);
    if (!hist->array_atom) continue;   // vector style: one row of get_nvalues() per atom
    wall_histories.push_back(hist);
    wall_values += hist->get_nvalues();
  }
}

void FixAdaptTimestep::init_list(int, NeighList *ptr)
{
  list = ptr;
}

void FixAdaptTimestep::setup(int)
{
  track_list_build();
  spacetree::TimestepVeto veto(0.0,safety,eps);
  const PairScan scan = scan_pairs(veto_on ? &veto : NULL);
  overlap_now = scan.maxOverlap;
  overlap_peak = std::max(overlap_peak,overlap_now);
  contacts_now = scan.contacts;
  choose_timestep(scan,veto.limit());
  if (rollback_on) save_state();
}

/* The deepest overlap and the number of contacts over the group's pairs, and the veto over the
   approaching ones (tested against the largest step creep can give). Own/ghost pairs appear on
   both ranks: they count half on each. */

FixAdaptTimestep::PairScan FixAdaptTimestep::scan_pairs(spacetree::TimestepVeto *veto)
{
  // max overlap, contacts, critical pairs, contact soon, largest contact speed (vimpact)
  double local[5] = {0.0,0.0,0.0,0.0,0.0};
  const bool speeds = policy.impactSpeed > 0.0;
  double **x = atom->x;
  double **v = atom->v;
  double *radius = atom->radius;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double dt_test = policy.creep*update->dt;   // the step the veto tests
  if (speeds) {
    // accelerations f/m at the end of the step (f is complete for owned atoms only): sent to
    // ghosts. Atoms outside the group count as held (a fixed base sphere feels a force it never
    // follows); keeping them in the group only overestimates the contact speed (smaller steps).
    const int nall = atom->nlocal + atom->nghost;
    accel.assign(3*size_t(nall),0.0);
    for (int i = 0; i < atom->nlocal; i++)
      if (atom->mask[i] & groupbit)
        for (int k = 0; k < 3; k++) accel[3*i+k] = atom->f[i][k]/atom->rmass[i];
    comm->forward_comm_fix(this);
  }
  if (list) {
    neighbor->build_one(list->index);
    for (int ii = 0; ii < list->inum; ii++) {
      const int i = list->ilist[ii];
      const int *jlist = list->firstneigh[i];
      for (int jj = 0; jj < list->numneigh[i]; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        if (!(mask[i] & groupbit) && !(mask[j] & groupbit)) continue;
        const double share = j < nlocal ? 1.0 : 0.5;
        const double dx = x[j][0]-x[i][0], dy = x[j][1]-x[i][1], dz = x[j][2]-x[i][2];
        const double dist = std::sqrt(dx*dx + dy*dy + dz*dz);
        const double overlap = radius[i] + radius[j] - dist;
        if (overlap > 0.0) {
          local[0] = std::max(local[0],overlap);
          local[1] += share;
          if (speeds && dist > 0.0) {
            const double vn = ((v[j][0]-v[i][0])*dx + (v[j][1]-v[i][1])*dy + (v[j][2]-v[i][2])*dz)/dist;
            const double *ai = &accel[3*size_t(i)], *aj = &accel[3*size_t(j)];
            const double an = ((aj[0]-ai[0])*dx + (aj[1]-ai[1])*dy + (aj[2]-ai[2])*dz)/dist;
            local[4] = std::max(local[4],spacetree::contactSpeed(vn,an,policy.contactTime));
          }
        } else if (policy.dtContact > 0.0 && dist > 0.0) {
          // a pair that may touch within the next step already needs the contact resolution
          const double approach = -((v[j][0]-v[i][0])*dx + (v[j][1]-v[i][1])*dy + (v[j][2]-v[i][2])*dz)/dist;
          if (approach*dt_test > -overlap) {
            local[3] = 1.0;
            local[4] = std::max(local[4],approach);
          }
        }
        if (veto && veto->consider(x[i],v[i],radius[i],x[j],v[j],radius[j],dt_test)) local[2] += share;
      }
    }
  }
  // walls: each local particle against the wall's closest point, treated as a sphere of radius 0
  // at rest; a moving wall only reports its overlaps (its speed is not known here)
  {
    const double rest[3] = {0.0,0.0,0.0};
    // gap = distance from the particle surface to the wall (< 0: overlap), delta = centre to
    // the wall's closest point
    auto wall_contact = [&](int i, double gap, const double *delta, bool moving) {
      const double dist = std::sqrt(delta[0]*delta[0] + delta[1]*delta[1] + delta[2]*delta[2]);
      if (gap < 0.0) {
        local[0] = std::max(local[0],-gap);
        local[1] += 1.0;
        if (speeds && dist > 0.0) {   // the particle's speed towards the wall
          const double vn = (v[i][0]*delta[0] + v[i][1]*delta[1] + v[i][2]*delta[2])/dist;
          const double an = (atom->f[i][0]*delta[0] + atom->f[i][1]*delta[1] + atom->f[i][2]*delta[2])
                            /(dist*atom->rmass[i]);
          local[4] = std::max(local[4],spacetree::contactSpeed(vn,an,policy.contactTime));
        }
        return;
      }
      if (moving) return;
      if (policy.dtContact > 0.0 && dist > 0.0) {
        const double approach = (v[i][0]*delta[0] + v[i][1]*delta[1] + v[i][2]*delta[2])/dist;
        if (approach*dt_test > gap) {
          local[3] = 1.0;
          local[4] = std::max(local[4],approach);
        }
      }
      const double xw[3] = {x[i][0]+delta[0],x[i][1]+delta[1],x[i][2]+delta[2]};
      if (veto && veto->consider(x[i],v[i],radius[i],xw,rest,0.0,dt_test)) local[2] += 1.0;
    };
    std::vector<double> mesh_gap, mesh_delta;
    for (int f = 0; f < modify->nfix; f++) {
      if (strcmp(modify->fix[f]->style,"wall/gran") != 0) continue;
      FixWallGran *wall = static_cast<FixWallGran*>(modify->fix[f]);
      if (!wall->is_mesh_wall()) {   // fix wall/gran ... primitive
        if (!wall->primitiveWall()) continue;
        for (int i = 0; i < nlocal; i++) {
          if (!(mask[i] & groupbit)) continue;
          double delta[3];
          const double gap = wall->primitiveWall()->resolveContact(x[i],radius[i],delta);
          wall_contact(i,gap,delta,wall->is_moving());
        }
        continue;
      }
      // fix wall/gran ... mesh: the particles of each triangle's contact list (fix
      // neighlist/mesh, owned and ghost triangles), the closest triangle per particle and mesh
      for (int m = 0; m < wall->n_meshes(); m++) {
        FixMeshSurface *fm = wall->mesh_list()[m];
        TriMesh *mesh = fm->triMesh();
        FixNeighlistMesh *nl = fm->meshNeighlist();
        if (!mesh || !nl) continue;
        const bool moving = mesh->prop().getElementProperty<MultiVectorContainer<double,3,3> >("v") != NULL;
        mesh_gap.assign(nlocal,std::numeric_limits<double>::infinity());
        mesh_delta.resize(3*size_t(nlocal));
        const int ntri = mesh->sizeLocal() + mesh->sizeGhost();
        for (int t = 0; t < ntri; t++) {
          const std::vector<int> &candidates = nl->get_contact_list(t);
          for (const int i : candidates) {
            if (i >= nlocal || !(mask[i] & groupbit)) continue;
            double delta[3];
            int barysign;
            const double gap = mesh->resolveTriSphereContact(i,t,radius[i],x[i],delta,barysign);
            if (gap < mesh_gap[i]) {
              mesh_gap[i] = gap;
              for (int d = 0; d < 3; d++) mesh_delta[3*size_t(i)+d] = delta[d];
            }
          }
        }
        for (int i = 0; i < nlocal; i++)
          if (mesh_gap[i] < 1e100) wall_contact(i,mesh_gap[i],&mesh_delta[3*size_t(i)],moving);
      }
    }
  }

  double global[5];
  MPI_Allreduce(&local[0],&global[0],1,MPI_DOUBLE,MPI_MAX,world);
  MPI_Allreduce(&local[1],&global[1],2,MPI_DOUBLE,MPI_SUM,world);
  MPI_Allreduce(&local[3],&global[3],2,MPI_DOUBLE,MPI_MAX,world);
  critical_last = global[2];
  PairScan scan;
  scan.maxOverlap = global[0];
  scan.contacts = global[1];
  scan.contactSoon = global[1] > 0.0 || global[3] > 0.0;
  scan.contactSpeed = global[4];
  return scan;
}

void FixAdaptTimestep::choose_timestep(const PairScan &scan, double veto_limit_local)
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
  contact_speed = scan.contactSpeed;
  limits.listMargin = list_margin();
  // keep at least half the skin as look-ahead: rebuild the lists in the next step when less is left
  if (limits.listMargin < 0.5*neighbor->skin) next_reneighbor = update->ntimestep + 1;
  if (neighbor->spacetree && neighbor->spacetree->tree.statistics().deepestPopulatedLevel >= 0)
    limits.finestCell = neighbor->spacetree->tree.meshSize(
        neighbor->spacetree->tree.statistics().deepestPopulatedLevel);

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
    fprintf(history,BIGINT_FORMAT " %.12g %.12g %g %d %d %.6g %g %g %.6g " BIGINT_FORMAT " %.6g\n",update->ntimestep,
            update->atime + (update->ntimestep - update->atimestep)*dt,d.dt,critical_last,
            int(d.vetoed),int(d.floored),scan.maxOverlap,scan.contacts,rollbacks,limits.listMargin,
            neighbor->lastcall,scan.contactSpeed);
  if (d.dt != dt) set_dt(d.dt);
}

/* Positions at the last list build: a rebuild happens after initial_integrate, so the positions
   at the end of that step are the ones the list was built from. */

void FixAdaptTimestep::track_list_build()
{
  if (neighbor->lastcall == x_build_step) return;
  x_build_step = neighbor->lastcall;
  const int nlocal = atom->nlocal;
  x_build.resize(3*nlocal);
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) x_build[3*i+k] = atom->x[i][k];
}

/* skin - 2 * largest displacement since the list was built (all ranks): a pair outside the list
   is at least this far from touching. */

double FixAdaptTimestep::list_margin()
{
  const int nlocal = atom->nlocal;
  double dmax_local = 0.0, dmax;
  if (int(x_build.size()) != 3*nlocal) dmax_local = 0.5*neighbor->skin;   // atoms came or went
  else
    for (int i = 0; i < nlocal; i++) {
      const double dx = atom->x[i][0]-x_build[3*i], dy = atom->x[i][1]-x_build[3*i+1],
                   dz = atom->x[i][2]-x_build[3*i+2];
      dmax_local = std::max(dmax_local,dx*dx + dy*dy + dz*dz);
    }
  if (int(x_build.size()) == 3*nlocal) dmax_local = std::sqrt(dmax_local);
  MPI_Allreduce(&dmax_local,&dmax,1,MPI_DOUBLE,MPI_MAX,world);
  return std::max(neighbor->skin - 2.0*dmax,1e-3*neighbor->skin);
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
  if (!redoing) save_history();
}

void FixAdaptTimestep::end_of_step()
{
  track_list_build();
  spacetree::TimestepVeto veto(0.0,safety,eps);
  PairScan scan = scan_pairs(veto_on ? &veto : NULL);

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
      restore_history();
      // the steps before this one keep their dt in the elapsed time; this one gets d.dt
      const bigint now = update->ntimestep;
      update->ntimestep = now - 1;
      set_dt(d.dt);
      update->ntimestep = now;
      if (neighbor->lastcall > saved_step) rollbacks_rebuilt += 1;
      redo_step();
      rollbacks += 1;
      veto.reset();
      scan = scan_pairs(veto_on ? &veto : NULL);
    }
  }

  overlap_now = scan.maxOverlap;
  overlap_peak = std::max(overlap_peak,overlap_now);
  contacts_now = scan.contacts;
  choose_timestep(scan,veto.limit());
  if (rollback_on) save_state();
}

/* The state at the start of the next step: what initial_integrate reads (x, v, omega, f,
   torque) and the image flags, by tag so that a step that re-neighboured (sorted atoms) can
   still be undone. */

void FixAdaptTimestep::save_state()
{
  const int nlocal = atom->nlocal;
  nsaved = nlocal;
  saved_step = update->ntimestep;
  s_tag.assign(atom->tag,atom->tag + nlocal);
  s_image.assign(atom->image,atom->image + nlocal);
  s_x.resize(3*nlocal);
  s_v.resize(3*nlocal);
  s_omega.resize(3*nlocal);
  s_f.resize(3*nlocal);
  s_torque.resize(3*nlocal);
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) {
      s_x[3*i+k] = atom->x[i][k];
      s_v[3*i+k] = atom->v[i][k];
      s_omega[3*i+k] = atom->omega[i][k];
      s_f[3*i+k] = atom->f[i][k];
      s_torque[3*i+k] = atom->torque[i][k];
    }
  s_wall.resize(size_t(wall_values)*nlocal);
  for (int i = 0, o = 0; i < nlocal; i++)
    for (FixPropertyAtom *hist : wall_histories)
      for (int k = 0; k < hist->get_nvalues(); k++) s_wall[o++] = hist->array_atom[i][k];
}

bool FixAdaptTimestep::restore_state()
{
  const int nlocal = atom->nlocal;
  const bool rebuilt = neighbor->lastcall > saved_step;
  const int R = 17 + wall_values;   // record: tag, image, x, v, omega, f, torque, wall histories
  auto record = [&](int k, double *r) {
    r[0] = s_tag[k];
    r[1] = s_image[k];
    for (int d = 0; d < 3; d++) {
      r[2+d] = s_x[3*k+d];
      r[5+d] = s_v[3*k+d];
      r[8+d] = s_omega[3*k+d];
      r[11+d] = s_f[3*k+d];
      r[14+d] = s_torque[3*k+d];
    }
    for (int w = 0; w < wall_values; w++) r[17+w] = s_wall[size_t(wall_values)*k + w];
  };
  std::vector<double> mine(size_t(R)*nsaved), shipped, received;
  for (int k = 0; k < nsaved; k++) record(k,&mine[size_t(R)*k]);

  // plan: the record each current local atom takes (nothing is changed before all ranks agree)
  std::vector<const double*> plan(nlocal,(const double*)NULL);
  int ok = (saved_step == update->ntimestep - 1) ? 1 : 0;
  if (ok && !rebuilt) {
    // no re-neighbouring: same atoms, same order
    ok = (nlocal == nsaved);
    for (int k = 0; ok && k < nsaved; k++) {
      if (atom->tag[k] != s_tag[k]) ok = 0;
      else plan[k] = &mine[size_t(R)*k];
    }
  } else if (ok) {
    // re-neighboured: atoms sorted and possibly moved to another rank; find them by ID and send
    // the records of atoms that left to every rank (few: only those that crossed a boundary)
    if (!atom->map_style) ok = 0;
    for (int k = 0; ok && k < nsaved; k++) {
      const int i = atom->map(s_tag[k]);
      if (i >= 0 && i < nlocal && !plan[i]) plan[i] = &mine[size_t(R)*k];
      else shipped.insert(shipped.end(),&mine[size_t(R)*k],&mine[size_t(R)*k] + R);
    }
  }
  if (rebuilt) {   // collective: every rank takes part, whatever its own verdict
    int nsend = int(shipped.size()), nprocs = comm->nprocs;
    std::vector<int> counts(nprocs), offsets(nprocs,0);
    MPI_Allgather(&nsend,1,MPI_INT,counts.data(),1,MPI_INT,world);
    for (int p = 1; p < nprocs; p++) offsets[p] = offsets[p-1] + counts[p-1];
    received.resize(size_t(offsets[nprocs-1] + counts[nprocs-1]));
    MPI_Allgatherv(shipped.data(),nsend,MPI_DOUBLE,received.data(),counts.data(),offsets.data(),
                   MPI_DOUBLE,world);
    for (size_t r = 0; ok && r < received.size(); r += R) {
      const int i = atom->map(int(received[r]));
      if (i >= 0 && i < nlocal && !plan[i]) plan[i] = &received[r];
    }
    for (int i = 0; ok && i < nlocal; i++) if (!plan[i]) ok = 0;   // an atom without a saved state
  }
  int counts_local[2] = {nlocal,nsaved}, counts_all[2];
  MPI_Allreduce(counts_local,counts_all,2,MPI_INT,MPI_SUM,world);
  if (counts_all[0] != counts_all[1]) ok = 0;                // atoms were added or deleted
  int all_ok;
  MPI_Allreduce(&ok,&all_ok,1,MPI_INT,MPI_MIN,world);
  if (!all_ok) return false;

  for (int i = 0; i < nlocal; i++) {
    const double *r = plan[i];
    // a re-neighbouring step may have wrapped the atom through a periodic boundary: keep its
    // current image and shift the saved position into that image
    double unwrapped[3], shift[3], zero[3] = {0.0,0.0,0.0};
    domain->unmap(const_cast<double*>(r+2),tagint(r[1]),unwrapped);
    domain->unmap(zero,atom->image[i],shift);
    for (int d = 0; d < 3; d++) {
      atom->x[i][d] = unwrapped[d] - shift[d];
      atom->v[i][d] = r[5+d];
      atom->omega[i][d] = r[8+d];
      atom->f[i][d] = r[11+d];
      atom->torque[i][d] = r[14+d];
    }
    int w = 17;
    for (FixPropertyAtom *hist : wall_histories)
      for (int k = 0; k < hist->get_nvalues(); k++) hist->array_atom[i][k] = r[w++];
  }
  comm->forward_comm();   // ghosts take the restored positions and velocities
  return true;
}

/* Contact history as the pair style holds it in the history list's pages: saved before the pair
   forces of each step (after any re-neighbouring, which refills the pages from the per-atom
   copy that fix contacthistory took at the start of the step). */

void FixAdaptTimestep::save_history()
{
  h_step = update->ntimestep;
  h_inum = -1;
  Pair *pair = force->pair;
  PairGran *pg = dynamic_cast<PairGran*>(pair);
  if (!pg || !pair->list || !pair->listgranhistory) return;
  NeighList *gl = pair->list, *hl = pair->listgranhistory;
  const int dnum = pg->dnum();
  h_flag.clear();
  h_value.clear();
  for (int ii = 0; ii < gl->inum; ii++) {
    const int i = gl->ilist[ii];
    const int n = gl->numneigh[i];
    h_flag.insert(h_flag.end(),hl->firstneigh[i],hl->firstneigh[i] + n);
    h_value.insert(h_value.end(),hl->firstdouble[i],hl->firstdouble[i] + dnum*n);
  }
  h_inum = gl->inum;
}

void FixAdaptTimestep::restore_history()
{
  Pair *pair = force->pair;
  PairGran *pg = dynamic_cast<PairGran*>(pair);
  if (!pg || !pair->list || !pair->listgranhistory) return;
  if (h_step != update->ntimestep || h_inum != pair->list->inum)
    error->one(FLERR,"Fix adapt/timestep rollback: contact-history snapshot does not match the list");
  NeighList *gl = pair->list, *hl = pair->listgranhistory;
  const int dnum = pg->dnum();
  size_t nf = 0, nv = 0;
  for (int ii = 0; ii < gl->inum; ii++) {
    const int i = gl->ilist[ii];
    const int n = gl->numneigh[i];
    std::copy(h_flag.begin() + nf,h_flag.begin() + nf + n,hl->firstneigh[i]);
    std::copy(h_value.begin() + nv,h_value.begin() + nv + dnum*n,hl->firstdouble[i]);
    nf += n;
    nv += dnum*n;
  }
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

int FixAdaptTimestep::pack_comm(int n, int *list_, double *buf, int, int *)
{
  for (int m = 0; m < n; m++)
    for (int k = 0; k < 3; k++) buf[3*m+k] = accel[3*size_t(list_[m])+k];
  return 3;   // LIGGGHTS 3.8 Comm::forward_comm_fix wants the values per atom
}

void FixAdaptTimestep::unpack_comm(int n, int first, double *buf)
{
  for (int m = 0; m < n; m++)
    for (int k = 0; k < 3; k++) accel[3*size_t(first+m)+k] = buf[3*m+k];
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
