/* spacetree-dem: see compute_halo.h */

#include "compute_halo.h"

#include <algorithm>
#include <cstdio>
#include <exception>
#include <vector>

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "multilevel_halo.h"
#include "neigh_spacetree.h"
#include "neighbor.h"
#include "parallel/HaloSizeClasses.h"
#include "update.h"

using namespace LAMMPS_NS;

namespace {
// Summary entries (0-based here, c_ID[index + 1] in a deck).
enum Summary {
  kOwned = 0,          // owned atoms of the group (sum over ranks)
  kGhosts,             // ghost atoms of the group (sum over ranks)
  kGhostsPerOwned,     // kGhosts / kOwned
  kClassesUsed,        // size classes holding atoms
  kServed,             // owned atoms sent farther than their own reach to serve a bigger ghost
  kRule,               // 1: halo levels (per size class), 0: the stock single shell
};
// Per class k: radius upper bound, owned, ghosts, ghosts per owned, largest reach (max).
enum PerClass { kBound = 0, kClassOwned, kClassGhosts, kClassRatio, kClassReach };
}

ComputeHalo::ComputeHalo(LAMMPS *lmp, int &iarg, int narg, char **arg) :
  Compute(lmp, iarg, narg, arg)
{
  if (iarg != narg) {
    char msg[256];
    snprintf(msg,sizeof(msg),"Illegal compute halo command: it takes no arguments, got '%s'",
             arg[iarg]);
    error->all(FLERR,msg);
  }
  if (!atom->radius_flag)
    error->all(FLERR,"Compute halo requires an atom style with a per-atom radius");
  vector_flag = 1;
  size_vector = kSummary + kPerClass*kClasses;
  extvector = 0;  // counts, not to be divided by the atom count (thermo_modify norm)
  vector = new double[size_vector];
  std::fill(vector,vector+size_vector,0.0);
}

ComputeHalo::~ComputeHalo()
{
  delete [] vector;
}

void ComputeHalo::compute_vector()
{
  invoked_vector = update->ntimestep;
  const MultilevelHalo *rule = comm->halo;
  const int nlocal = atom->nlocal, nall = nlocal + atom->nghost;
  double *radius = atom->radius;
  int *mask = atom->mask;

  // the classes of the rule's last exchange, or the same construction from the largest radius
  spacetree::parallel::HaloSizeClasses classes;
  if (rule) {
    classes = rule->classes();
  } else {
    double local = 0.0, largest = 0.0;
    for (int i = 0; i < nlocal; i++) local = std::max(local,radius[i]);
    MPI_Allreduce(&local,&largest,1,MPI_DOUBLE,MPI_MAX,world);
    const MultilevelHalo *settings = neighbor->spacetree ? neighbor->spacetree->halo.get() : NULL;
    try {
      classes = spacetree::parallel::HaloSizeClasses(largest,settings ? settings->ratio() : 4.0,kClasses);
    } catch (const std::exception &e) {
      error->all(FLERR,e.what());
    }
  }
  const auto class_of = [&](int i) {
    return std::min(kClasses-1,classes.classOf(rule ? rule->radius_of(i) : radius[i]));
  };

  std::vector<double> local(size_vector,0.0), reach(kClasses,0.0), global_reach(kClasses,0.0);
  for (int i = 0; i < nall; i++) {
    if (!(mask[i] & groupbit)) continue;
    const int c = class_of(i);
    local[kSummary + kPerClass*c + (i < nlocal ? kClassOwned : kClassGhosts)] += 1.0;
  }
  if (rule) {
    const std::vector<MultilevelHalo::ClassCounts> &counts = rule->counts();
    for (int c = 0; c < int(counts.size()) && c < kClasses; c++) {
      local[kServed] += double(counts[c].served);
      reach[c] = counts[c].largest_reach;
    }
  }
  MPI_Allreduce(local.data(),vector,size_vector,MPI_DOUBLE,MPI_SUM,world);
  MPI_Allreduce(reach.data(),global_reach.data(),kClasses,MPI_DOUBLE,MPI_MAX,world);

  vector[kOwned] = vector[kGhosts] = vector[kClassesUsed] = 0.0;
  for (int c = 0; c < kClasses; c++) {
    double *v = vector + kSummary + kPerClass*c;
    v[kBound] = c < classes.count() ? classes.upperBound(c) : 0.0;
    v[kClassRatio] = v[kClassOwned] > 0.0 ? v[kClassGhosts]/v[kClassOwned] : 0.0;
    v[kClassReach] = global_reach[c];
    vector[kOwned] += v[kClassOwned];
    vector[kGhosts] += v[kClassGhosts];
    if (v[kClassOwned] > 0.0) vector[kClassesUsed] += 1.0;
  }
  vector[kGhostsPerOwned] = vector[kOwned] > 0.0 ? vector[kGhosts]/vector[kOwned] : 0.0;
  vector[kRule] = rule ? 1.0 : 0.0;
}
