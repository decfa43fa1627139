/* spacetree-dem: see compute_neigh_local.h */

#include "compute_neigh_local.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "granular_list_copy.h"
#include "memory.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"

using namespace LAMMPS_NS;

ComputeNeighLocal::ComputeNeighLocal(LAMMPS *lmp, int &iarg, int narg, char **arg) :
  Compute(lmp, iarg, narg, arg), list(NULL), nmax(0), array(NULL)
{
  if (iarg != narg) error->all(FLERR,"Illegal compute neigh/local command: it takes no arguments");
  if (!atom->tag_enable) error->all(FLERR,"Compute neigh/local requires atom IDs");
  local_flag = 1;
  size_local_cols = 2;
}

ComputeNeighLocal::~ComputeNeighLocal()
{
  memory->destroy(array);
}

void ComputeNeighLocal::init()
{
  if (force->pair == NULL)
    error->all(FLERR,"Compute neigh/local requires a granular pair style");

  request_granular_list_copy(neighbor,this,GranularListUser::Compute);
}

void ComputeNeighLocal::init_list(int, NeighList *ptr)
{
  list = ptr;
}

void ComputeNeighLocal::compute_local()
{
  invoked_local = update->ntimestep;
  neighbor->build_one(list->index);

  const int n = count_pairs(false);
  if (n > nmax) {
    memory->destroy(array);
    nmax = n;
    memory->create(array,nmax,2,"neigh/local:array");
    array_local = array;
  }
  size_local_rows = n;
  count_pairs(true);
}

int ComputeNeighLocal::count_pairs(bool store)
{
  int *tag = atom->tag;
  int *mask = atom->mask;
  int n = 0;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!(mask[i] & groupbit) && !(mask[j] & groupbit)) continue;
      if (store) {
        array[n][0] = tag[i];
        array[n][1] = tag[j];
      }
      n++;
    }
  }
  return n;
}

double ComputeNeighLocal::memory_usage()
{
  return 2.0*nmax*sizeof(double);
}
