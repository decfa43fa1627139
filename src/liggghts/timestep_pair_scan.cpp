/* spacetree-dem: see timestep_pair_scan.h */

#include "timestep_pair_scan.h"

#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "atom.h"
#include "comm.h"
#include "fix.h"
#include "fix_mesh_surface.h"
#include "fix_neighlist_mesh.h"
#include "fix_wall_gran.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair_trimesh.h"
#include "primitive_wall.h"
#include "tri_mesh.h"

using namespace LAMMPS_NS;

TimestepPairScan::Result TimestepPairScan::scan(NeighList *list, const spacetree::TimestepPolicy &policy,
                                                double dtTest, spacetree::TimestepVeto *veto)
{
  policy_ = &policy;
  veto_ = veto;
  dt_test_ = dtTest;
  speeds_ = policy.impactSpeed > 0.0;
  std::fill(tally_,tally_ + NTALLY,0.0);

  if (speeds_) share_accelerations();
  if (trimesh_) scan_trimesh(list);   // collective
  else if (list) scan_list(list);
  for (int f = 0; f < modify->nfix; f++) {
    if (strcmp(modify->fix[f]->style,"wall/gran") != 0) continue;
    FixWallGran *wall = static_cast<FixWallGran*>(modify->fix[f]);
    if (wall->is_mesh_wall()) scan_mesh_wall(wall);
    else scan_primitive_wall(wall);
  }

  double global[NTALLY];
  MPI_Allreduce(&tally_[OVERLAP],&global[OVERLAP],1,MPI_DOUBLE,MPI_MAX,world);
  MPI_Allreduce(&tally_[CONTACTS],&global[CONTACTS],2,MPI_DOUBLE,MPI_SUM,world);   // and CRITICAL
  MPI_Allreduce(&tally_[SOON],&global[SOON],3,MPI_DOUBLE,MPI_MAX,world);           // SPEED, INV_STABLE
  Result r;
  r.maxOverlap = global[OVERLAP];
  r.contacts = global[CONTACTS];
  r.criticalPairs = global[CRITICAL];
  r.contactSoon = global[CONTACTS] > 0.0 || global[SOON] > 0.0;
  r.contactSpeed = global[SPEED];
  r.stableStep = global[INV_STABLE] > 0.0 ? 1.0 / global[INV_STABLE] : 0.0;
  return r;
}

/* Accelerations f/m at the end of the step (f is complete for owned atoms only), sent to the
   ghosts. Atoms outside the group count as held (a fixed base sphere feels a force it never
   follows); keeping them in the group only overestimates the contact speed (smaller steps). */

void TimestepPairScan::share_accelerations()
{
  const int nall = atom->nlocal + atom->nghost;
  accel_.assign(3*size_t(nall),0.0);
  for (int i = 0; i < atom->nlocal; i++)
    if (atom->mask[i] & owner_->groupbit)
      for (int k = 0; k < 3; k++) accel_[3*i+k] = atom->f[i][k]/atom->rmass[i];
  comm->forward_comm_fix(owner_);
}

/* Triangulated particles: the veto and the approach test take the velocities at the contact
   points, so the ghosts get the end-of-step velocities and angular velocities of their owners
   (LIGGGHTS' forward communication of the step carried the half-step ones): a pair across two
   ranks is then judged alike on both, as on one rank. */

void TimestepPairScan::share_velocities()
{
  sharing_ = Shared::Velocities;
  comm->forward_comm_fix(owner_);
  sharing_ = Shared::Accelerations;
}

int TimestepPairScan::pack_comm(int n, int *list, double *buf) const
{
  if (sharing_ == Shared::Velocities) {
    for (int m = 0; m < n; m++)
      for (int k = 0; k < 3; k++) {
        buf[6*m+k] = atom->v[list[m]][k];
        buf[6*m+3+k] = atom->omega[list[m]][k];
      }
    return 6;
  }
  for (int m = 0; m < n; m++)
    for (int k = 0; k < 3; k++) buf[3*m+k] = accel_[3*size_t(list[m])+k];
  return 3;   // LIGGGHTS 3.8 Comm::forward_comm_fix wants the values per atom
}

