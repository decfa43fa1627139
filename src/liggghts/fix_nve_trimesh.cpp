/* spacetree-dem: velocity Verlet for triangulated rigid particles over the core RigidBody. */

#include "fix_nve_trimesh.h"


#include "atom.h"
#include "dynamics/RigidBody.h"
#include "error.h"
#include "fix_trimesh_state.h"
#include "fix_trimesh_template.h"
#include "force.h"
#include "update.h"

#include <mpi.h>

using namespace LAMMPS_NS;
using spacetree::dynamics::RigidBody;

namespace {

RigidBody load(const TrimeshTypeTemplate &tt, int i, double **x, double **v, double *rmass,
               double **quat, double **angmom)
{
  RigidBody b;
  b.position = Eigen::Vector3d(x[i][0],x[i][1],x[i][2]);
  b.orientation = Eigen::Quaterniond(quat[i][0],quat[i][1],quat[i][2],quat[i][3]);
  b.velocity = Eigen::Vector3d(v[i][0],v[i][1],v[i][2]);
  b.angularMomentum = Eigen::Vector3d(angmom[i][0],angmom[i][1],angmom[i][2]);
  b.inverseMass = 1.0 / rmass[i];
  b.inverseInertia = (tt.inertia * (rmass[i] / tt.mass)).cwiseInverse();
  return b;
}

void store(const RigidBody &b, int i, double **x, double **v, double **omega, double **quat,
           double **angmom)
{
  const Eigen::Vector3d w = b.angularVelocity();
  for (int k = 0; k < 3; k++) {
    x[i][k] = b.position[k];
    v[i][k] = b.velocity[k];
    angmom[i][k] = b.angularMomentum[k];
    omega[i][k] = w[k];
  }
  quat[i][0] = b.orientation.w(); quat[i][1] = b.orientation.x();
  quat[i][2] = b.orientation.y(); quat[i][3] = b.orientation.z();
}

}

FixNVETrimesh::FixNVETrimesh(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), dtv(0.0), dtf(0.0), templ(NULL)
{
  if (narg != 3) error->all(FLERR,"Illegal fix nve/trimesh command: it takes no arguments");
  if (!atom->sphere_flag)
    error->all(FLERR,"Fix nve/trimesh requires atom_style sphere or granular");
  time_integrate = 1;
  scalar_flag = 1;
  global_freq = 1;
  extscalar = 1;
}

int FixNVETrimesh::setmask()
{
  return FixConst::INITIAL_INTEGRATE | FixConst::FINAL_INTEGRATE;
}

void FixNVETrimesh::init()
{
  templ = FixTrimeshTemplate::find(lmp,"Fix nve/trimesh");
  if (!templ) error->all(FLERR,"Fix nve/trimesh requires fix trimesh/template");
  reset_dt();
}

void FixNVETrimesh::reset_dt()
{
  dtv = update->dt;
  dtf = 0.5 * update->dt * force->ftm2v;
}

/* One half kick of every moving body of the group, then (first half of the step) the drift. */

void FixNVETrimesh::kick_and_drift(bool drift)
{
  double **x = atom->x, **v = atom->v, **f = atom->f, **omega = atom->omega;
  double **torque = atom->torque;
  double *rmass = atom->rmass;
  int *mask = atom->mask, *type = atom->type;
  double **quat = templ->state()->quat, **angmom = templ->state()->angmom;
  const int nlocal = atom->nlocal;

  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const TrimeshTypeTemplate *tt = templ->type_template(type[i]);
    if (!tt || tt->fixed) continue;
    RigidBody b = load(*tt,i,x,v,rmass,quat,angmom);
    b.kick(Eigen::Vector3d(f[i][0],f[i][1],f[i][2]),
           Eigen::Vector3d(torque[i][0],torque[i][1],torque[i][2]),dtf);
    if (drift) b.drift(dtv);
    store(b,i,x,v,omega,quat,angmom);
  }
}

void FixNVETrimesh::initial_integrate(int)
{
  kick_and_drift(true);
}

void FixNVETrimesh::final_integrate()
{
  kick_and_drift(false);
}

double FixNVETrimesh::compute_scalar()
{
  double **x = atom->x, **v = atom->v;
  double *rmass = atom->rmass;
  int *mask = atom->mask, *type = atom->type;
  double **quat = templ->state()->quat, **angmom = templ->state()->angmom;
  double mine = 0.0;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    const TrimeshTypeTemplate *tt = templ->type_template(type[i]);
    if (!tt || tt->fixed) continue;
    mine += load(*tt,i,x,v,rmass,quat,angmom).kineticEnergy();
  }
  double all = 0.0;
  MPI_Allreduce(&mine,&all,1,MPI_DOUBLE,MPI_SUM,world);
  return all;
}
