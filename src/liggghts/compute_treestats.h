/* spacetree-dem: statistics of the spacetree and its adaptive grid, as a global vector
   readable from thermo output (c_ID[i]); see docs/compute_treestats.md for the layout.

     compute ID group treestats

   Values describe the last neighbour-list build, summed over the MPI ranks (each rank's grid
   covers its owned + ghost particles); the deepest level and the update time are maxima. */

#ifdef COMPUTE_CLASS

ComputeStyle(treestats,ComputeTreestats)

#else

#ifndef LMP_COMPUTE_TREESTATS_H
#define LMP_COMPUTE_TREESTATS_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeTreestats : public Compute {
 public:
  // c_ID[1..kSummary] summary values, then kPerLevel values per level 0..kLevels-1
  static const int kSummary = 11;
  static const int kPerLevel = 4;
  static const int kLevels = 13;

  ComputeTreestats(class LAMMPS *, int &iarg, int, char **);
  ~ComputeTreestats();
  void init();
  void compute_vector();
};

}

#endif
#endif
