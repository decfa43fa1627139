/* spacetree-dem: surfaces of all triangulated rigid particles (fix trimesh/template) of the
   group, one legacy-VTK polydata file per frame, written by rank 0 without a VTK library.

     dump ID group trimesh/vtk N file      (file with '*' = one file per frame, step number)

   Points: every particle's template vertices placed with its pose (x + q * v_body); polygons:
   its triangles. Cell data: atom id, atom type. Particles are written in atom-id order, so
   the file does not depend on the number of ranks. */

#ifdef DUMP_CLASS

DumpStyle(trimesh/vtk,DumpTrimeshVtk)

#else

#ifndef LMP_DUMP_TRIMESH_VTK_H
#define LMP_DUMP_TRIMESH_VTK_H

#include "dump.h"

namespace LAMMPS_NS {

class DumpTrimeshVtk : public Dump {
 public:
  DumpTrimeshVtk(class LAMMPS *, int, char **);
  void write();

 protected:
  void init_style();
  void write_header(bigint) {}
  void pack(int *) {}
  void write_data(int, double *) {}

 private:
  class FixTrimeshTemplate *templ;
};

}

#endif
#endif
