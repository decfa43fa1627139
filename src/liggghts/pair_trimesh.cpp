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
#include "trimesh_contact_body.h"
#include "trimesh_parallel_contacts.h"
#include "trimesh_wall_contacts.h"
#include "contact/SphereMeshContact.h"
#include "update.h"

using namespace LAMMPS_NS;
namespace ct = spacetree::contact;
namespace cm = spacetree::contact_model;
namespace dy = spacetree::dynamics;

namespace {

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

  // Spheres (types without template) against grains and obstacles: candidates (a: the body,
  // b: the sphere), searched on the calling thread, and their contacts (offsets per candidate).
  std::unique_ptr<ct::SphereMeshContactFinder> spheres;
  std::vector<TrimeshCandidatePair> sphere_pairs;
  std::vector<ct::ContactPoint> sphere_contacts;
  std::vector<std::size_t> sphere_offsets;
  std::vector<double> sphere_type_radius;      // per type without template: largest radius

  // Grains against the walls of fix wall/gran (serially, after the pairs).
  std::unique_ptr<TrimeshWallContacts> walls;
  std::vector<TrimeshWallContact> wall_contacts;
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
  model->spheres.reset(new ct::SphereMeshContactFinder(model->contact));
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

  // Types without template are spheres: they meet grains and obstacles here, each other through
  // pair_style gran (pair_style hybrid; compute() stops at a touching pair of spheres); their
  // largest radius sizes the cut-offs (insertion templates and existing atoms, as pair gran).
  const int ntypes = atom->ntypes;
  std::vector<double> mine(ntypes+1,0.0);
  for (int t = 1; t <= ntypes; t++)
    if (!templ->type_template(t))
      for (int k = 0; k < modify->nfix; k++) mine[t] = std::max(mine[t],modify->fix[k]->max_rad(t));
  for (int i = 0; i < atom->nlocal; i++)
    if (!templ->type_template(atom->type[i])) mine[atom->type[i]] = std::max(mine[atom->type[i]],atom->radius[i]);
  model->sphere_type_radius.assign(ntypes+1,0.0);
  MPI_Allreduce(mine.data(),model->sphere_type_radius.data(),ntypes+1,MPI_DOUBLE,MPI_MAX,world);

  if (!model->walls) model->walls.reset(new TrimeshWallContacts(lmp));
  model->walls->init(templ,model->contact);

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
  // bounding radius + eps of each type (fixed obstacles included), the largest radius of a
  // sphere type: the gran list uses the per-atom radius; this cut-off sizes bins and the ghost
  // shell
  const auto reach = [&](int t) {
    return templ->type_template(t) ? templ->max_rad(t) : model->sphere_type_radius[t];
  };
  return reach(i) + reach(j);
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

  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  double *rmass = atom->rmass, *radius = atom->radius;
  int *type = atom->type, *tag = atom->tag;
  double **quat = templ->state()->quat;
  const bool rotation = model->rotation;

  model->stats = ct::MeshContactStatistics();
  stat_max_penetration = 0.0;
  model->pairs.clear();

