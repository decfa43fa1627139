/* spacetree-dem: pair style for triangulated rigid particles (thin layer over the core's
   MeshContactFinder and ContactModel). */

#include "pair_trimesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>
#include <vector>

#include <mpi.h>

#include "atom.h"
#include "comm.h"
#include "contact/MeshContact.h"
#include "contact_model/ContactModel.h"
#include "dynamics/RigidBody.h"
#include "error.h"
#include "fix_trimesh_state.h"
#include "fix_trimesh_template.h"
#include "force.h"
#include "geometry/PenaltyTriangleDistance.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neigh_request.h"
#include "neighbor.h"
#include "trimesh_deck_checks.h"
#include "trimesh_parallel_contacts.h"
#include "update.h"

using namespace LAMMPS_NS;
namespace ct = spacetree::contact;
namespace cm = spacetree::contact_model;
namespace dy = spacetree::dynamics;

namespace {

// The core's view of atom i for the contact kinematics: pose, velocity, angular velocity
// (as angular momentum; none without rotation), infinite mass for obstacles.
dy::RigidBody body(const TrimeshTypeTemplate &tt, const ct::Pose &pose, const double *v,
                   const double *omega, double rmass, bool rotation)
{
  dy::RigidBody b = tt.fixed ? dy::RigidBody::fixed(pose.position,pose.orientation)
                             : dy::RigidBody::free(rmass,tt.inertia * (rmass / tt.mass),
                                                   pose.position,pose.orientation);
  if (!tt.fixed) {
    b.velocity = Eigen::Vector3d(v[0],v[1],v[2]);
    if (rotation) b.setAngularVelocity(Eigen::Vector3d(omega[0],omega[1],omega[2]));
  }
  return b;
}

// Upper limit of penalty Newton steps (stage 1 + stage 2): the core's kMaxNewtonIterations.
const int kMaxNewtonSteps = spacetree::geometry::kMaxNewtonIterations;

}

namespace LAMMPS_NS {
struct PairTrimeshModel {
  ct::MeshContactOptions contact;
  double stiffness = 0.0, damping = 0.0;        // eq. (1): S, D
  double friction = 0.0, sliding_damping = 0.0; // Coulomb mu, viscous gamma
  bool rotation = true;
  cm::ContactModelSpec spec;                    // sub-models (core contact_model/)
  cm::ContactParameters parameters;             // their coefficients (every type pair)
  cm::ContactModelTable models;                 // one per type pair, built at init

  int threads = 0;                              // threads keyword: 0 = TBB default, 1 = serial
  std::unique_ptr<TrimeshParallelContacts> search;
  std::vector<TrimeshCandidatePair> pairs;
  ct::MeshContactStatistics stats;
};
}

PairTrimesh::PairTrimesh(LAMMPS *lmp) :
  Pair(lmp), model(new PairTrimeshModel), templ(NULL), list(NULL),
  stat_max_penetration(0)
{
  single_enable = 0;
  restartinfo = 0;
}

PairTrimesh::~PairTrimesh()
{
  if (allocated) {
    memory->destroy(setflag);
    memory->destroy(cutsq);
  }
}

void PairTrimesh::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag,n+1,n+1,"pair:setflag");
  memory->create(cutsq,n+1,n+1,"pair:cutsq");
  for (int i = 1; i <= n; i++)
    for (int j = i; j <= n; j++) setflag[i][j] = 0;
}

