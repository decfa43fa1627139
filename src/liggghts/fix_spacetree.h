/* spacetree-dem: the persistent, dynamically adaptive grid behind `neighbor <skin> spacetree`
   (paper §5.1; core: src/core/tree/AdaptiveGrid).

     fix ID group spacetree grid regular|adaptive|reluctant [shock S] [threshold T]
                                 [maxlevel L] [padding P] [vtk N file]
     (after read_restart `grid` may be left out: it comes from the restart file)

   At every neighbour-list build the builder (neigh_spacetree.cpp) asks this fix to update the
   grid over the rank's owned + ghost particles (refine, coarsen, re-host) and builds the tree
   on the grid's cube and host levels. The lists stay exactly bin's for every grid type.
   vtk N file: every N steps each rank writes its leaf cells as legacy VTK; in `file` a '*' is
   replaced by the time step and a '%' by the rank (required on more than one rank).

   Restart: write_restart stores the options and every rank's grid state (gathered on proc 0,
   with the rank count and processor grid); a restated fix with the same ID takes the options
   it does not name from the file (named ones win, with a warning when they differ) and reuses
   the grids when the type, rank count, processor grid, skin and maxlevel match. */

#ifdef FIX_CLASS

FixStyle(spacetree,FixSpacetree)

#else

#ifndef LMP_FIX_SPACETREE_H
#define LMP_FIX_SPACETREE_H

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "fix.h"
#include "tree/AdaptiveGrid.h"

namespace LAMMPS_NS {

class FixSpacetree : public Fix {
 public:
  FixSpacetree(class LAMMPS *, int, char **);
  void pre_delete(bool unfixflag);
  int setmask();
  void init();
  void end_of_step();
  void write_restart(FILE *);
  void restart(char *);

  // Called by the spacetree list builder: update the grid over x[0..nall) (v may be NULL)
  // and build `tree` on it. Throws what the core throws (bad positions / radii).
  void build_tree(spacetree::Spacetree &tree, const double (*x)[3], const double (*v)[3],
                  const double *radius, int nall, int nlocal);

  // Called after the sweep on that tree with the listed pairs (j may carry the builder's
  // touching mark ~j): the reluctant grid refines for the approaching ones (paper: refinement
  // triggered by the traversal's comparisons; the particles drop at the next build).
  void after_sweep(const double (*x)[3], const double (*v)[3], const double *radius, int nall,
                   const std::vector<int> &pair_i, const std::vector<int> &pair_j);

  const spacetree::AdaptiveGrid *grid() const { return grid_.get(); }
  double last_update_seconds() const { return update_seconds; }
  int max_level() const { return options.maxLevel; }

 private:
  void write_vtk();
  void check_options();
  // Restart: this rank's stored grid under `wanted`, or none.
  void apply_restored_grid(const spacetree::AdaptiveGridOptions &wanted);

  // Which keywords the command named (the others may come from a restart file).
  enum Keyword { kGrid, kShock, kThreshold, kMaxlevel, kPadding, kVtk, kKeywords };
  bool given[kKeywords];

  spacetree::AdaptiveGridOptions options;
  std::unique_ptr<spacetree::AdaptiveGrid> grid_;
  double update_seconds;
  int vtk_every;
  std::string vtk_file;
  std::vector<int> pair_second;  // scratch: pair_j without the touching mark
  // This rank's grid state from the restart file, applied (or dropped) at the next init().
  bool restart_read;            // restart() ran: options not named came from the file
  bool restored_grid_pending;   // the file's grids are to be reused (all ranks agree)
  std::vector<std::int64_t> restored_grid;
};

}

#endif
#endif
