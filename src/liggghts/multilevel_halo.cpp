/* spacetree-dem: the per-size ghost rule of neighbor spacetree (see multilevel_halo.h). */

#include "multilevel_halo.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>

#include <mpi.h>

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "domain_wedge.h"
#include "error.h"
#include "fix.h"
#include "fix_trimesh_state.h"
#include "fix_trimesh_template.h"
#include "force.h"
#include "modify.h"
#include "neighbor.h"

using namespace LAMMPS_NS;
namespace pl = spacetree::parallel;

MultilevelHalo::MultilevelHalo(LAMMPS *lmp) : Pointers(lmp) {}

MultilevelHalo::~MultilevelHalo() = default;

void MultilevelHalo::reset_settings()
{
  levels_ = true;
  ratio_ = 4.0;
  largest_guess_ = -1.0;
}

bool MultilevelHalo::set_keyword(const char *key, const char *value)
{
  char msg[256];
  if (strcmp(key,"halo") == 0) {
    if (!value || (strcmp(value,"levels") != 0 && strcmp(value,"single") != 0)) {
      snprintf(msg,sizeof(msg),"Illegal neighbor spacetree command: halo '%s' is neither "
               "'levels' nor 'single'",value ? value : "");
      error->all(FLERR,msg);
    }
    levels_ = strcmp(value,"levels") == 0;
    return true;
  }
  if (strcmp(key,"halo_ratio") == 0) {
    char *end = NULL;
    const double q = value ? strtod(value,&end) : 0.0;
    if (!value || end == value || *end != '\0' || !(q > 1.0) || !std::isfinite(q)) {
      snprintf(msg,sizeof(msg),"Illegal neighbor spacetree command: halo_ratio '%s' must be a "
               "number > 1",value ? value : "");
      error->all(FLERR,msg);
    }
    ratio_ = q;
    return true;
  }
  return false;
}

MultilevelHalo *MultilevelHalo::install()
{
  if (!levels_) return NULL;
  char why[200] = "";
  if (domain->triclinic) snprintf(why,sizeof(why),"a triclinic box");
  else if (force->newton_pair) snprintf(why,sizeof(why),"newton on");
  else if (dynamic_cast<DomainWedge *>(domain)) snprintf(why,sizeof(why),"a wedge domain");
  else
    for (int i = 0; i < modify->nfix && !why[0]; i++) {
      Fix *f = modify->fix[i];
      if (f->use_rad_for_cut_neigh_and_ghost() && f->extend_cut_ghost() > 0.0)
        snprintf(why,sizeof(why),"fix %s (%s), which extends the ghost cut-off",f->id,f->style);
    }
  if (why[0]) {
    char msg[400];
    snprintf(msg,sizeof(msg),"Neighbor spacetree: halo levels does not apply with %s: every atom "
             "gets the stock ghost shell (radius + largest radius + skin)",why);
    if (comm->me == 0) error->warning(FLERR,msg);
    return NULL;
  }
  return this;
}

double MultilevelHalo::shell_floor() const
{
  const double skin = neighbor->skin;
  double floor = 0.0;
  // comm_modify cutoff: the shell the stock rule would give for it
  if (comm->cutghostuser > 0.0) floor = 0.5*comm->cutghostuser + 0.5*skin;
  // insertion fixes check new particles for overlap against owned and ghost atoms
  const double factor = std::max(1.0,neighbor->contactDistanceFactor);
  for (int i = 0; i < modify->nfix; i++) {
    Fix *f = modify->fix[i];
    if (strncmp(f->style,"insert",6) != 0) continue;
    double rins = 0.0;
    for (int t = 1; t <= atom->ntypes; t++) rins = std::max(rins,f->max_rad(t));
    floor = std::max(floor,rins*factor + skin);
  }
  return floor;
}

double MultilevelHalo::effective_radius(int type, double radius) const
{
  const double t = type_radius_[type];
  return t > 0.0 ? t : radius;
}

double MultilevelHalo::radius_of(int i) const
{
  return effective_radius(atom->type[i],atom->radius[i]);
}

