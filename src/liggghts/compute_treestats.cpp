/* spacetree-dem: see compute_treestats.h */

#include "compute_treestats.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <vector>

#include "atom.h"
#include "error.h"
#include "modify.h"
#include "neigh_spacetree.h"
#include "neighbor.h"
#include "update.h"

using namespace LAMMPS_NS;

namespace {
// Summary entries (0-based here, c_ID[index + 1] in a deck).
enum Summary {
  kComparisons = 0,    // candidate pairs tested by the last sweep
  kRefinements,        // cells refined by the last grid update
  kCoarsenings,        // refined cells removed (27 children each) by the last grid update
  kDeepestLevel,       // finest level hosting a particle (max over ranks)
  kCells,              // cells of all levels
  kLeafCells,          // cells that are not refined
  kVertices,           // non-hanging grid vertices of all levels
  kRealParticles,      // owned particles (sum over ranks = atom count)
  kVirtualLinks,       // (vertex, coarser particle) links of the last sweep
  kGridResets,         // cube re-chosen since the start (cumulative)
  kUpdateSeconds,      // wall time of the last grid update (max over ranks)
};
// Per level l: cells, vertices, real (owned) particles, virtual links.
}

ComputeTreestats::ComputeTreestats(LAMMPS *lmp, int &iarg, int narg, char **arg) :
  Compute(lmp, iarg, narg, arg)
{
  if (iarg != narg) {
    char msg[256];
    snprintf(msg,sizeof(msg),"Illegal compute treestats command: it takes no arguments, got '%s'",
             arg[iarg]);
    error->all(FLERR,msg);
  }
  vector_flag = 1;
  size_vector = kSummary + kPerLevel*kLevels;
  extvector = 0;  // counts, not to be divided by the atom count (thermo_modify norm)
  vector = new double[size_vector];
  std::fill(vector,vector+size_vector,0.0);
}

ComputeTreestats::~ComputeTreestats()
{
  delete [] vector;
}

void ComputeTreestats::init()
{
  if (!modify->find_fix_style_strict("spacetree",0))
    error->all(FLERR,"Compute treestats requires fix spacetree (which requires "
               "'neighbor <skin> spacetree')");
}

void ComputeTreestats::compute_vector()
{
  invoked_vector = update->ntimestep;
  double local[kSummary + kPerLevel*kLevels];
  std::fill(local,local+size_vector,0.0);
  double deepest = 0.0, seconds = 0.0;

  const NeighSpacetree *st = neighbor->spacetree;
  const spacetree::AdaptiveGrid *grid = st ? st->search.grid() : NULL;
  if (grid) {
    const spacetree::Spacetree &tree = st->search.tree();
    const spacetree::AdaptiveGridStatistics &g = grid->statistics();
    const spacetree::SpacetreeStatistics &t = tree.statistics();
    local[kComparisons] = double(t.candidatePairs);
    local[kRefinements] = double(g.refinements);
    local[kCoarsenings] = double(g.coarsenings);
    local[kCells] = double(g.cells);
    local[kLeafCells] = double(grid->leafCellCount());
    local[kGridResets] = double(g.geometryResets);
    deepest = g.deepestLevel;
    seconds = st->search.lastGridSeconds();
    const int nlevels = std::min<int>(kLevels,int(g.levels.size()));
    const std::vector<std::uint64_t> vertices = grid->verticesPerLevel();
    for (int l = 0; l < nlevels; l++) {
      local[kSummary + kPerLevel*l + 0] = double(g.levels[l].cells);
      local[kSummary + kPerLevel*l + 1] = double(vertices[l]);
      local[kVertices] += double(vertices[l]);
    }
    const int tlevels = std::min<int>(kLevels,int(t.levels.size()));
    for (int l = 0; l < tlevels; l++) {
      local[kSummary + kPerLevel*l + 3] = double(t.levels[l].virtualLinks);
      local[kVirtualLinks] += double(t.levels[l].virtualLinks);
    }
    // Owned particles only, so that the sum over ranks is the atom count.
    const int nown = std::min(atom->nlocal,tree.particleCount());
    for (int i = 0; i < nown; i++) {
      const int l = tree.levelOf(i);
      if (l < kLevels) local[kSummary + kPerLevel*l + 2] += 1.0;
    }
    local[kRealParticles] = nown;
  }
  MPI_Allreduce(local,vector,size_vector,MPI_DOUBLE,MPI_SUM,world);
  double maxima[2] = {deepest,seconds}, global_max[2];
  MPI_Allreduce(maxima,global_max,2,MPI_DOUBLE,MPI_MAX,world);
  vector[kDeepestLevel] = global_max[0];
  vector[kUpdateSeconds] = global_max[1];
}
