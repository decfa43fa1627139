# Issue 6, MPI: spacetree sphere runs agree across rank counts (1 vs 2 vs 4 ranks: particle count
# exact, thermo to 1e-8) and continue from write_restart / read_restart (same or another rank
# count) as the uninterrupted run does.
# Driver: check_ranks.py (uses compare_runs.py's runner and thermo comparison); decks: in.settle,
# in.restart.  Run: ctest --test-dir build -R 'liggghts\.(ranks|restart)'
set(_ranks_driver "${CMAKE_CURRENT_SOURCE_DIR}/check_ranks.py")

# ranks_test(<driver test name> <timeout s> <ranks used at most>)
function(ranks_test driver_name timeout nprocs)
  string(REPLACE ":" "." ctest_name "liggghts.${driver_name}")
  string(REPLACE ":" "_" work "${driver_name}")
  lg_driver_test("${ctest_name}" "${_ranks_driver}" "${driver_name}" "${work}" ${timeout} ${nprocs}
                 MPI_FLAGS PYTHON_AND_TIMEOUT)
endfunction()

foreach(case settle wide)
  ranks_test("ranks:${case}:2" 120 2)
  ranks_test("ranks:${case}:4" 120 4)
endforeach()
ranks_test("restart:1" 120 1)
ranks_test("restart:2" 120 2)
ranks_test("restart:2:1" 120 2)   # written on 2 ranks, continued on 1
