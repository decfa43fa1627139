# pair_style trimesh ... threads N: bit-identical trajectories for 1, 2, 4 threads (1 rank) and
# 1, 2 threads (2 ranks); bad threads values. Driver: check_threads.py, deck: threads_hopper.in.
# Run: ctest --test-dir build -R liggghts.threads
foreach(case threads ranks bad)
  set(_np 1)
  if(case STREQUAL "ranks")
    set(_np 2)
  endif()
  add_test(NAME liggghts.threads.${case}
           COMMAND "${Python3_EXECUTABLE}" "${CMAKE_CURRENT_SOURCE_DIR}/check_threads.py" ${case}
                   --exe "${LIGGGHTS_EXE}"
                   --mpiexec "${MPIEXEC_EXECUTABLE}"
                   "--mpiexec-flags=${SPACETREE_MPIEXEC_PREFLAGS}"
                   --workdir "${_workroot}/threads_${case}")
  set_tests_properties(liggghts.threads.${case} PROPERTIES
                       LABELS liggghts TIMEOUT 180 PROCESSORS ${_np})
endforeach()
