# fix adapt/timestep with triangulated particles (pair_style trimesh): veto and contact ceiling on
# the surface gap, halo penetration, rollback of the rigid-body state, a short grain pour.
# Driver: check_timestep_trimesh.py; decks: in.bodies here, inputs/pour/in.pour.
# Run: ctest --test-dir build -R liggghts.timestep_trimesh
set(_tt_driver "${CMAKE_CURRENT_LIST_DIR}/check_timestep_trimesh.py")
foreach(case collide veto rollback)
  lg_driver_test(liggghts.timestep_trimesh.${case}.1 "${_tt_driver}" ${case} timestep_trimesh_${case}_1 180 1 MPI_FLAGS)
  lg_driver_test(liggghts.timestep_trimesh.${case}.2 "${_tt_driver}" ${case}:2 timestep_trimesh_${case}_2 240 2 MPI_FLAGS)
endforeach()
lg_driver_test(liggghts.timestep_trimesh.pour "${_tt_driver}" pour timestep_trimesh_pour 300 1 MPI_FLAGS)
lg_driver_test(liggghts.timestep_trimesh.badinput "${_tt_driver}" badinput timestep_trimesh_badinput 60 1 MPI_FLAGS)