void TimestepPairScan::unpack_comm(int n, int first, const double *buf)
{
  if (sharing_ == Shared::Velocities) {
    for (int m = 0; m < n; m++)
      for (int k = 0; k < 3; k++) {
        atom->v[first+m][k] = buf[6*m+k];
        atom->omega[first+m][k] = buf[6*m+3+k];
      }
    return;
  }
  for (int m = 0; m < n; m++)
    for (int k = 0; k < 3; k++) accel_[3*size_t(first+m)+k] = buf[3*m+k];
}

/* The pairs of the granular list with at least one atom in the group. Own/ghost pairs appear on
   both ranks: they count half on each. */

void TimestepPairScan::scan_list(NeighList *list)
{
  double **x = atom->x;
  double **v = atom->v;
  double *radius = atom->radius;
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const int groupbit = owner_->groupbit;
  neighbor->build_one(list->index);
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!(mask[i] & groupbit) && !(mask[j] & groupbit)) continue;
      const double share = j < nlocal ? 1.0 : 0.5;
      const double dx = x[j][0]-x[i][0], dy = x[j][1]-x[i][1], dz = x[j][2]-x[i][2];
      const double dist = std::sqrt(dx*dx + dy*dy + dz*dz);
      const double overlap = radius[i] + radius[j] - dist;
      if (overlap > 0.0) {
        tally_[OVERLAP] = std::max(tally_[OVERLAP],overlap);
        tally_[CONTACTS] += share;
        if (speeds_ && dist > 0.0) {
          const double vn = ((v[j][0]-v[i][0])*dx + (v[j][1]-v[i][1])*dy + (v[j][2]-v[i][2])*dz)/dist;
          const double *ai = &accel_[3*size_t(i)], *aj = &accel_[3*size_t(j)];
          const double an = ((aj[0]-ai[0])*dx + (aj[1]-ai[1])*dy + (aj[2]-ai[2])*dz)/dist;
          tally_[SPEED] = std::max(tally_[SPEED],spacetree::contactSpeed(vn,an,policy_->contactTime));
        }
      } else if (policy_->dtContact > 0.0 && dist > 0.0) {
        // a pair that may touch within the next step already needs the contact resolution
        const double approach = -((v[j][0]-v[i][0])*dx + (v[j][1]-v[i][1])*dy + (v[j][2]-v[i][2])*dz)/dist;
        if (approach*dt_test_ > -overlap) {
          tally_[SOON] = 1.0;
          tally_[SPEED] = std::max(tally_[SPEED],approach);
        }
      }
      if (veto_ && veto_->consider(x[i],v[i],radius[i],x[j],v[j],radius[j],dt_test_)) tally_[CRITICAL] += share;
    }
  }
}

void TimestepPairScan::use_trimesh(PairTrimesh *pair, double allowedPenetration, double safety)
{
  trimesh_.reset(pair ? new TimestepTrimeshScan(lmp,pair) : NULL);
  allowed_penetration_ = allowedPenetration;
  safety_ = safety;
}

void TimestepPairScan::scan_trimesh(NeighList *list)
{
  share_velocities();
  TimestepTrimeshScan::Settings s;
  s.groupbit = owner_->groupbit;
  s.dtTest = dt_test_;
  s.allowedPenetration = allowed_penetration_;
  s.safety = safety_;
  s.ceiling = policy_->dtContact > 0.0 || policy_->stableCeiling;
  s.stable = policy_->stableCeiling;
  s.speeds = speeds_;
  s.contactTime = policy_->contactTime;
  s.accel = accel_.data();
  const TimestepTrimeshScan::Tally t = trimesh_->scan(list,s,veto_);
  tally_[OVERLAP] = std::max(tally_[OVERLAP],t.maxPenetration);
  tally_[CONTACTS] += t.contacts;
  tally_[CRITICAL] += t.critical;
  if (t.soon) tally_[SOON] = 1.0;
  tally_[SPEED] = std::max(tally_[SPEED],t.speed);
  if (t.stable < std::numeric_limits<double>::infinity())
    tally_[INV_STABLE] = std::max(tally_[INV_STABLE],1.0 / t.stable);
}