void PairTrimesh::settings(int narg, char **arg)
{
  bool have_eps = false, have_s = false, have_d = false;
  bool have_continuation = false;
  // a Newton step count: an integer >= lo (the sum with the other stage is checked below)
  const auto newton_steps = [&](const char *kw, const char *val, long lo) {
    char *end = NULL;
    const long n = strtol(val,&end,10);
    if (end == val || *end != '\0' || n < lo || n > kMaxNewtonSteps) {
      char msg[200];
      snprintf(msg,sizeof(msg),"Illegal pair_style trimesh command: %s '%s' must be an integer in "
               "[%ld, %d]",kw,val,lo,kMaxNewtonSteps);
      error->all(FLERR,msg);
    }
    return int(n);
  };
  int iarg = 0;
  while (iarg < narg) {
    const char *kw = arg[iarg];
    if (iarg+2 > narg) {
      std::string msg = std::string("Illegal pair_style trimesh command: keyword '") + kw + "' needs a value";
      error->all(FLERR,msg.c_str());
    }
    const char *val = arg[iarg+1];
    if (strcmp(kw,"eps") == 0) { model->contact.epsilon = force->numeric(FLERR,val); have_eps = true; }
    else if (strcmp(kw,"stiffness") == 0) { model->stiffness = force->numeric(FLERR,val); have_s = true; }
    else if (strcmp(kw,"damping") == 0) { model->damping = force->numeric(FLERR,val); have_d = true; }
    else if (strcmp(kw,"friction") == 0) {
      if (iarg+3 > narg) error->all(FLERR,"Illegal pair_style trimesh command: friction needs MU GAMMA");
      model->friction = force->numeric(FLERR,val);
      model->sliding_damping = force->numeric(FLERR,arg[iarg+2]);
      iarg++;
    } else if (strcmp(kw,"method") == 0) {
      try { model->contact.method = ct::parseTriangleDistanceMethod(val); }
      catch (const std::exception &) {
        std::string msg = std::string("Illegal pair_style trimesh command: method '") + val +
                          "' (exact, penalty or hybrid)";
        error->all(FLERR,msg.c_str());
      }
    } else if (strcmp(kw,"iterations") == 0) {
      model->contact.newtonIterations = newton_steps(kw,val,1);
    } else if (strcmp(kw,"continuation") == 0) {
      model->contact.continuationIterations = newton_steps(kw,val,0);
      have_continuation = true;
    } else if (strcmp(kw,"rotation") == 0) {
      if (strcmp(val,"yes") == 0) model->rotation = true;
      else if (strcmp(val,"no") == 0) model->rotation = false;
      else error->all(FLERR,"Illegal pair_style trimesh command: rotation must be yes or no");
    } else if (strcmp(kw,"threads") == 0) {
      char *end = NULL;
      const long n = strtol(val,&end,10);
      if (end == val || *end != '\0' || n < 0 || n > 4096) {
        std::string msg = std::string("Illegal pair_style trimesh command: threads '") + val +
                          "' must be an integer >= 0 (0 = TBB default, 1 = serial)";
        error->all(FLERR,msg.c_str());
      }
      model->threads = int(n);
    } else {
      std::string msg = std::string("Illegal pair_style trimesh command: unknown keyword '") + kw + "'";
      error->all(FLERR,msg.c_str());
    }
    iarg += 2;
  }
  if (!have_eps || !have_s || !have_d)
    error->all(FLERR,"Illegal pair_style trimesh command: eps, stiffness and damping are required");
  if (!(model->contact.epsilon > 0.0)) error->all(FLERR,"Illegal pair_style trimesh command: eps must be > 0");
  if (!(model->stiffness > 0.0)) error->all(FLERR,"Illegal pair_style trimesh command: stiffness must be > 0");
  if (!(model->damping >= 0.0)) error->all(FLERR,"Illegal pair_style trimesh command: damping must be >= 0");
  if (!(model->friction >= 0.0) || !(model->sliding_damping >= 0.0))
    error->all(FLERR,"Illegal pair_style trimesh command: friction MU GAMMA must be >= 0");
  // Newton steps, defaults resolved by the core (penalty 8; hybrid 5 + 4, the two-stage hybrid)
  const ct::TriangleDistanceMethod method = model->contact.method;
  if (have_continuation && method != ct::TriangleDistanceMethod::Hybrid)
    error->all(FLERR,"Illegal pair_style trimesh command: continuation needs method hybrid");
  const int stage1 = ct::newtonIterationsOf(model->contact);
  const int stage2 = ct::continuationIterationsOf(model->contact);
  if (stage1 + stage2 > kMaxNewtonSteps) {
    char msg[200];
    snprintf(msg,sizeof(msg),"Illegal pair_style trimesh command: iterations %d + continuation %d "
             "must be <= %d Newton steps",stage1,stage2,kMaxNewtonSteps);
    error->all(FLERR,msg);
  }
  // the contact model: eq. (1), plus viscous friction with `friction MU GAMMA`
  model->spec = cm::ContactModelSpec();
  model->parameters = cm::ContactParameters();
  model->parameters.set("stiffness",model->stiffness);
  model->parameters.set("damping",model->damping);
  if (model->friction > 0.0 && model->sliding_damping > 0.0) {
    model->spec.tangential = "viscous";
    model->parameters.set("friction",model->friction);
    model->parameters.set("slidingDamping",model->sliding_damping);
  }
  try { cm::ContactModel probe(model->spec,model->parameters); }
  catch (const std::exception &e) {
    error->all(FLERR,(std::string("Illegal pair_style trimesh command: ") + e.what()).c_str());
  }
  // threads 0: TBB's default is every core this process may use; ranks that share a node share
  // those cores, so each takes its part (no oversubscription with several ranks per node)
  int threads = model->threads, on_node = 1, tbb_default = 0;
  if (threads == 0) {
    MPI_Comm node;
    MPI_Comm_split_type(world,MPI_COMM_TYPE_SHARED,comm->me,MPI_INFO_NULL,&node);
    MPI_Comm_size(node,&on_node);
    MPI_Comm_free(&node);
    tbb_default = TrimeshParallelContacts::defaultThreads();
    if (on_node > 1) threads = std::max(1,tbb_default/on_node);
  }
  model->search.reset(new TrimeshParallelContacts(model->contact,threads));
  if (comm->me == 0 && screen) {
    if (method == ct::TriangleDistanceMethod::Hybrid)
      fprintf(screen,"pair_style trimesh: method hybrid, %d Newton steps%s%s\n",stage1,
              stage2 > 0 ? " + " : " (single stage)",
              stage2 > 0 ? (std::to_string(stage2) + " for the pairs stage 1 leaves uncertified").c_str() : "");
    else if (method == ct::TriangleDistanceMethod::Penalty)
      fprintf(screen,"pair_style trimesh: method penalty, %d Newton steps\n",stage1);
    if (model->threads == 0)
      fprintf(screen,"pair_style trimesh: triangle checks on %d thread(s) per rank (threads 0: TBB "
              "default %d shared by %d rank(s) on this node)\n",model->search->threads(),tbb_default,on_node);
    else
      fprintf(screen,"pair_style trimesh: triangle checks on %d thread(s)\n",model->search->threads());
  }
}