void MultilevelHalo::begin()
{
  const int ntypes = atom->ntypes;
  // triangulated types: radius = template bounding radius + eps (apply_to_atoms sets exactly
  // that before the list build, also for atoms inserted since the last one)
  templ_ = NULL;
  for (int i = 0; i < modify->nfix && !templ_; i++)
    if (strcmp(modify->fix[i]->style,"trimesh/template") == 0)
      templ_ = static_cast<FixTrimeshTemplate *>(modify->fix[i]);
  type_radius_.assign(ntypes+1,0.0);
  if (templ_)
    for (int t = 1; t <= ntypes; t++)
      if (const TrimeshTypeTemplate *tt = templ_->type_template(t))
        type_radius_[t] = tt->boundingRadius + templ_->halo();

  // Global classes: built from the largest radius, then the largest radius in each. One
  // collective when the largest radius is the one of the last call (the usual case), two when
  // it changed: each round reduces [largest radius, largest radius per class of the guess].
  const int nlocal = atom->nlocal;
  double local = 0.0;
  for (int i = 0; i < nlocal; i++) local = std::max(local,radius_of(i));
  for (int round = 0; ; round++) {
    try {
      classes_ = pl::HaloSizeClasses(std::max(largest_guess_,0.0),ratio_);
    } catch (const std::exception &e) {
      error->all(FLERR,e.what());
    }
    const int nclass = classes_.count();
    std::vector<double> mine(nclass+1,-1.0), all(nclass+1,-1.0);
    mine[0] = local;
    for (int i = 0; i < nlocal; i++) {
      const double r = radius_of(i);
      double &c = mine[1 + classes_.classOf(r)];
      c = std::max(c,r);
    }
    MPI_Allreduce(mine.data(),all.data(),nclass+1,MPI_DOUBLE,MPI_MAX,world);
    const double largest = std::max(all[0],0.0);
    if (largest == largest_guess_ || round > 0) {
      class_largest_.assign(all.begin()+1,all.end());
      break;
    }
    largest_guess_ = largest;
  }
  const int nclass = classes_.count();
  pass_class_.clear();
  for (int c = 0; c < nclass; c++)
    if (class_largest_[c] >= 0.0) pass_class_.push_back(c);
  if (pass_class_.empty()) pass_class_.push_back(0);   // no atoms: one (empty) pass

  // the processor grid's boxes, as Domain::set_local_box cuts them
  std::array<std::vector<double>,3> splits;
  const double *split[3] = {comm->xsplit,comm->ysplit,comm->zsplit};
  for (int d = 0; d < 3; d++)
    splits[d].assign(split[d],split[d] + comm->procgrid[d] + 1);
  const Eigen::Vector3d lo(domain->boxlo[0],domain->boxlo[1],domain->boxlo[2]);
  const Eigen::Vector3d hi(domain->boxhi[0],domain->boxhi[1],domain->boxhi[2]);
  const std::array<bool,3> periodic{{domain->periodicity[0] != 0,domain->periodicity[1] != 0,
                                     domain->periodicity[2] != 0}};
  pl::HaloRule rule;
  rule.skin = neighbor->skin;
  rule.contactFactor = neighbor->contactDistanceFactor;
  rule.minimumShell = shell_floor();
  // rounding of ghost coordinates (x + box length) and of the subdomain cuts
  rule.slack = 1e-10*std::max({(hi-lo).maxCoeff(),lo.cwiseAbs().maxCoeff(),hi.cwiseAbs().maxCoeff()});
  try {
    reach_ = pl::HaloReach(rule,pl::SubdomainGrid(lo,hi,periodic,splits));
  } catch (const std::exception &e) {
    error->all(FLERR,e.what());
  }
  reach_.setOwnBox(Eigen::Vector3d(domain->sublo[0],domain->sublo[1],domain->sublo[2]),
                   Eigen::Vector3d(domain->subhi[0],domain->subhi[1],domain->subhi[2]));
  surfaces_.clear();
  counts_.assign(nclass,ClassCounts());
}

const pl::HaloSurface *MultilevelHalo::surface_of(int i)
{
  if (!templ_) return nullptr;
  const TrimeshTypeTemplate *tt = templ_->type_template(atom->type[i]);
  if (!tt || !tt->fixed) return nullptr;
  // A turning obstacle sweeps its surface through space without moving its atom (no list
  // rebuild follows): it reaches by its bounding sphere. Without ghost velocities its turning
  // is unknown here, so every obstacle does. (Translation moves the atom: the skin covers it.)
  if (!comm->ghost_velocity || !atom->omega) return nullptr;
  const double *w = atom->omega[i];
  if (w[0] != 0.0 || w[1] != 0.0 || w[2] != 0.0) return nullptr;
  const double *q = templ_->state()->quat[i];
  surfaces_.emplace_back(new pl::PosedShapeSurface(
      tt->shape,Eigen::Vector3d(atom->x[i][0],atom->x[i][1],atom->x[i][2]),
      Eigen::Quaterniond(q[0],q[1],q[2],q[3])));
  return surfaces_.back().get();
}

const std::vector<int> &MultilevelHalo::owned_of_class(int c, int nowned, bool keep)
{
  double **x = atom->x;
  owned_.clear();
  owned_reach_.clear();
  ClassCounts &count = counts_[c];
  for (int i = 0; i < nowned; i++) {
    const double r = radius_of(i);
    if (classes_.classOf(r) != c) continue;
    bool served = false;
    const double reach = reach_.reach(Eigen::Vector3d(x[i][0],x[i][1],x[i][2]),r,
                                      class_largest_[c],&served);
    if (keep) {
      owned_.push_back(i);
      owned_reach_.push_back(reach);
    }
    count.served += served;
    count.largest_reach = std::max(count.largest_reach,reach);
  }
  return owned_;
}

void MultilevelHalo::add_partners(int first, int last, int c)
{
  double **x = atom->x;
  for (int i = first; i < last; i++)
    reach_.addPartner(Eigen::Vector3d(x[i][0],x[i][1],x[i][2]),radius_of(i),surface_of(i));
  // the particles that will ask are those of the finer classes
  double finer = 0.0;
  for (size_t k = c + 1; k < class_largest_.size(); k++) finer = std::max(finer,class_largest_[k]);
  reach_.indexPartners(finer);
}

void MultilevelHalo::count_pass(int c, int nsent, int nrecv)
{
  counts_[c].sent += nsent;
  counts_[c].received += nrecv;
}
