/* spacetree-dem: how much of the neighbour skin fix adapt/timestep may still spend: the owned
   atoms' positions at the last list build (Neighbor::xhold is not public) and, from them,
   skin - 2 * (largest displacement since), the relative approach a pair outside the list needs
   before it could touch. */

#ifndef LMP_TIMESTEP_LIST_MARGIN_H
#define LMP_TIMESTEP_LIST_MARGIN_H

#include <vector>

#include "lmptype.h"
#include "pointers.h"

namespace LAMMPS_NS {

class TimestepListMargin : protected Pointers {
 public:
  explicit TimestepListMargin(class LAMMPS *lmp) : Pointers(lmp) {}
  // At the end of a step: takes the positions if the lists were built in it.
  void track_build();
  // skin - 2 * largest displacement (all ranks), at least skin/1000. Collective.
  double margin() const;

 private:
  std::vector<double> x_build_;
  bigint build_step_ = -1;
};

}

#endif
