/* spacetree-dem: ask for an occasional granular neighbour list. Neighbor::init turns such a
   request of a fix or compute into a copy of the pair style's granular list (whichever
   neighbour style built it); the caller refreshes it with neighbor->build_one(list->index). */

#ifndef LMP_GRANULAR_LIST_COPY_H
#define LMP_GRANULAR_LIST_COPY_H

#include "neigh_request.h"
#include "neighbor.h"

namespace LAMMPS_NS {

enum class GranularListUser { Fix, Compute };

inline void request_granular_list_copy(Neighbor *neighbor, void *requestor, GranularListUser user)
{
  const int irequest = neighbor->request(requestor);
  NeighRequest *rq = neighbor->requests[irequest];
  rq->pair = 0;
  rq->fix = (user == GranularListUser::Fix);
  rq->compute = (user == GranularListUser::Compute);
  rq->half = 0;
  rq->gran = 1;
  rq->occasional = 1;
}

}

#endif
