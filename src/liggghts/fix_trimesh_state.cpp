/* spacetree-dem: per-atom orientation and angular momentum of triangulated rigid particles. */

#include "fix_trimesh_state.h"

#include <cstring>

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "memory.h"

using namespace LAMMPS_NS;

FixTrimeshState::FixTrimeshState(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), quat(NULL), angmom(NULL), values_(NULL), with_shape_(false)
{
  if (narg != 3) error->all(FLERR,"Illegal fix trimesh/state command: it takes no arguments");
  restart_peratom = 1;
  create_attribute = 1;
  comm_forward = 6;   // the largest forward comm (forward_shapes)
  comm_border = 4;
  // f_ID[1..7] in dump custom, compute reduce, variables: always current (peratom_freq 1)
  peratom_flag = 1;
  size_peratom_cols = 7;
  peratom_freq = 1;

  grow_arrays(atom->nmax);
  atom->add_callback(0);   // grow + exchange
  atom->add_callback(1);   // restart
  atom->add_callback(2);   // border
  for (int i = 0; i < atom->nmax; i++) set_arrays(i);
  // Modify::setup() would call set_arrays() on every atom of a "just created" fix at the end
  // of the first setup, after fix trimesh/template has set the orientations: the arrays are
  // initialised here instead
  just_created = 0;
}

FixTrimeshState::~FixTrimeshState()
{
  atom->delete_callback(id,0);
  atom->delete_callback(id,1);
  atom->delete_callback(id,2);
  // Atom's destructor frees atom->quaternion: it must not see ours
  if (atom->quaternion == quat) atom->quaternion = NULL;
  memory->destroy(values_);
  memory->sfree(quat);
  memory->sfree(angmom);
}

void FixTrimeshState::grow_arrays(int nmax)
{
  memory->grow(values_,nmax,7,"trimesh/state:values");
  array_atom = values_;
  point_rows(values_ ? nmax : 0);
}

void FixTrimeshState::point_rows(int nmax)
{
  // quat / angmom are row pointers into values_ (re-pointed whenever values_ moves)
  double **old = quat;
  const bigint bytes = sizeof(double *) * static_cast<bigint>(nmax > 0 ? nmax : 1);
  quat = static_cast<double **>(memory->srealloc(quat,bytes,"trimesh/state:quat"));
  angmom = static_cast<double **>(memory->srealloc(angmom,bytes,"trimesh/state:angmom"));
  for (int i = 0; i < nmax; i++) {
    quat[i] = values_[i];
    angmom[i] = values_[i] + 4;
  }
  // dump custom quat1..quat4 read atom->quaternion (patch 0003); another style's is left alone
  if (atom->quaternion == NULL || atom->quaternion == old) atom->quaternion = quat;
}

void FixTrimeshState::copy_arrays(int i, int j, int)
{
  for (int k = 0; k < 4; k++) quat[j][k] = quat[i][k];
  for (int k = 0; k < 3; k++) angmom[j][k] = angmom[i][k];
}

void FixTrimeshState::set_arrays(int i)
{
  // quat = 0 marks "orientation not set": fix trimesh/template initialises it at setup
  for (int k = 0; k < 4; k++) quat[i][k] = 0.0;
  for (int k = 0; k < 3; k++) angmom[i][k] = 0.0;
}

int FixTrimeshState::pack_exchange(int i, double *buf)
{
  int m = 0;
  for (int k = 0; k < 4; k++) buf[m++] = quat[i][k];
  for (int k = 0; k < 3; k++) buf[m++] = angmom[i][k];
  return m;
}

int FixTrimeshState::unpack_exchange(int i, double *buf)
{
  int m = 0;
  for (int k = 0; k < 4; k++) quat[i][k] = buf[m++];
  for (int k = 0; k < 3; k++) angmom[i][k] = buf[m++];
  return m;
}

int FixTrimeshState::pack_border(int n, int *list, double *buf)
{
  int m = 0;
  for (int ii = 0; ii < n; ii++)
    for (int k = 0; k < 4; k++) buf[m++] = quat[list[ii]][k];
  return m;
}

int FixTrimeshState::unpack_border(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first+n; i++)
    for (int k = 0; k < 4; k++) quat[i][k] = buf[m++];
  return m;
}

int FixTrimeshState::pack_comm(int n, int *list, double *buf, int, int *)
{
  int m = 0;
  for (int ii = 0; ii < n; ii++) {
    const int j = list[ii];
    for (int k = 0; k < 4; k++) buf[m++] = quat[j][k];
    if (with_shape_) { buf[m++] = atom->radius[j]; buf[m++] = atom->rmass[j]; }
  }
  return with_shape_ ? 6 : 4;   // Comm::forward_comm_fix wants the count per atom
}

void FixTrimeshState::unpack_comm(int n, int first, double *buf)
{
  int m = 0;
  for (int i = first; i < first+n; i++) {
    for (int k = 0; k < 4; k++) quat[i][k] = buf[m++];
    if (with_shape_) { atom->radius[i] = buf[m++]; atom->rmass[i] = buf[m++]; }
  }
}

void FixTrimeshState::forward_orientations()
{
  with_shape_ = false;
  comm->forward_comm_fix(this);
}

void FixTrimeshState::forward_shapes()
{
  with_shape_ = true;
  comm->forward_comm_fix(this);
  with_shape_ = false;
}

int FixTrimeshState::pack_restart(int i, double *buf)
{
  buf[0] = 8;   // count including itself, LAMMPS restart convention
  int m = 1;
  for (int k = 0; k < 4; k++) buf[m++] = quat[i][k];
  for (int k = 0; k < 3; k++) buf[m++] = angmom[i][k];
  return m;
}

void FixTrimeshState::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  // skip to the nth stored fix's values
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  m++;
  for (int k = 0; k < 4; k++) quat[nlocal][k] = extra[nlocal][m++];
  for (int k = 0; k < 3; k++) angmom[nlocal][k] = extra[nlocal][m++];
}

double FixTrimeshState::memory_usage()
{
  return (7.0 * sizeof(double) + 2.0 * sizeof(double *)) * atom->nmax;
}

void FixTrimeshState::pack(int i, double *values) const
{
  for (int k = 0; k < 7; k++) values[k] = values_[i][k];
}

void FixTrimeshState::unpack(int i, const double *values)
{
  for (int k = 0; k < 7; k++) values_[i][k] = values[k];
}
