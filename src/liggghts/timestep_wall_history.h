/* spacetree-dem: the tangential history of a primitive wall (fix wall/gran ... primitive with a
   history model), restored by a rollback of fix adapt/timestep with the atoms. The wall keeps it
   in a per-atom fix property/atom named history_<wall-ID> (created in FixWallGran::post_create);
   its values travel in the atoms' records (TimestepAtomState), so they are found by atom ID after
   a re-neighbouring step. Mesh walls keep theirs in per-atom contact lists that are not restored:
   collect() warns about them. */

#ifndef LMP_TIMESTEP_WALL_HISTORY_H
#define LMP_TIMESTEP_WALL_HISTORY_H

#include <memory>
#include <vector>

#include "timestep_atom_state.h"

namespace LAMMPS_NS {

class TimestepWallHistory : public TimestepAtomValues {
 public:
  // One per primitive wall with history in the fix list, in its order.
  static std::vector<std::unique_ptr<TimestepWallHistory>> collect(class LAMMPS *lmp);

  explicit TimestepWallHistory(class FixPropertyAtom *history);
  int count() const { return nvalues_; }
  void pack(int i, double *values) const;
  void unpack(int i, const double *values);

 private:
  class FixPropertyAtom *history_;
  int nvalues_;
};

}

#endif
