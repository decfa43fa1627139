/* spacetree-dem: state behind `neighbor <skin> spacetree [keyword value ...]`.
   Owned by LAMMPS_NS::Neighbor (pointer `spacetree`, see liggghts_patch/). The
   search itself lives in the LIGGGHTS-independent core (src/core/tree). */

#ifndef LMP_NEIGH_SPACETREE_H
#define LMP_NEIGH_SPACETREE_H

#include <memory>
#include <vector>

#include "multilevel_halo.h"
#include "tree/Spacetree.h"

namespace LAMMPS_NS {

class FixSpacetree;

class NeighSpacetree {
 public:
  spacetree::SpacetreeOptions options;  // epsilon is set from the skin at each build
  spacetree::Spacetree tree;
  bool bins_for_meshes = false;         // a mesh wall reads Neighbor's bins
  FixSpacetree *grid_fix = nullptr;     // fix spacetree: persistent adaptive grid (else regular)
  std::unique_ptr<MultilevelHalo> halo; // per-size ghost rule (keywords halo, halo_ratio)

  // Scratch of the list build, kept between builds to avoid reallocation.
  std::vector<double> contact_radius;   // radius * contact_distance_factor
  std::vector<int> first;               // CSR offsets of each owned atom's neighbours
  std::vector<int> fill;
  std::vector<int> neighbours;
  std::vector<int> pair_i, pair_j;

  // Mesh size of the finest cell that hosts a particle at the last build (0 before any); with
  // fix spacetree the tree is built on that grid's hosts, so it is the grid's finest such cell.
  double finest_cell() const { return tree.finestPopulatedMeshSize(); }
};

}  // namespace LAMMPS_NS

#endif
