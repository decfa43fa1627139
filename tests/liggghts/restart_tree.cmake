# fix spacetree across write_restart / read_restart (issue 6): options and per-rank grid state.
# N steps + write_restart, then read_restart + N steps in a new process, equal the 2N steps of one
# process (grid counters of compute treestats exactly, particle thermo to 1e-8), for grid adaptive
# and reluctant, the fix restated with or without its options; a conflicting option warns; another
# rank count warns and starts from the start-off grid.
# Driver: check_restart_tree.py; deck in.restart_tree.  Run: ctest --test-dir build -R liggghts.restart_tree
set(_restart_tree_driver "${CMAKE_CURRENT_SOURCE_DIR}/check_restart_tree.py")
foreach(ranks 1 2 2:1)
  string(REGEX REPLACE ":.*" "" _np "${ranks}")
  string(REPLACE ":" "." _name "${ranks}")
  string(REPLACE ":" "_" _work "${ranks}")
  lg_driver_test("liggghts.restart_tree.${_name}" "${_restart_tree_driver}" "restart:${ranks}"
                 "restart_tree_${_work}" 150 ${_np} MPI_FLAGS PYTHON_AND_TIMEOUT)
endforeach()
