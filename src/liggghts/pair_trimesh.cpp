/* spacetree-dem: pair style for triangulated rigid particles (thin layer over the core's
   MeshContactFinder and ContactModel).
   Slightly over 600 lines because settings() carries the style's whole keyword grammar (sub-model
   slots, coefficients, method, threads: ~150 lines of checks, each naming its keyword) beside
   compute(); the contact law, materials, walls, history and deck checks live in their own files
   (trimesh_contact_coefficients, trimesh_wall_contacts, fix_trimesh_contact_history, ...). */

#include "pair_trimesh.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include <mpi.h>

#include "atom.h"
#include "comm.h"
#include "contact/MeshContact.h"
#include "contact_model/ContactHistory.h"
#include "contact_model/ContactModel.h"
#include "contact_model/SubModelRegistry.h"
#include "dynamics/RigidBody.h"
#include "error.h"
#include "fix_trimesh_contact_history.h"
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
#include "trimesh_contact_coefficients.h"
#include "trimesh_deck_checks.h"
#include "trimesh_parallel_contacts.h"
#include "trimesh_wall_contacts.h"
#include "contact/SphereMeshContact.h"
#include "update.h"

using namespace LAMMPS_NS;
namespace ct = spacetree::contact;
namespace cm = spacetree::contact_model;
namespace dy = spacetree::dynamics;

namespace {

// Whether a word is a number (a keyword's optional value follows).
bool is_number(const char *word)
{
  char *end = NULL;
  strtod(word,&end);
  return end != word && *end == '\0';
}

// Upper limit of penalty Newton steps (stage 1 + stage 2): the core's kMaxNewtonIterations.
const int kMaxNewtonSteps = spacetree::geometry::kMaxNewtonIterations;

}

namespace LAMMPS_NS {
struct PairTrimeshModel {
  ct::MeshContactOptions contact;
  bool rotation = true;
  TrimeshContactSettings settings;              // sub-models and explicit coefficients
  cm::ContactModelTable models;                 // one per type pair, built at init
  std::vector<double> stable_steps;             // per type pair (TrimeshContactCoefficients)
  FixTrimeshContactHistory *history = NULL;     // per-contact history (sub-models that keep it)
  std::unique_ptr<cm::ContactHistoryMatcher> matcher;
  std::vector<double> records;                  // one pair's new history records

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
  std::vector<ct::ContactPoint> group_contacts;    // one pair's contacts (spheres, walls)
  std::vector<Eigen::Vector3d> group_forces;       // their forces on the grain (walls)
};
}

