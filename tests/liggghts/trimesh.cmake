# Triangulated rigid particles (pair_style trimesh, fix trimesh/template, fix nve/trimesh,
# dump trimesh/vtk, compute trimesh/contacts). Driver: trimesh_check.py; decks: trimesh_*.in,
# inputs/hopper/. Run: ctest --test-dir build -R liggghts.trimesh
foreach(case collide floor edge insert ranks restart bad hopper)
  set(_np 1)
  if(case MATCHES "^(ranks|restart|hopper|insert)$")
    set(_np 2)
  endif()
  add_test(NAME liggghts.trimesh.${case}
           COMMAND "${Python3_EXECUTABLE}" "${CMAKE_CURRENT_SOURCE_DIR}/trimesh_check.py" ${case}
                   --exe "${LIGGGHTS_EXE}"
                   --mpiexec "${MPIEXEC_EXECUTABLE}"
                   "--mpiexec-flags=${SPACETREE_MPIEXEC_PREFLAGS}"
                   --workdir "${_workroot}/trimesh_${case}")
  set_tests_properties(liggghts.trimesh.${case} PROPERTIES
                       LABELS liggghts TIMEOUT 180 PROCESSORS ${_np})
endforeach()
