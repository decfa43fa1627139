/* spacetree-dem: see timestep_list_margin.h */

#include "timestep_list_margin.h"

#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "atom.h"
#include "neighbor.h"

using namespace LAMMPS_NS;

/* A rebuild happens after initial_integrate, so the positions at the end of that step are the
   ones the list was built from. */

void TimestepListMargin::track_build()
{
  if (neighbor->lastcall == build_step_) return;
  build_step_ = neighbor->lastcall;
  const int nlocal = atom->nlocal;
  x_build_.resize(3*nlocal);
  for (int i = 0; i < nlocal; i++)
    for (int k = 0; k < 3; k++) x_build_[3*i+k] = atom->x[i][k];
}

double TimestepListMargin::margin() const
{
  const int nlocal = atom->nlocal;
  double dmax_local = 0.0, dmax;
  if (int(x_build_.size()) != 3*nlocal) dmax_local = 0.5*neighbor->skin;   // atoms came or went
  else
    for (int i = 0; i < nlocal; i++) {
      const double dx = atom->x[i][0]-x_build_[3*i], dy = atom->x[i][1]-x_build_[3*i+1],
                   dz = atom->x[i][2]-x_build_[3*i+2];
      dmax_local = std::max(dmax_local,dx*dx + dy*dy + dz*dz);
    }
  if (int(x_build_.size()) == 3*nlocal) dmax_local = std::sqrt(dmax_local);
  MPI_Allreduce(&dmax_local,&dmax,1,MPI_DOUBLE,MPI_MAX,world);
  return std::max(neighbor->skin - 2.0*dmax,1e-3*neighbor->skin);
}
