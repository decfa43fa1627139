/* spacetree-dem: the contact search of pair_style trimesh over the candidate pairs of one
   compute() (neighbour-list pairs that passed the bounding-sphere precheck, in neighbour-list
   order, each in the pair style's canonical body order). With 1 thread the pairs are searched
   one after the other on the calling thread (the serial path); otherwise they are checked by the
   core engine's candidate sweep (parallel/TaskParallelPairChecks::runCandidates: consecutive
   candidates gathered into tasks of whole pairs on a TBB arena, one join per compute). Each
   candidate's ContactPoints are written to its own slot by the one task that checks it, so the
   pair style applies forces in list order, candidate by candidate, as on the serial path:
   forces, torques and trajectories are bit-identical for any thread count. Not
   LIGGGHTS-specific, but kept next to the only adapter that uses it. */

#ifndef LMP_TRIMESH_PARALLEL_CONTACTS_H
#define LMP_TRIMESH_PARALLEL_CONTACTS_H

#include <cstddef>
#include <memory>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/RigidShape.h"
#include "trimesh_type_template.h"

namespace LAMMPS_NS {

// One candidate pair: local atom indices (a first in the canonical body order), shapes, poses.
struct TrimeshCandidatePair {
  int a, b;
  const spacetree::geometry::RigidShape *shape_a, *shape_b;
  spacetree::contact::Pose pose_a, pose_b;
};

// Atoms i and j (templates ti, tj; IDs, positions and orientations w x y z of the atoms) as a
// candidate pair in the canonical body order, the same on every rank (with newton off a pair
// across two ranks is computed on both): the body with more triangles first - the core searches
// in the first body's frame and transforms only the second's triangles, so a big obstacle goes
// first (pair time of the hopper short case -9 %, median of 3) - ties broken by the smaller ID.
TrimeshCandidatePair canonical_candidate_pair(int i, int j, const TrimeshTypeTemplate &ti,
                                              const TrimeshTypeTemplate &tj, const int *tag,
                                              double **x, double **quat);

class TrimeshParallelContacts {
 public:
  // threads: 1 = serial on the calling thread, 0 = TBB's default, N > 1 = an arena of N
  // threads (the TBB thread limit is raised to N if N exceeds the cores). Throws
  // std::invalid_argument for threads < 0.
  TrimeshParallelContacts(const spacetree::contact::MeshContactOptions &options, int threads);
  ~TrimeshParallelContacts();

  // Searches every pair; afterwards contacts(k) are the contacts of pairs[k]. `stats` gets the
  // search counters of this call added (integers: the same for any thread count).
  void search(const std::vector<TrimeshCandidatePair> &pairs,
              spacetree::contact::MeshContactStatistics &stats);
  const std::vector<spacetree::contact::ContactPoint> &contacts(std::size_t k) const {
    return found_[k];
  }
  // Threads that search (1 on the serial path) and tasks spawned by the last search.
  int threads() const;
  // TBB's default concurrency for this process (the cores its affinity mask allows)
  static int defaultThreads();
  std::size_t tasks() const;

 private:
  struct Engine;
  std::unique_ptr<spacetree::contact::MeshContactFinder> serial_;  // threads == 1
  std::unique_ptr<Engine> engine_;                                 // threads != 1
  std::vector<std::vector<spacetree::contact::ContactPoint>> found_;
};

}

#endif
