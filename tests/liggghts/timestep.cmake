# fix adapt/timestep: closed-form two-sphere checks (tests/liggghts/timestep) and the hard-case
# suite (tests/liggghts/hardcases), all with `neighbor ... spacetree`. Included from CMakeLists.txt.
set(_ts_dir "${CMAKE_CURRENT_SOURCE_DIR}/timestep")
set(_hc_dir "${CMAKE_CURRENT_SOURCE_DIR}/hardcases")

# ts_test(<ctest name> <driver> <case> <ranks> <timeout s>)
function(ts_test name driver case nprocs timeout)
  string(REPLACE ":" "_" work "${name}")
  lg_driver_test("liggghts.${name}" "${driver}" "${case}" "${work}" ${timeout} ${nprocs})
endfunction()

foreach(case damped elastic rollback rollback_periodic rollback_tally rollback_history mesh_wall vimpact)
  ts_test("timestep.${case}.1" "${_ts_dir}/check_closed_form.py" "${case}" 1 120)
  ts_test("timestep.${case}.2" "${_ts_dir}/check_closed_form.py" "${case}:2" 2 120)
endforeach()
ts_test("timestep.control" "${_ts_dir}/check_closed_form.py" control 1 60)
ts_test("timestep.badinput" "${_ts_dir}/check_closed_form.py" badinput 1 60)

foreach(case impact100 impact100veto ratio1000 squeeze threebody stack stackrest)
  ts_test("hardcase.${case}" "${_hc_dir}/check_hardcases.py" "${case}" 1 180)
endforeach()
ts_test("hardcase.impact100.2" "${_hc_dir}/check_hardcases.py" "impact100:2" 2 180)
ts_test("hardcase.squeeze.2" "${_hc_dir}/check_hardcases.py" "squeeze:2" 2 180)
