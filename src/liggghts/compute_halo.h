/* spacetree-dem: the ghost shell per size class, as a global vector readable from thermo
   output (c_ID[i]); see docs/compute_halo.md for the layout.

     compute ID group halo

   Counts the owned and ghost atoms of the group on all ranks at the time of the compute (the
   ghosts of the last borders()), per size class (class 0 the largest radii, each next class
   radii a factor halo_ratio smaller, as `neighbor ... spacetree halo levels` exchanges them).
   Works with any neighbor style: with `bin` or `halo single` it shows the stock shell. */

#ifdef COMPUTE_CLASS

ComputeStyle(halo,ComputeHalo)

#else

#ifndef LMP_COMPUTE_HALO_H
#define LMP_COMPUTE_HALO_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeHalo : public Compute {
 public:
  // c_ID[1..kSummary] summary values, then kPerClass values per class 0..kClasses-1
  static const int kSummary = 6;
  static const int kPerClass = 5;
  static const int kClasses = 16;

  ComputeHalo(class LAMMPS *, int &iarg, int, char **);
  ~ComputeHalo();
  void init() {}
  void compute_vector();
};

}

#endif
#endif