namespace {
// The fix holding the per-contact history (ID and style: a restart file restores it by both).
const char *const kHistoryFixId = "trimesh_contact_history";
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
  // a repeated pair_style line starts from the defaults
  model->settings = TrimeshContactSettings();
  model->contact = ct::MeshContactOptions();
  model->rotation = true;
  model->threads = 0;
  TrimeshContactSettings &cs = model->settings;
  bool have_eps = false, have_continuation = false, have_tangential = false;
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
  // a coefficient: a finite number > 0 (or >= 0)
  const auto coefficient = [&](const char *kw, const char *val, bool positive) {
    // parsed here (not by force->numeric) so that 'nan', 'inf' and words name their keyword
    char *end = NULL;
    const double v = strtod(val,&end);
    if (end == val || *end != '\0' || !std::isfinite(v) || v < 0.0 || (positive && v == 0.0)) {
      std::string msg = std::string("Illegal pair_style trimesh command: ") + kw + " '" + val +
                        "' must be a finite number " + (positive ? "> 0" : ">= 0");
      error->all(FLERR,msg.c_str());
    }
    return v;
  };
  // a sub-model keyword of a slot (the core's registry names the choices)
  const auto sub_model = [&](cm::Slot slot, const char *val) {
    try { cm::findSubModel(slot,val); }
    catch (const std::exception &e) {
      error->all(FLERR,(std::string("Illegal pair_style trimesh command: ") + e.what()).c_str());
    }
    cs.spec[slot] = val;
  };
  int iarg = 0;
  while (iarg < narg) {
    const char *kw = arg[iarg];
    if (iarg+2 > narg) {
      std::string msg = std::string("Illegal pair_style trimesh command: keyword '") + kw + "' needs a value";
      error->all(FLERR,msg.c_str());
    }
    const char *val = arg[iarg+1];
    if (strcmp(kw,"eps") == 0) { model->contact.epsilon = coefficient(kw,val,true); have_eps = true; }
    else if (strcmp(kw,"stiffness") == 0) cs.stiffness = coefficient(kw,val,true);
    else if (strcmp(kw,"damping") == 0) cs.damping = coefficient(kw,val,false);
    else if (strcmp(kw,"friction") == 0) {
      cs.friction = coefficient("friction MU",val,false);
      // GAMMA (the viscous model's sliding coefficient) when a number follows
      if (iarg+2 < narg && is_number(arg[iarg+2])) {
        cs.sliding_damping = coefficient("friction GAMMA",arg[iarg+2],false);
        iarg++;
      }
    } else if (strcmp(kw,"tangential_stiffness") == 0) cs.tangential_stiffness = coefficient(kw,val,true);
    else if (strcmp(kw,"model") == 0) sub_model(cm::Slot::Normal,val);
    else if (strcmp(kw,"damping_model") == 0) sub_model(cm::Slot::Damping,val);
    else if (strcmp(kw,"tangential") == 0) { sub_model(cm::Slot::Tangential,val); have_tangential = true; }
    else if (strcmp(kw,"rolling_friction") == 0) sub_model(cm::Slot::Rolling,val);
    else if (strcmp(kw,"cohesion") == 0) sub_model(cm::Slot::Cohesion,val);
    else if (strcmp(kw,"method") == 0) {
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
  if (!have_eps) error->all(FLERR,"Illegal pair_style trimesh command: eps is required");
  cs.eps = model->contact.epsilon;
  cs.rotation = model->rotation;
  // `friction MU GAMMA` alone: the viscous model of eq. (1) (none unless both are > 0)
  if (!have_tangential && !std::isnan(cs.friction) && !std::isnan(cs.sliding_damping) &&
      cs.friction > 0.0 && cs.sliding_damping > 0.0)
    cs.spec.tangential = "viscous";
  if (cs.spec.tangential == "viscous" && std::isnan(cs.sliding_damping))
    error->all(FLERR,"Illegal pair_style trimesh command: tangential viscous needs friction MU GAMMA "
               "(GAMMA: sliding damping, N s/m)");
  if (cs.spec.tangential != "viscous" && have_tangential && !std::isnan(cs.sliding_damping))
    error->all(FLERR,"Illegal pair_style trimesh command: friction MU GAMMA: GAMMA is the sliding damping "
               "of tangential viscous (give friction MU alone)");
  if (cs.spec.tangential != "history" && !std::isnan(cs.tangential_stiffness))
    error->all(FLERR,"Illegal pair_style trimesh command: tangential_stiffness needs tangential history");
  if (cs.spec.rolling != "none" && !model->rotation)
    error->all(FLERR,"Illegal pair_style trimesh command: rolling_friction needs rotation yes");
  if (cs.spec.damping == "none" && !std::isnan(cs.damping))
    error->all(FLERR,"Illegal pair_style trimesh command: damping D with damping_model none");
  // the history store exists from here on (thermo may name it; a restart file fills it)
  if (cm::historySizeOf(cs.spec) > 0 && modify->find_fix(kHistoryFixId) < 0) {
    char *fixarg[3] = {(char *) kHistoryFixId,(char *) "all",(char *) "trimesh/contact_history"};
    modify->add_fix(3,fixarg);
  }
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
    error->all(FLERR,cm::historySizeOf(model->settings.spec) > 0
               ? "Pair style trimesh requires newton off (granular half list, forces on owned atoms; "
                 "the contact history of tangential history and rolling_friction epsd is kept on "
                 "the owned atoms of each pair)"
               : "Pair style trimesh requires newton off (granular half list, forces on owned atoms)");

  templ = FixTrimeshTemplate::find(lmp,"Pair style trimesh");
  if (!templ) error->all(FLERR,"Pair style trimesh requires fix trimesh/template");

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

  // the contact model of every type pair, from the keywords and the materials
  TrimeshContactCoefficients coefficients(lmp);
  model->models = coefficients.build(model->settings,templ,model->sphere_type_radius);
  coefficients.report(model->models,model->settings,templ);
  model->stable_steps = coefficients.stable_steps(model->models,model->settings,templ);
  setup_history();

  templ->set_halo(model->contact.epsilon);
  templ->apply_to_atoms(false);   // radius = bounding radius + eps before the neighbour lists
  check_template_types_reach_trimesh(lmp,*templ);
  check_grains_fit_box(lmp,*templ);

  if (!model->walls) model->walls.reset(new TrimeshWallContacts(lmp));
  model->walls->init(templ,model->contact);

  const int irequest = neighbor->request(this);
  neighbor->requests[irequest]->half = 0;
  neighbor->requests[irequest]->gran = 1;
}

/* The fix holding the per-contact history when the contact model keeps any (created by
   settings(); a restart file restores it when its ID and style match); none otherwise. */
void PairTrimesh::setup_history()
{
  const int size = model->models.historySize();
  model->history = NULL;
  model->matcher.reset();
  if (size == 0) return;
  const int ifix = modify->find_fix(kHistoryFixId);
  if (ifix >= 0) model->history = dynamic_cast<FixTrimeshContactHistory*>(modify->fix[ifix]);
  if (!model->history)
    error->all(FLERR,"Pair style trimesh: fix trimesh_contact_history (its per-contact history) was "
               "deleted or is not trimesh/contact_history");
  cm::ContactHistoryMatchOptions match;
  match.normalCosine = model->contact.mergeNormalCosine;
  model->matcher.reset(new cm::ContactHistoryMatcher(size,match));
  model->history->set_record_size(model->matcher->recordSize());
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

double PairTrimesh::stable_step(int itype, int jtype) const
{
  const int n = atom->ntypes;
  if (itype < 1 || jtype < 1 || itype > n || jtype > n || model->stable_steps.size() != size_t((n+1)*(n+1)))
    return std::numeric_limits<double>::infinity();
  return model->stable_steps[itype*(n+1)+jtype];
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

  // Forces: grain pairs in list order, then sphere pairs, then grains against walls, each pair's
  // contacts through the law of its type pair (with history: matched to the pair's previous
  // records, which live on its owned atoms and vanish when the pair opens). A run's setup
  // repeats the last force computation: dt 0 leaves the history as it is (LIGGGHTS'
  // shearupdate 0).
  const double history_dt = update->setupflag ? 0.0 : update->dt;
  if (model->history) model->history->begin();
  const auto body_of = [&](int k, const ct::Pose &pose) {
    return trimesh_contact_body(templ->type_template(type[k]),pose,v[k],omega[k],rmass[k],radius[k],
                                rotation);
  };
  const auto edge = [&](int k) { return templ->type_template(type[k])->shape.minimumEdgeLength; };
  for (std::size_t kp = 0; kp < model->pairs.size(); kp++) {
    const std::vector<ct::ContactPoint> &contacts = model->search->contacts(kp);
    if (contacts.empty()) continue;
    const TrimeshCandidatePair &p = model->pairs[kp];
    add_pair_forces(p.a,body_of(p.a,p.pose_a),p.b,body_of(p.b,p.pose_b),0,contacts,
                    0.5 * std::min(edge(p.a),edge(p.b)),history_dt,NULL);
  }
  std::vector<ct::ContactPoint> &group = model->group_contacts;
  for (std::size_t kp = 0; kp < model->sphere_pairs.size(); kp++) {
    const std::size_t begin = model->sphere_offsets[kp], end = model->sphere_offsets[kp+1];
    if (begin == end) continue;
    const TrimeshCandidatePair &p = model->sphere_pairs[kp];
    group.assign(model->sphere_contacts.begin() + begin,model->sphere_contacts.begin() + end);
    add_pair_forces(p.a,body_of(p.a,p.pose_a),p.b,body_of(p.b,p.pose_b),0,group,0.5 * edge(p.a),
                    history_dt,NULL);
  }

  // Grains against walls (the grain first; a wall is a body of infinite mass moving with its
  // surface velocity at the contact point), one grain-wall pair (consecutive contacts) at a time.
  if (!model->walls->empty()) {
    model->walls->find(model->wall_contacts,model->stats);
    const std::vector<TrimeshWallContact> &wcs = model->wall_contacts;
    std::vector<Eigen::Vector3d> &forces = model->group_forces;
    for (std::size_t k = 0; k < wcs.size();) {
      std::size_t e = k;
      group.clear();
      while (e < wcs.size() && wcs[e].atom == wcs[k].atom && wcs[e].wall_key == wcs[k].wall_key)
        group.push_back(wcs[e++].contact);
      const int a = wcs[k].atom;
      ct::Pose pa;
      pa.position = Eigen::Vector3d(x[a][0],x[a][1],x[a][2]);
      pa.orientation = Eigen::Quaterniond(quat[a][0],quat[a][1],quat[a][2],quat[a][3]);
      // the wall's velocity at the pair's first contact point (each point's own below)
      forces.resize(group.size());
      add_pair_forces(a,body_of(a,pa),-1,trimesh_wall_body(group[0].point,wcs[k].wall_velocity),
                      wcs[k].wall_type,group,0.5 * edge(a),history_dt,forces.data(),&wcs[k]);
      for (std::size_t c = k; c < e; c++) model->walls->report_to_mesh(wcs[c],forces[c-k]);
      k = e;
    }
  }
  if (model->history) model->history->finish();
}

/* The contacts of one body pair: a (first, owned or ghost) and b (second; b < 0: a wall of
   material type wall_type, whose contacts wall[0..n) give each point's wall velocity and the
   history key) by the law of their type pair, forces and torques to the atoms this rank owns
   (newton off: a pair across two ranks is computed on both, in the same body order). With
   history, the pair's records are read from an owned atom (keyed by the partner's tag, a wall's
   key for a wall), matched to these contacts within match_distance, advanced by dt and stored
   on every owned atom of the pair. force_on_a (if given): the force on a of each contact. */

void PairTrimesh::add_pair_forces(int a, const dy::RigidBody &ba, int b, const dy::RigidBody &bb,
                                  int wall_type, const std::vector<ct::ContactPoint> &contacts,
                                  double match_distance, double dt, Eigen::Vector3d *force_on_a,
                                  const TrimeshWallContact *wall)
{
  double **f = atom->f, **torque = atom->torque;
  const int *type = atom->type, *tag = atom->tag;
  const int nlocal = atom->nlocal;
  const bool a_owned = force->newton_pair || a < nlocal;
  const bool b_owned = b >= 0 && (force->newton_pair || b < nlocal);
  if (!a_owned && !b_owned) return;
  const int partner_of_a = b >= 0 ? tag[b] : wall->wall_key;
  const cm::ContactModel &law = model->models.at(type[a],b >= 0 ? type[b] : wall_type);

  double *slots = NULL;
  int stride = 0;
  FixTrimeshContactHistory *history = model->history;
  if (history) {
    const int owner = a_owned ? a : b, partner = a_owned ? partner_of_a : tag[a];
    int count = 0;
    const double *previous = history->lookup(owner,partner,count);
    ct::Pose pa;
    pa.position = ba.position;
    pa.orientation = ba.orientation;
    model->matcher->setDistance(match_distance);
    model->matcher->match(previous,std::size_t(count),contacts,pa,model->records);
    slots = model->records.data() + cm::kContactAnchorDoubles;
    stride = model->matcher->recordSize();
  }

  dy::RigidBody wall_body = bb;
  for (std::size_t kc = 0; kc < contacts.size(); kc++) {
    const ct::ContactPoint &c = contacts[kc];
    if (wall) wall_body = trimesh_wall_body(c.point,wall[kc].wall_velocity);
    stat_max_penetration = std::max(stat_max_penetration,c.penetration);
    // a merged point stands for c.weight contact points (ContactMerger)
    const cm::Contact k = cm::makeContact(ba,wall ? wall_body : bb,c.point,c.normal,c.weight * c.penetration,
                                          law.rolling() != NULL);
    // on the first body; the second gets -fa (and -ta)
    const cm::ContactForces out = law.evaluate(k,slots ? slots + kc*stride : NULL,dt);
    const Eigen::Vector3d &fa = out.forceOnFirst;
    if (force_on_a) force_on_a[kc] = fa;
    if (a_owned) { f[a][0] += fa[0]; f[a][1] += fa[1]; f[a][2] += fa[2]; }
    if (b_owned) { f[b][0] -= fa[0]; f[b][1] -= fa[1]; f[b][2] -= fa[2]; }
    if (model->rotation) {
      if (a_owned) {
        Eigen::Vector3d tq = (c.point - ba.position).cross(fa);
        if (law.rolling()) tq += out.torqueOnFirst;
        torque[a][0] += tq[0]; torque[a][1] += tq[1]; torque[a][2] += tq[2];
      }
      if (b_owned) {
        Eigen::Vector3d tq = (c.point - bb.position).cross(-fa);
        if (law.rolling()) tq -= out.torqueOnFirst;
        torque[b][0] += tq[0]; torque[b][1] += tq[1]; torque[b][2] += tq[2];
      }
    }
  }
  if (history) {
    const int n = int(contacts.size());
    if (a_owned) history->store(a,partner_of_a,model->records.data(),n);
    if (b_owned) history->store(b,tag[a],model->records.data(),n);
  }
}
