# Triangulated rigid particles (pair_style trimesh, fix trimesh/template, fix nve/trimesh,
# dump trimesh/vtk, compute trimesh/contacts). Driver: trimesh_check.py; decks: trimesh_*.in,
# inputs/hopper/. Run: ctest --test-dir build -R liggghts.trimesh
foreach(case collide floor edge insert pose big_obstacle ranks restart bad hopper)
  set(_np 1)
  if(case MATCHES "^(ranks|restart|hopper|insert|pose|big_obstacle)$")
    set(_np 2)
  endif()
  lg_driver_test(liggghts.trimesh.${case} "${CMAKE_CURRENT_SOURCE_DIR}/trimesh_check.py" ${case}
                 trimesh_${case} 180 ${_np} MPI_FLAGS)
endforeach()
