# Hostile-user decks: each once ran on silently or crashed; each must now stop with an ERROR
# naming the problem (teardown: run cleanly). Driver: reliability/check_reliability.py.
# Run: ctest --test-dir build -R liggghts.reliability
foreach(case teardown fix_replace nan_mesh dented_limit adapt_twice creep hybrid_types grain_box error_one)
  lg_driver_test(liggghts.reliability.${case}
                 "${CMAKE_CURRENT_SOURCE_DIR}/reliability/check_reliability.py" ${case}
                 reliability_${case} 180 1)
endforeach()
