/* spacetree-dem: `compute ID group neigh/local` lists the pairs of the pair
   style's granular neighbour list (atom IDs of both atoms) as a local array,
   e.g. to compare `neighbor spacetree` with `neighbor bin` pair by pair:
     compute nl all neigh/local
     dump    d  all local 100 pairs.dump c_nl[1] c_nl[2]
   A pair is listed when the group contains either atom. On several ranks an
   owned/ghost pair appears on both ranks. */

#ifdef COMPUTE_CLASS

ComputeStyle(neigh/local,ComputeNeighLocal)

#else

#ifndef LMP_COMPUTE_NEIGH_LOCAL_H
#define LMP_COMPUTE_NEIGH_LOCAL_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeNeighLocal : public Compute {
 public:
  ComputeNeighLocal(class LAMMPS *, int &iarg, int, char **);
  ~ComputeNeighLocal();
  void init();
  void init_list(int, class NeighList *);
  void compute_local();
  double memory_usage();

 private:
  int count_pairs(bool store);

  class NeighList *list;
  int nmax;
  double **array;
};

}

#endif
#endif