void PairTrimesh::coeff(int narg, char **arg)
{
  if (narg != 2) error->all(FLERR,"Incorrect args for pair coefficients: pair_coeff * * (no values)");
  if (!allocated) allocate();
  int ilo,ihi,jlo,jhi;
  force->bounds(arg[0],atom->ntypes,ilo,ihi);
  force->bounds(arg[1],atom->ntypes,jlo,jhi);
  int count = 0;
  for (int i = ilo; i <= ihi; i++)
    for (int j = MAX(jlo,i); j <= jhi; j++) { setflag[i][j] = 1; count++; }
  if (count == 0) error->all(FLERR,"Incorrect args for pair coefficients");
}

void PairTrimesh::init_style()
{
  if (!atom->sphere_flag)
    error->all(FLERR,"Pair style trimesh requires atom_style sphere or granular (atom style mismatch)");
  if (comm->ghost_velocity == 0)
    error->all(FLERR,"Pair style trimesh requires ghost atoms store velocity: use 'communicate single vel yes'");
  if (force->newton_pair)
    error->all(FLERR,"Pair style trimesh requires newton off (granular half list, forces on owned atoms)");

  templ = FixTrimeshTemplate::find(lmp,"Pair style trimesh");
  if (!templ) error->all(FLERR,"Pair style trimesh requires fix trimesh/template");
  try {
    const cm::ContactParameters &p = model->parameters;
    model->models = cm::ContactModelTable(atom->ntypes,model->spec,[&p](int,int) { return p; });
  } catch (const std::exception &e) {
    error->all(FLERR,(std::string("Pair style trimesh: ") + e.what()).c_str());
  }

  templ->set_halo(model->contact.epsilon);
  templ->apply_to_atoms(false);   // radius = bounding radius + eps before the neighbour lists
  check_template_types_reach_trimesh(lmp,*templ);
  check_grains_fit_box(lmp,*templ);

  const int irequest = neighbor->request(this);
  neighbor->requests[irequest]->half = 0;
  neighbor->requests[irequest]->gran = 1;
}

void PairTrimesh::init_list(int, NeighList *ptr)
{
  list = ptr;
}

double PairTrimesh::init_one(int i, int j)
{
  // bounding radius + eps of each type (fixed obstacles included): the gran list uses the
  // per-atom radius; this cut-off sizes bins and the ghost shell
  return templ->max_rad(i) + templ->max_rad(j);
}

void *PairTrimesh::extract(const char *name, int &dim)
{
  dim = 0;
  if (strcmp(name,"eps") == 0) return (void *) &model->contact.epsilon;
  return NULL;
}

void PairTrimesh::contact_statistics(double out[5])
{
  double local[4] = {(double) model->stats.contacts, (double) model->stats.bodyPairs,
                     (double) model->stats.trianglePairsChecked, (double) model->stats.fallbacks};
  MPI_Allreduce(local,out,4,MPI_DOUBLE,MPI_SUM,world);
  MPI_Allreduce(&stat_max_penetration,&out[4],1,MPI_DOUBLE,MPI_MAX,world);
}

