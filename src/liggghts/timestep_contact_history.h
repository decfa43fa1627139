/* spacetree-dem: the particle-particle contact history of a granular sphere pair style
   (pair_style gran ... with history), restored by a rollback of fix adapt/timestep. It lives in
   the pages of the pair's history list; the copy is taken just before the pair forces (after any
   re-neighbouring, which refills the pages from the per-atom copy that fix contacthistory took at
   the start of the step), so it follows the list's order until the rollback. */

#ifndef LMP_TIMESTEP_CONTACT_HISTORY_H
#define LMP_TIMESTEP_CONTACT_HISTORY_H

#include <vector>

#include "dynamics/TimestepStateSource.h"
#include "lmptype.h"
#include "pointers.h"

namespace LAMMPS_NS {

class TimestepContactHistory : public spacetree::TimestepStateSource, protected Pointers {
 public:
  explicit TimestepContactHistory(class LAMMPS *lmp) : Pointers(lmp) {}

  Moment moment() const { return Moment::BeforeForces; }
  void save();
  void restore();   // error when the copy is not of this step's list

 private:
  std::vector<int> flags_;       // contact flags, per neighbour of each list atom in list order
  std::vector<double> values_;   // dnum values per neighbour
  int inum_ = -1;                // list atoms at save (-1: nothing saved)
  bigint step_ = -1;
};

}

#endif
