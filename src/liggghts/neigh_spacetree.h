/* spacetree-dem: state behind `neighbor <skin> spacetree [keyword value ...]`.
   Owned by LAMMPS_NS::Neighbor (pointer `spacetree`, see liggghts_patch/). The search
   itself (grid update, tree, sweep, refinement) is the LIGGGHTS-independent core object
   spacetree::NeighbourSearch (src/core/tree); fix spacetree chooses its grid. */

#ifndef LMP_NEIGH_SPACETREE_H
#define LMP_NEIGH_SPACETREE_H

#include <memory>
#include <vector>

#include "multilevel_halo.h"
#include "tree/NeighbourSearch.h"

namespace LAMMPS_NS {

class NeighSpacetree {
 public:
  spacetree::NeighbourSearch search;    // eps = skin/2, maxlevel, the optional adaptive grid
  bool bins_for_meshes = false;         // a mesh wall reads Neighbor's bins
  std::unique_ptr<MultilevelHalo> halo; // per-size ghost rule (keywords halo, halo_ratio)

  // Scratch of the list build, kept between builds to avoid reallocation.
  std::vector<double> contact_radius;   // radius * contact_distance_factor
  spacetree::NeighbourSearch::ListedPairs pairs;  // second marked (~j): touching

  // Mesh size of the finest cell that hosts a particle at the last build (0 before any); with
  // fix spacetree the tree is built on that grid's hosts, so it is the grid's finest such cell.
  double finest_cell() const { return search.finestCell(); }
};

}  // namespace LAMMPS_NS

#endif