// fix wall/gran ... primitive: every local particle of the group against the wall
void TimestepPairScan::scan_primitive_wall(FixWallGran *wall)
{
  PrimitiveWall *pw = wall->primitiveWall();
  if (!pw) return;
  const bool moving = wall->is_moving();
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(atom->mask[i] & owner_->groupbit)) continue;
    if (wall->excludes_type(atom->type[i])) continue;   // grains: pair_style trimesh's contacts
    double delta[3];
    const double gap = pw->resolveContact(atom->x[i],atom->radius[i],delta);
    wall_contact(i,gap,delta,moving);
  }
}

/* fix wall/gran ... mesh: the particles of each triangle's contact list (fix neighlist/mesh, owned
   and ghost triangles), the closest triangle per particle and mesh. */

void TimestepPairScan::scan_mesh_wall(FixWallGran *wall)
{
  const int nlocal = atom->nlocal;
  for (int m = 0; m < wall->n_meshes(); m++) {
    FixMeshSurface *fm = wall->mesh_list()[m];
    TriMesh *mesh = fm->triMesh();
    FixNeighlistMesh *nl = fm->meshNeighlist();
    if (!mesh || !nl) continue;
    const bool moving = mesh->prop().getElementProperty<MultiVectorContainer<double,3,3> >("v") != NULL;
    mesh_gap_.assign(nlocal,std::numeric_limits<double>::infinity());
    mesh_delta_.resize(3*size_t(nlocal));
    const int ntri = mesh->sizeLocal() + mesh->sizeGhost();
    for (int t = 0; t < ntri; t++) {
      const std::vector<int> &candidates = nl->get_contact_list(t);
      for (const int i : candidates) {
        if (i >= nlocal || !(atom->mask[i] & owner_->groupbit)) continue;
        if (wall->excludes_type(atom->type[i])) continue;   // grains: pair_style trimesh's
        double delta[3];
        int barysign;
        const double gap = mesh->resolveTriSphereContact(i,t,atom->radius[i],atom->x[i],delta,barysign);
        if (gap < mesh_gap_[i]) {
          mesh_gap_[i] = gap;
          for (int d = 0; d < 3; d++) mesh_delta_[3*size_t(i)+d] = delta[d];
        }
      }
    }
    for (int i = 0; i < nlocal; i++)
      if (mesh_gap_[i] < 1e100) wall_contact(i,mesh_gap_[i],&mesh_delta_[3*size_t(i)],moving);
  }
}

void TimestepPairScan::wall_contact(int i, double gap, const double *delta, bool moving)
{
  static const double rest[3] = {0.0,0.0,0.0};
  double **x = atom->x;
  double **v = atom->v;
  const double dist = std::sqrt(delta[0]*delta[0] + delta[1]*delta[1] + delta[2]*delta[2]);
  if (gap < 0.0) {
    tally_[OVERLAP] = std::max(tally_[OVERLAP],-gap);
    tally_[CONTACTS] += 1.0;
    if (speeds_ && dist > 0.0) {   // the particle's speed towards the wall
      const double vn = (v[i][0]*delta[0] + v[i][1]*delta[1] + v[i][2]*delta[2])/dist;
      const double an = (atom->f[i][0]*delta[0] + atom->f[i][1]*delta[1] + atom->f[i][2]*delta[2])
                        /(dist*atom->rmass[i]);
      tally_[SPEED] = std::max(tally_[SPEED],spacetree::contactSpeed(vn,an,policy_->contactTime));
    }
    return;
  }
  if (moving) return;
  if (policy_->dtContact > 0.0 && dist > 0.0) {
    const double approach = (v[i][0]*delta[0] + v[i][1]*delta[1] + v[i][2]*delta[2])/dist;
    if (approach*dt_test_ > gap) {
      tally_[SOON] = 1.0;
      tally_[SPEED] = std::max(tally_[SPEED],approach);
    }
  }
  const double xw[3] = {x[i][0]+delta[0],x[i][1]+delta[1],x[i][2]+delta[2]};
  if (veto_ && veto_->consider(x[i],v[i],atom->radius[i],xw,rest,0.0,dt_test_)) tally_[CRITICAL] += 1.0;
}
