/* spacetree-dem: see fix_spacetree.h */

#include "fix_spacetree.h"

#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>

#include "comm.h"
#include "error.h"
#include "force.h"
#include "modify.h"
#include "neigh_spacetree.h"
#include "neighbor.h"
#include "tree/LeafCellVtk.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
const int kSpacetreeNeighborStyle = 3;  // Neighbor::style of `neighbor <skin> spacetree`
}

FixSpacetree::FixSpacetree(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), update_seconds(0.0), vtk_every(0)
{
  char msg[512];
  if (narg < 5 || strcmp(arg[3],"grid") != 0)
    error->all(FLERR,"Illegal fix spacetree command: expected 'grid regular|adaptive|reluctant' "
               "after the style");
  if (strcmp(arg[4],"regular") == 0) options.type = spacetree::GridType::Regular;
  else if (strcmp(arg[4],"adaptive") == 0) options.type = spacetree::GridType::Adaptive;
  else if (strcmp(arg[4],"reluctant") == 0) options.type = spacetree::GridType::Reluctant;
  else {
    snprintf(msg,sizeof(msg),"Illegal fix spacetree command: unknown grid type '%s' "
             "(regular, adaptive or reluctant)",arg[4]);
    error->all(FLERR,msg);
  }

  int iarg = 5;
  while (iarg < narg) {
    const char *key = arg[iarg];
    const int nvalues = strcmp(key,"vtk") == 0 ? 2 : 1;
    if (iarg + nvalues >= narg) {
      snprintf(msg,sizeof(msg),"Illegal fix spacetree command: keyword '%s' needs %d value%s",
               key,nvalues,nvalues > 1 ? "s" : "");
      error->all(FLERR,msg);
    }
    if (strcmp(key,"shock") == 0) {
      options.shock = force->inumeric(FLERR,arg[iarg+1]);
      if (options.shock <= 0) error->all(FLERR,"Illegal fix spacetree command: shock must be > 0");
    } else if (strcmp(key,"threshold") == 0) {
      options.coarseningThreshold = force->inumeric(FLERR,arg[iarg+1]);
      if (options.coarseningThreshold < 0)
        error->all(FLERR,"Illegal fix spacetree command: threshold must be >= 0");
    } else if (strcmp(key,"maxlevel") == 0) {
      options.maxLevel = force->inumeric(FLERR,arg[iarg+1]);
      if (options.maxLevel < 0 || options.maxLevel > spacetree::kMaxSpacetreeLevel) {
        snprintf(msg,sizeof(msg),"Illegal fix spacetree command: maxlevel %d is outside [0,%d]",
                 options.maxLevel,spacetree::kMaxSpacetreeLevel);
        error->all(FLERR,msg);
      }
    } else if (strcmp(key,"padding") == 0) {
      options.padding = force->numeric(FLERR,arg[iarg+1]);
      if (!(options.padding >= 0.0 && options.padding <= 10.0))
        error->all(FLERR,"Illegal fix spacetree command: padding must be in [0,10]");
    } else if (strcmp(key,"vtk") == 0) {
      vtk_every = force->inumeric(FLERR,arg[iarg+1]);
      vtk_file = arg[iarg+2];
      if (vtk_every <= 0) error->all(FLERR,"Illegal fix spacetree command: vtk interval must be > 0");
      if (comm->nprocs > 1 && vtk_file.find('%') == std::string::npos)
        error->all(FLERR,"Illegal fix spacetree command: on more than one MPI rank the vtk file "
                   "name needs a '%' (replaced by the rank; each rank writes its own grid)");
    } else {
      snprintf(msg,sizeof(msg),"Illegal fix spacetree command: unknown keyword '%s' "
               "(known: shock threshold maxlevel padding vtk)",key);
      error->all(FLERR,msg);
    }
    iarg += 1 + nvalues;
  }
  if (options.coarseningThreshold >= options.shock) {
    snprintf(msg,sizeof(msg),"Illegal fix spacetree command: threshold %d must be below shock %d "
             "(else fresh refinements are coarsened at once)",options.coarseningThreshold,options.shock);
    error->all(FLERR,msg);
  }
  if (modify->find_fix_style_strict("spacetree",0))
    error->all(FLERR,"Fix spacetree: only one fix spacetree may exist");
  if (vtk_every > 0) nevery = vtk_every;
}

