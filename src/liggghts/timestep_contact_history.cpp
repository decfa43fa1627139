/* spacetree-dem: see timestep_contact_history.h */

#include "timestep_contact_history.h"

#include <algorithm>

#include "error.h"
#include "force.h"
#include "neigh_list.h"
#include "pair_gran.h"
#include "update.h"

using namespace LAMMPS_NS;

void TimestepContactHistory::save()
{
  step_ = update->ntimestep;
  inum_ = -1;
  Pair *pair = force->pair;
  PairGran *pg = dynamic_cast<PairGran*>(pair);
  if (!pg || !pair->list || !pair->listgranhistory) return;   // a model without history
  NeighList *gl = pair->list, *hl = pair->listgranhistory;
  const int dnum = pg->dnum();
  flags_.clear();
  values_.clear();
  for (int ii = 0; ii < gl->inum; ii++) {
    const int i = gl->ilist[ii];
    const int n = gl->numneigh[i];
    flags_.insert(flags_.end(),hl->firstneigh[i],hl->firstneigh[i] + n);
    values_.insert(values_.end(),hl->firstdouble[i],hl->firstdouble[i] + dnum*n);
  }
  inum_ = gl->inum;
}

void TimestepContactHistory::restore()
{
  Pair *pair = force->pair;
  PairGran *pg = dynamic_cast<PairGran*>(pair);
  if (!pg || !pair->list || !pair->listgranhistory) return;
  if (step_ != update->ntimestep || inum_ != pair->list->inum)
    error->one(FLERR,"Fix adapt/timestep rollback: contact-history snapshot does not match the list");
  NeighList *gl = pair->list, *hl = pair->listgranhistory;
  const int dnum = pg->dnum();
  size_t nf = 0, nv = 0;
  for (int ii = 0; ii < gl->inum; ii++) {
    const int i = gl->ilist[ii];
    const int n = gl->numneigh[i];
    std::copy(flags_.begin() + nf,flags_.begin() + nf + n,hl->firstneigh[i]);
    std::copy(values_.begin() + nv,values_.begin() + nv + dnum*n,hl->firstdouble[i]);
    nf += n;
    nv += dnum*n;
  }
}
