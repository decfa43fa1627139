# fix spacetree (regular / adaptive / reluctant grids) and compute treestats: pair sets equal
# bin's on the polydisperse decks and on a randomised moving gas (1 and 2 ranks), the paper's
# §7.1 two-sphere deck (comparisons, cells, leaf-cell VTK), an empty box filled by insertion
# (in.treestats_empty), bad input.
# Driver: check_adaptive_grid.py (reuses compare_runs.py); decks in.grid_pairs, in.bad_grid.
# Run:  ctest --test-dir build -R liggghts.grid

set(_grid_driver "${CMAKE_CURRENT_SOURCE_DIR}/check_adaptive_grid.py")

# grid_test(<test name for the driver> <timeout s> <number of MPI ranks used at most>)
function(grid_test driver_name timeout nprocs)
  string(REPLACE ":" "." ctest_name "liggghts.grid.${driver_name}")
  string(REPLACE ":" "_" work "grid_${driver_name}")
  lg_driver_test("${ctest_name}" "${_grid_driver}" "${driver_name}" "${work}" ${timeout} ${nprocs}
                 MPI_FLAGS PYTHON_AND_TIMEOUT)
endfunction()

foreach(case r10_cont_periodic r100_bi_periodic)
  grid_test("pairs:${case}:1" 120 1)
  grid_test("pairs:${case}:2" 150 2)
endforeach()
grid_test("moving:1" 150 1)
grid_test("moving:2" 180 2)
grid_test("paper71" 120 1)
grid_test("empty:1" 60 1)
grid_test("empty:2" 90 2)
foreach(bad gridtype gridmissing keyword novalue threshold maxlevel noneighbor treestats)
  grid_test("bad:${bad}" 60 1)
endforeach()