FixSpacetree::~FixSpacetree()
{
  if (neighbor->spacetree && neighbor->spacetree->grid_fix == this)
    neighbor->spacetree->grid_fix = NULL;
}

int FixSpacetree::setmask()
{
  return vtk_every > 0 ? END_OF_STEP : 0;
}

void FixSpacetree::init()
{
  if (neighbor->style != kSpacetreeNeighborStyle || !neighbor->spacetree)
    error->all(FLERR,"Fix spacetree requires 'neighbor <skin> spacetree' (the grid drives that "
               "neighbor list builder; with bin, nsq or multi it would have no effect)");
  // The grid and the tree must agree on the halo and on the deepest level.
  spacetree::AdaptiveGridOptions wanted = options;
  wanted.epsilon = 0.5*neighbor->skin;
  wanted.pairsFromCaller = true;  // the builder's sweep reports its pairs (after_sweep)
  const int neighbor_max = neighbor->spacetree->options.maxLevel;
  if (wanted.maxLevel > neighbor_max) wanted.maxLevel = neighbor_max;
  if (!grid_ || grid_->options().epsilon != wanted.epsilon ||
      grid_->options().maxLevel != wanted.maxLevel) {
    try {
      grid_.reset(new spacetree::AdaptiveGrid(wanted));
    } catch (const std::exception &e) {
      error->all(FLERR,e.what());
    }
  }
}

void FixSpacetree::build_tree(spacetree::Spacetree &tree, const double (*x)[3],
                              const double (*v)[3], const double *radius, int nall, int nlocal)
{
  const double t0 = MPI_Wtime();
  grid_->update(x,v,radius,nall);
  update_seconds = MPI_Wtime() - t0;
  grid_->buildSpacetree(tree,x,radius,nall,nlocal);
}

void FixSpacetree::after_sweep(const double (*x)[3], const double (*v)[3], const double *radius,
                               int nall, const std::vector<int> &pair_i,
                               const std::vector<int> &pair_j)
{
  if (options.type != spacetree::GridType::Reluctant) return;
  const double t0 = MPI_Wtime();
  pair_second.resize(pair_j.size());
  for (size_t k = 0; k < pair_j.size(); k++) pair_second[k] = pair_j[k] < 0 ? ~pair_j[k] : pair_j[k];
  grid_->refineForPairs(x,v,radius,nall,pair_i.data(),pair_second.data(),pair_i.size());
  update_seconds += MPI_Wtime() - t0;
}

void FixSpacetree::end_of_step()
{
  if (vtk_every > 0 && update->ntimestep % vtk_every == 0) write_vtk();
}

void FixSpacetree::write_vtk()
{
  std::string name;
  char number[32];
  for (char c : vtk_file) {
    if (c == '*') {
      snprintf(number,sizeof(number),BIGINT_FORMAT,update->ntimestep);
      name += number;
    } else if (c == '%') {
      snprintf(number,sizeof(number),"%d",comm->me);
      name += number;
    } else name += c;
  }
  if (comm->me != 0 && vtk_file.find('%') == std::string::npos) return;  // one rank only
  std::ofstream out(name.c_str(),std::ios::binary);
  if (!out) {
    char msg[512];
    snprintf(msg,sizeof(msg),"Fix spacetree: cannot open vtk file '%s'",name.c_str());
    error->one(FLERR,msg);
  }
  char title[128];
  snprintf(title,sizeof(title),"spacetree %s leaf cells, step " BIGINT_FORMAT ", rank %d",
           spacetree::gridTypeName(options.type),update->ntimestep,comm->me);
  try {
    spacetree::writeLeafCellsVtk(*grid_,out,title);
  } catch (const std::exception &e) {
    error->one(FLERR,e.what());
  }
}
