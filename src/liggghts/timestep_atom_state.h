/* spacetree-dem: the owned atoms' state at the start of a step, for a rollback of
   fix adapt/timestep: x, v, omega, f, torque (what initial_integrate reads) and the image flags,
   one record per atom kept by atom ID, so that a step that re-neighboured (atoms sorted, or moved
   to another rank) can still be undone. Per-atom values of other sources (TimestepAtomValues,
   e.g. a primitive wall's tangential history) travel in the same records. */

#ifndef LMP_TIMESTEP_ATOM_STATE_H
#define LMP_TIMESTEP_ATOM_STATE_H

#include <vector>

#include "dynamics/TimestepStateSource.h"
#include "lmptype.h"
#include "pointers.h"

namespace LAMMPS_NS {

// Values per owned atom that a rollback restores with the atom: packed into its record, they
// reach the atom wherever the undone step took it.
class TimestepAtomValues {
 public:
  virtual ~TimestepAtomValues() {}
  virtual int count() const = 0;                     // values per atom
  virtual void pack(int i, double *values) const = 0;   // of owned atom i
  virtual void unpack(int i, const double *values) = 0;
};

class TimestepAtomState : public spacetree::TimestepStateSource, protected Pointers {
 public:
  explicit TimestepAtomState(class LAMMPS *lmp) : Pointers(lmp) {}

  void clear_values() { values_.clear(); }
  void add_values(TimestepAtomValues *v) { values_.push_back(v); }   // not owned
  bigint saved_step() const { return saved_step_; }

  Moment moment() const { return Moment::StepStart; }
  void save();
  // False when atoms were added or deleted since save(), or a re-neighboured step is to be undone
  // without an atom map. Collective: sends the records of atoms that changed rank to every rank.
  bool restorable();
  // The planned records into the atoms, then forward_comm (ghosts take the restored positions).
  void restore();

 private:
  int record_size() const;
  bigint saved_step_ = -1;
  int nsaved_ = 0;
  std::vector<double> records_;           // record_size() doubles per atom saved
  std::vector<double> received_;          // records of atoms that changed rank (restorable)
  std::vector<const double *> plan_;      // the record each local atom takes (restorable)
  std::vector<TimestepAtomValues *> values_;
};

}

#endif
