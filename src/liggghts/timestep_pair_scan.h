/* spacetree-dem: what fix adapt/timestep needs to know about the contacts before it chooses the
   next step: over the group's pairs of the granular neighbour list and its particles against the
   walls (fix wall/gran, primitive and mesh), the deepest overlap, the number of contacts, whether
   a pair is in contact or about to touch (the contact ceiling applies), the largest contact speed
   (vimpact), and the veto over the approaching pairs. The decisions themselves are the core's
   (src/core/dynamics). Pairs of triangulated particles (pair_style trimesh) are judged by their
   surface distance instead (TimestepTrimeshScan): their overlap is the halo penetration. */

#ifndef LMP_TIMESTEP_PAIR_SCAN_H
#define LMP_TIMESTEP_PAIR_SCAN_H

#include <memory>
#include <vector>

#include "dynamics/AdaptiveTimestep.h"
#include "dynamics/TimestepVeto.h"
#include "pointers.h"
#include "timestep_trimesh_scan.h"

namespace LAMMPS_NS {

class TimestepPairScan : protected Pointers {
 public:
  struct Result {
    double maxOverlap;     // deepest overlap (length), all ranks
    double contacts;       // pairs and wall contacts in overlap, all ranks
    double criticalPairs;  // pairs the veto cut the step for, all ranks
    bool contactSoon;      // some pair overlaps or may touch within the tested step
    double contactSpeed;   // largest contact speed (vimpact), or approach speed of a pair about to touch
    double stableStep;     // stability ceiling: smallest stable step of the pairs in contact or about to touch (0: none)
  };

  // owner: the fix whose group is scanned and whose forward communication carries the
  // accelerations (and, for triangulated particles, the end-of-step velocities) to the ghosts
  // (its pack_comm / unpack_comm call the ones below; at most 6 values per atom).
  TimestepPairScan(class LAMMPS *lmp, class Fix *owner) : Pointers(lmp), owner_(owner) {}

  // The pairs of the list are triangulated particles of `pair` (NULL: spheres): judged by their
  // surface distance, the veto keeping their halo penetration within allowedPenetration.
  void use_trimesh(class PairTrimesh *pair, double allowedPenetration, double safety);
  const TimestepTrimeshScan *trimesh() const { return trimesh_.get(); }

  // list: the fix's copy of the granular list (NULL: walls only); veto: NULL when off. dtTest is
  // the step the veto and "about to touch" are tested against (the largest creep can give).
  // Collective.
  Result scan(class NeighList *list, const spacetree::TimestepPolicy &policy, double dtTest,
              spacetree::TimestepVeto *veto);

  int pack_comm(int n, int *list, double *buf) const;
  void unpack_comm(int n, int first, const double *buf);

 private:
  // this rank's part: max overlap, contacts, critical pairs, contact soon, largest contact speed,
  // 1 / the smallest stable step (stability ceiling)
  enum { OVERLAP, CONTACTS, CRITICAL, SOON, SPEED, INV_STABLE, NTALLY };
  void share_accelerations();
  void share_velocities();
  void scan_list(class NeighList *list);
  void scan_trimesh(class NeighList *list);
  void scan_primitive_wall(class FixWallGran *wall);
  void scan_mesh_wall(class FixWallGran *wall);
  // particle i against a wall at its closest point (delta: centre to that point; gap < 0:
  // overlap), the wall treated as a sphere of radius 0 at rest; a moving wall only reports overlaps
  void wall_contact(int i, double gap, const double *delta, bool moving);

  class Fix *owner_;
  // settings of the scan in progress
  const spacetree::TimestepPolicy *policy_ = nullptr;
  spacetree::TimestepVeto *veto_ = nullptr;
  double dt_test_ = 0.0;
  bool speeds_ = false;
  double tally_[NTALLY];
  std::vector<double> accel_;   // f/m of owned and ghost atoms (vimpact: relative normal acceleration)
  std::vector<double> mesh_gap_, mesh_delta_;
  std::unique_ptr<TimestepTrimeshScan> trimesh_;
  enum class Shared { Accelerations, Velocities } sharing_ = Shared::Accelerations;   // of pack_comm
  double allowed_penetration_ = 0.0, safety_ = 1.0;
};

}

#endif
