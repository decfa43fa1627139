/* spacetree-dem: the persistent, dynamically adaptive grid behind `neighbor <skin> spacetree`
   (paper §5.1; core: src/core/tree/AdaptiveGrid).

     fix ID group spacetree grid regular|adaptive|reluctant [shock S] [threshold T]
                                 [maxlevel L] [padding P] [vtk N file]
     (after read_restart `grid` may be left out: it comes from the restart file)

   The fix chooses the grid of the neighbour search (spacetree::NeighbourSearch, owned by the
   `neighbor ... spacetree` builder), which updates it over the rank's owned + ghost particles
   at every list build (refine, coarsen, re-host) and builds the tree on the grid's cube and
   host levels. The lists stay exactly bin's for every grid type.
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
#include <string>
#include <vector>

#include "fix.h"
#include "tree/AdaptiveGridOptions.h"

namespace spacetree { class AdaptiveGrid; class NeighbourSearch; }

namespace LAMMPS_NS {

class FixSpacetree : public Fix {
 public:
  FixSpacetree(class LAMMPS *, int, char **);
  ~FixSpacetree();
  int setmask();
  void init();
  void end_of_step();
  void write_restart(FILE *);
  void restart(char *);


 private:
  // The neighbour search whose grid this fix chooses (init() checks that it exists).
  spacetree::NeighbourSearch &search();
  // This fix's grid: the search's once init() gave it one, else none.
  const spacetree::AdaptiveGrid *grid();
  void write_vtk();
  void check_options();
  // Restart: this rank's stored grid for the search, or (all ranks agree) none.
  void apply_restored_grid();

  // Which keywords the command named (the others may come from a restart file).
  enum Keyword { kGrid, kShock, kThreshold, kMaxlevel, kPadding, kVtk, kKeywords };
  bool given[kKeywords];

  spacetree::AdaptiveGridOptions options;  // halo and depth: the search's
  bool grid_given;              // init() gave the search this fix's grid
  int vtk_every;
  std::string vtk_file;
  // This rank's grid state from the restart file, applied (or dropped) at the next init().
  bool restart_read;            // restart() ran: options not named came from the file
  bool restored_grid_pending;   // the file's grids are to be reused (all ranks agree)
  std::vector<std::int64_t> restored_grid;
};

}

#endif
#endif
