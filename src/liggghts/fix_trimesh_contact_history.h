/* spacetree-dem: the per-contact history of pair_style trimesh (e.g. the tangential spring of
   `tangential history`), stored per particle pair on the owned atoms so that it follows them
   across ranks and into restart files.

   Each owned atom keeps a list of partner entries [partner tag, n, n records]; a record is one
   contact point of the pair (spacetree::contact_model::ContactHistoryMatcher: anchor point and
   normal in the frame of the pair's first body, then the sub-models' history). With newton off
   a pair is computed on every rank owning one of its atoms, in the same body order everywhere,
   so each owned atom of a pair carries the same copy. In every force computation the pair style
   reads the previous records from an owned atom (lookup) and writes the new ones for both owned
   atoms (store); finish() makes them current: the entries of pairs that were not in contact are
   gone (opened contacts lose their history).

   Created by pair_style trimesh as fix "trimesh_contact_history" when its contact model keeps
   history (never in a deck). Per-atom data: grow/copy (sorting), exchange, restart (a restart
   file written with it restores it when the pair style is given again). As a TimestepStateSource
   it is part of fix adapt/timestep's rollback snapshot (saved by atom ID at the step start).
   Global vector (thermo f_trimesh_contact_history[1..2]): [1] contact points with history, each
   pair counted once; [2] sum of the absolute history values of those points (the tangential
   springs' |xi_x| + |xi_y| + |xi_z|, m). */

#ifdef FIX_CLASS

FixStyle(trimesh/contact_history,FixTrimeshContactHistory)

#else

#ifndef LMP_FIX_TRIMESH_CONTACT_HISTORY_H
#define LMP_FIX_TRIMESH_CONTACT_HISTORY_H

#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "dynamics/TimestepStateSource.h"
#include "fix.h"

namespace LAMMPS_NS {

class FixTrimeshContactHistory : public Fix, public spacetree::TimestepStateSource {
 public:
  FixTrimeshContactHistory(class LAMMPS *, int, char **);
  ~FixTrimeshContactHistory();
  int setmask() { return 0; }

  // Doubles per record (the matcher's recordSize); set by the pair style at init. A change
  // (another contact model) clears every history.
  void set_record_size(int size);
  int record_size() const { return record_size_; }

  // The current records of owned atom i with partner `tag`: pointer and count (NULL, 0 if none).
  const double *lookup(int i, int tag, int &count) const;
  // Starts a force computation: the next lists of the owned atoms are emptied.
  void begin();
  // The new records of owned atom i with partner `tag` (count records).
  void store(int i, int tag, const double *records, int count);
  // Ends it: the next lists become current.
  void finish();

  void grow_arrays(int);
  void copy_arrays(int, int, int);
  int pack_exchange(int, double *);
  int unpack_exchange(int, double *);
  int pack_restart(int, double *);
  void unpack_restart(int, int);
  int size_restart(int);
  int maxsize_restart();
  double memory_usage();
  double compute_vector(int);

  // TimestepStateSource
  Moment moment() const { return Moment::StepStart; }
  void save();
  bool restorable();
  void restore();

 private:
  void note_size(int i);

  int record_size_;
  std::vector<std::vector<double> > current_, next_;   // per atom: entries as above
  int largest_;                                        // largest list on this rank (doubles)
  std::map<int, std::vector<double> > saved_;          // rollback copy, by atom ID
  std::vector<double> received_;                       // lists of atoms that changed rank
  std::vector<std::pair<const double *, std::size_t> > plan_;   // restore(): list of atom i
};

}

#endif
#endif
