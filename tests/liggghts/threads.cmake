# pair_style trimesh ... threads N: bit-identical trajectories for 1, 2, 4 threads (1 rank) and
# 1, 2 threads (2 ranks); bad threads values. Driver: check_threads.py, deck: threads_hopper.in.
# Run: ctest --test-dir build -R liggghts.threads
foreach(case threads ranks bad)
  set(_np 1)
  if(case STREQUAL "ranks")
    set(_np 2)
  endif()
  lg_driver_test(liggghts.threads.${case} "${CMAKE_CURRENT_SOURCE_DIR}/check_threads.py" ${case}
                 threads_${case} 180 ${_np} MPI_FLAGS)
endforeach()