  const int inum = list->inum;
  int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  model->sphere_pairs.clear();
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const TrimeshTypeTemplate *ti = templ->type_template(type[i]);
    int *jlist = firstneigh[i];
    const int jnum = numneigh[i];
    for (int jj = 0; jj < jnum; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const TrimeshTypeTemplate *tj = templ->type_template(type[j]);
      if (ti && tj && ti->fixed && tj->fixed) continue;

      // bounding-sphere precheck on radius = R + eps: surfaces closer than 2 eps needs this
      // (a sphere's radius is its outer surface: core r - eps plus the halo)
      const double dx = x[i][0]-x[j][0], dy = x[i][1]-x[j][1], dz = x[i][2]-x[j][2];
      const double radsum = radius[i] + radius[j];
      if (dx*dx + dy*dy + dz*dz >= radsum*radsum) continue;
      if (!ti && !tj) {
        char msg[512];
        snprintf(msg,sizeof(msg),"Pair style trimesh: spheres %d and %d (types %d and %d have no "
                 "template in fix trimesh/template) touch: sphere-sphere contacts need pair_style "
                 "gran, e.g. 'pair_style hybrid gran ... trimesh ...' with 'pair_coeff %d %d gran'",
                 tag[i],tag[j],type[i],type[j],std::min(type[i],type[j]),std::max(type[i],type[j]));
        error->one(FLERR,msg);
      }

      const auto pose_of = [&](int k) {
        ct::Pose p;
        p.position = Eigen::Vector3d(x[k][0],x[k][1],x[k][2]);
        if (templ->type_template(type[k]))
          p.orientation = Eigen::Quaterniond(quat[k][0],quat[k][1],quat[k][2],quat[k][3]);
        return p;
      };
      if (!ti || !tj) {   // a sphere against a grain or an obstacle: the body first
        const int a = ti ? i : j, b = ti ? j : i;
        const TrimeshTypeTemplate *ta = ti ? ti : tj;
        model->sphere_pairs.push_back({a,b,&ta->shape,NULL,pose_of(a),pose_of(b)});
        continue;
      }

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

  // Spheres against bodies, serially (a few closest points per pair).
  model->sphere_contacts.clear();
  model->sphere_offsets.assign(1,0);
  for (const TrimeshCandidatePair &p : model->sphere_pairs) {
    if (!(radius[p.b] > model->contact.epsilon)) {
      char msg[256];
      snprintf(msg,sizeof(msg),"Pair style trimesh: sphere atom %d has radius %g m, not above eps "
               "%g m (a sphere is a rigid core of radius r - eps plus the halo)",tag[p.b],radius[p.b],
               model->contact.epsilon);
      error->one(FLERR,msg);
    }
    model->spheres->find(*p.shape_a,p.pose_a,p.pose_b.position,radius[p.b],model->sphere_contacts,
                         &model->stats);
    model->sphere_offsets.push_back(model->sphere_contacts.size());
  }

  // Forces: grain pairs in list order, then sphere pairs.
  const auto body_of = [&](int k, const ct::Pose &pose) {
    return trimesh_contact_body(templ->type_template(type[k]),pose,v[k],omega[k],rmass[k],radius[k],
                                rotation);
  };
  for (std::size_t kp = 0; kp < model->pairs.size(); kp++) {
    const std::vector<ct::ContactPoint> &contacts = model->search->contacts(kp);
    if (contacts.empty()) continue;
    const TrimeshCandidatePair &p = model->pairs[kp];
    const dy::RigidBody ba = body_of(p.a,p.pose_a), bb = body_of(p.b,p.pose_b);
    for (const ct::ContactPoint &c : contacts) add_contact_force(p.a,ba,type[p.a],p.b,bb,type[p.b],c);
  }
  for (std::size_t kp = 0; kp < model->sphere_pairs.size(); kp++) {
    const std::size_t begin = model->sphere_offsets[kp], end = model->sphere_offsets[kp+1];
    if (begin == end) continue;
    const TrimeshCandidatePair &p = model->sphere_pairs[kp];
    const dy::RigidBody ba = body_of(p.a,p.pose_a), bb = body_of(p.b,p.pose_b);
    for (std::size_t c = begin; c < end; c++)
      add_contact_force(p.a,ba,type[p.a],p.b,bb,type[p.b],model->sphere_contacts[c]);
  }

  // Grains against walls (the grain first; a wall is a body of infinite mass moving with its
  // surface velocity at the contact point).
  if (!model->walls->empty()) {
    model->walls->find(model->wall_contacts,model->stats);
    for (const TrimeshWallContact &wc : model->wall_contacts) {
      const int a = wc.atom;
      ct::Pose pa;
      pa.position = Eigen::Vector3d(x[a][0],x[a][1],x[a][2]);
      pa.orientation = Eigen::Quaterniond(quat[a][0],quat[a][1],quat[a][2],quat[a][3]);
      const dy::RigidBody ba = body_of(a,pa);
      const Eigen::Vector3d fa =
          add_contact_force(a,ba,type[a],-1,trimesh_wall_body(wc.contact.point,wc.wall_velocity),
                            wc.wall_type,wc.contact);
      model->walls->report_to_mesh(wc,fa);
    }
  }
}

/* One contact by the pair style's law: the force on the first body a (its opposite on b, b < 0:
   a wall, nothing to add) and the torques about each centre; only to atoms this rank owns
   (newton off: a pair across two ranks is computed on both). */

Eigen::Vector3d PairTrimesh::add_contact_force(int a, const dy::RigidBody &ba, int type_a, int b,
                                               const dy::RigidBody &bb, int type_b,
                                               const ct::ContactPoint &c)
{
  double **f = atom->f, **torque = atom->torque;
  const int nlocal = atom->nlocal;
  const bool a_owned = a >= 0 && (force->newton_pair || a < nlocal);
  const bool b_owned = b >= 0 && (force->newton_pair || b < nlocal);
  stat_max_penetration = std::max(stat_max_penetration,c.penetration);
  const cm::Contact k = cm::makeContact(ba,bb,c.point,c.normal,c.penetration);
  // on the first body; the second gets -fa
  const Eigen::Vector3d fa = model->models.at(type_a,type_b).evaluate(k,nullptr,update->dt).forceOnFirst;
  if (a_owned) { f[a][0] += fa[0]; f[a][1] += fa[1]; f[a][2] += fa[2]; }
  if (b_owned) { f[b][0] -= fa[0]; f[b][1] -= fa[1]; f[b][2] -= fa[2]; }
  if (model->rotation) {
    if (a_owned) {
      const Eigen::Vector3d tq = (c.point - ba.position).cross(fa);
      torque[a][0] += tq[0]; torque[a][1] += tq[1]; torque[a][2] += tq[2];
    }
    if (b_owned) {
      const Eigen::Vector3d tq = (c.point - bb.position).cross(-fa);
      torque[b][0] += tq[0]; torque[b][1] += tq[1]; torque[b][2] += tq[2];
    }
  }
  return fa;
}
