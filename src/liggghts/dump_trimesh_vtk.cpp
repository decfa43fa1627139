/* spacetree-dem: legacy-VTK polydata of the surfaces of triangulated rigid particles. */

#include "dump_trimesh_vtk.h"

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <mpi.h>

#include "atom.h"
#include "error.h"
#include "fix_trimesh_state.h"
#include "fix_trimesh_template.h"
#include "update.h"

using namespace LAMMPS_NS;

namespace {
constexpr int kRecord = 9;   // tag, type, x[3], quat[4]
}

DumpTrimeshVtk::DumpTrimeshVtk(LAMMPS *lmp, int narg, char **arg) :
  Dump(lmp, narg, arg), templ(NULL)
{
  if (narg != 5) error->all(FLERR,"Illegal dump trimesh/vtk command: dump ID group trimesh/vtk N file");
  if (binary || compressed || multiproc)
    error->all(FLERR,"Dump trimesh/vtk writes one text file per frame from rank 0 "
                     "(no .bin, .gz or % in the file name)");
  if (!multifile)
    error->all(FLERR,"Dump trimesh/vtk needs a '*' in the file name (one VTK file per frame)");
}

void DumpTrimeshVtk::init_style()
{
  templ = FixTrimeshTemplate::find(lmp,"Dump trimesh/vtk");
  if (!templ) error->all(FLERR,"Dump trimesh/vtk requires fix trimesh/template");
}

void DumpTrimeshVtk::write()
{
  // gather the poses of the group's template particles on rank 0
  const int nlocal = atom->nlocal;
  double **quat = templ->state()->quat;
  std::vector<double> mine;
  for (int i = 0; i < nlocal; i++) {
    if (!(atom->mask[i] & groupbit) || !templ->type_template(atom->type[i])) continue;
    mine.push_back(atom->tag[i]);
    mine.push_back(atom->type[i]);
    for (int k = 0; k < 3; k++) mine.push_back(atom->x[i][k]);
    for (int k = 0; k < 4; k++) mine.push_back(quat[i][k]);
  }
  int nmine = static_cast<int>(mine.size());
  std::vector<int> counts(nprocs), displs(nprocs);
  MPI_Gather(&nmine,1,MPI_INT,counts.data(),1,MPI_INT,0,world);
  int total = 0;
  if (me == 0)
    for (int p = 0; p < nprocs; p++) { displs[p] = total; total += counts[p]; }
  std::vector<double> all(me == 0 ? std::max(total,1) : 1);
  MPI_Gatherv(mine.data(),nmine,MPI_DOUBLE,all.data(),counts.data(),displs.data(),MPI_DOUBLE,0,world);
  if (me != 0) return;

  const int n = total / kRecord;
  std::vector<int> order(n);
  for (int k = 0; k < n; k++) order[k] = k;
  std::sort(order.begin(),order.end(),[&](int a, int b) { return all[a*kRecord] < all[b*kRecord]; });

  std::string name(filename);
  name.replace(name.find('*'),1,std::to_string(update->ntimestep));
  FILE *out = fopen(name.c_str(),"w");
  if (!out) {
    std::string msg = "Dump trimesh/vtk cannot open file '" + name + "'";
    error->one(FLERR,msg.c_str());
  }

  long npoints = 0, ntris = 0;
  for (int k : order) {
    const TrimeshTypeTemplate *tt = templ->type_template(static_cast<int>(all[k*kRecord+1]));
    npoints += static_cast<long>(tt->shape.bodyMesh.vertexCount());
    ntris += static_cast<long>(tt->shape.bodyMesh.triangleCount());
  }
  fprintf(out,"# vtk DataFile Version 3.0\nspacetree-dem trimesh particles, step " BIGINT_FORMAT
          "\nASCII\nDATASET POLYDATA\nPOINTS %ld double\n",update->ntimestep,npoints);
  for (int k : order) {
    const double *r = &all[k*kRecord];
    const TrimeshTypeTemplate *tt = templ->type_template(static_cast<int>(r[1]));
    const Eigen::Quaterniond q(r[5],r[6],r[7],r[8]);
    const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
    const Eigen::Vector3d x(r[2],r[3],r[4]);
    for (const Eigen::Vector3d &v : tt->shape.bodyMesh.vertices) {
      const Eigen::Vector3d w = R * v + x;
      fprintf(out,"%.10g %.10g %.10g\n",w[0],w[1],w[2]);
    }
  }
  fprintf(out,"POLYGONS %ld %ld\n",ntris,4*ntris);
  long offset = 0;
  for (int k : order) {
    const TrimeshTypeTemplate *tt = templ->type_template(static_cast<int>(all[k*kRecord+1]));
    for (const auto &t : tt->shape.bodyMesh.triangles)
      fprintf(out,"3 %ld %ld %ld\n",offset+t[0],offset+t[1],offset+t[2]);
    offset += static_cast<long>(tt->shape.bodyMesh.vertexCount());
  }
  fprintf(out,"CELL_DATA %ld\nSCALARS id int 1\nLOOKUP_TABLE default\n",ntris);
  for (int k : order) {
    const TrimeshTypeTemplate *tt = templ->type_template(static_cast<int>(all[k*kRecord+1]));
    for (std::size_t t = 0; t < tt->shape.bodyMesh.triangleCount(); t++)
      fprintf(out,"%d\n",static_cast<int>(all[k*kRecord]));
  }
  fprintf(out,"SCALARS type int 1\nLOOKUP_TABLE default\n");
  for (int k : order) {
    const TrimeshTypeTemplate *tt = templ->type_template(static_cast<int>(all[k*kRecord+1]));
    for (std::size_t t = 0; t < tt->shape.bodyMesh.triangleCount(); t++)
      fprintf(out,"%d\n",static_cast<int>(all[k*kRecord+1]));
  }
  fclose(out);
}