std::size_t PairTrimesh::candidate_pairs() const
{
  return model->pairs.size();
}

const TrimeshCandidatePair &PairTrimesh::candidate_pair(std::size_t k) const
{
  return model->pairs[k];
}

const std::vector<ct::ContactPoint> &PairTrimesh::contacts_of(std::size_t k) const
{
  return model->search->contacts(k);
}

const ct::MeshContactOptions &PairTrimesh::contact_options() const
{
  return model->contact;
}

void PairTrimesh::compute(int eflag, int vflag)
{
  if (eflag || vflag) ev_setup(eflag,vflag);
  else evflag = vflag_fdotr = 0;

  // ghosts need the owners' current orientation (positions came with the regular comm)
  templ->state()->forward_orientations();

  double **x = atom->x, **v = atom->v, **f = atom->f, **omega = atom->omega;
  double **torque = atom->torque;
  double *rmass = atom->rmass, *radius = atom->radius;
  int *type = atom->type, *tag = atom->tag;
  double **quat = templ->state()->quat;
  const int nlocal = atom->nlocal;
  const bool rotation = model->rotation;
  const double dt = update->dt;

  model->stats = ct::MeshContactStatistics();
  stat_max_penetration = 0.0;
  model->pairs.clear();

  const int inum = list->inum;
  int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const TrimeshTypeTemplate *ti = templ->type_template(type[i]);
    if (!ti) continue;
    int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const TrimeshTypeTemplate *tj = templ->type_template(type[j]);
      if (!tj || (ti->fixed && tj->fixed)) continue;

      // bounding-sphere precheck on radius = R + eps: surfaces closer than 2 eps needs this
      const double dx = x[i][0]-x[j][0], dy = x[i][1]-x[j][1], dz = x[i][2]-x[j][2];
      const double radsum = radius[i] + radius[j];
      if (dx*dx + dy*dy + dz*dz >= radsum*radsum) continue;

      // canonical body order, the same on every rank (newton off: computed on both)
      model->pairs.push_back(canonical_candidate_pair(i,j,*ti,*tj,tag,x,quat));
    }
  }

  // The triangle checks of all candidates: serially (threads 1) or as tasks of the core engine;
  // the forces below follow the candidates and their contacts in list order either way.
  try { model->search->search(model->pairs,model->stats); }
  catch (const std::exception &e) {
    error->one(FLERR,(std::string("pair_style trimesh: contact search failed: ") + e.what()).c_str());
  }

  for (std::size_t kp = 0; kp < model->pairs.size(); kp++) {
    const std::vector<ct::ContactPoint> &contacts = model->search->contacts(kp);
    if (contacts.empty()) continue;
    {
      const TrimeshCandidatePair &p = model->pairs[kp];
      const int a = p.a, b = p.b;
      const ct::Pose &pa = p.pose_a, &pb = p.pose_b;
      const TrimeshTypeTemplate *ta = templ->type_template(type[a]), *tb = templ->type_template(type[b]);
      dy::RigidBody ba = body(*ta,pa,v[a],omega[a],rmass[a],rotation);
      dy::RigidBody bb = body(*tb,pb,v[b],omega[b],rmass[b],rotation);
      const cm::ContactModel &law = model->models.at(type[a],type[b]);
      // i is owned; j only where newton off lets this rank add to it
      const bool a_owned = force->newton_pair || a < nlocal;
      const bool b_owned = force->newton_pair || b < nlocal;

      for (const ct::ContactPoint &c : contacts) {
        stat_max_penetration = std::max(stat_max_penetration,c.penetration);
        const cm::Contact k = cm::makeContact(ba,bb,c.point,c.normal,c.penetration);
        // on the first body; the second gets -fa
        const Eigen::Vector3d fa = law.evaluate(k,nullptr,dt).forceOnFirst;
        if (a_owned) { f[a][0] += fa[0]; f[a][1] += fa[1]; f[a][2] += fa[2]; }
        if (b_owned) { f[b][0] -= fa[0]; f[b][1] -= fa[1]; f[b][2] -= fa[2]; }
        if (rotation) {
          if (a_owned) {
            const Eigen::Vector3d tq = (c.point - pa.position).cross(fa);
            torque[a][0] += tq[0]; torque[a][1] += tq[1]; torque[a][2] += tq[2];
          }
          if (b_owned) {
            const Eigen::Vector3d tq = (c.point - pb.position).cross(-fa);
            torque[b][0] += tq[0]; torque[b][1] += tq[1]; torque[b][2] += tq[2];
          }
        }
      }
    }
  }
}
