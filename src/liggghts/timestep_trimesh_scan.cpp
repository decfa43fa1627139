/* spacetree-dem: see timestep_trimesh_scan.h */

#include "timestep_trimesh_scan.h"

#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "atom.h"
#include "dynamics/AdaptiveTimestep.h"
#include "fix_trimesh_state.h"
#include "fix_trimesh_template.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "pair_trimesh.h"
#include "trimesh_parallel_contacts.h"

using namespace LAMMPS_NS;
namespace ct = spacetree::contact;

namespace {
std::uint64_t pair_key(int i, int j)
{
  const std::uint32_t lo = std::uint32_t(std::min(i,j)), hi = std::uint32_t(std::max(i,j));
  return (std::uint64_t(lo) << 32) | hi;
}
}

TimestepTrimeshScan::TimestepTrimeshScan(LAMMPS *lmp, PairTrimesh *pair) :
  Pointers(lmp), pair_(pair), templ_(pair->trimesh_template()),
  halo_(pair->contact_options().epsilon),
  probe_(new ct::SurfaceGapProbe(pair->contact_options()))
{
}

bool TimestepTrimeshScan::moving(int i) const
{
  // grains and obstacles: a static obstacle has v = omega = 0 (fix trimesh/template), one that
  // fix move/trimesh moves has its prescribed velocities, as in the contact law
  return templ_->type_template(atom->type[i]) != NULL;
}

double TimestepTrimeshScan::normal_velocity(int a, int b, const double *point, const double *normal) const
{
  double rel[3] = {0.0,0.0,0.0};
  const int body[2] = {a,b};
  const double sign[2] = {-1.0,1.0};
  for (int k = 0; k < 2; k++) {
    const int i = body[k];
    if (!moving(i)) continue;
    const double *x = atom->x[i], *v = atom->v[i], *w = atom->omega[i];
    const double r[3] = {point[0]-x[0], point[1]-x[1], point[2]-x[2]};
    rel[0] += sign[k]*(v[0] + w[1]*r[2] - w[2]*r[1]);
    rel[1] += sign[k]*(v[1] + w[2]*r[0] - w[0]*r[2]);
    rel[2] += sign[k]*(v[2] + w[0]*r[1] - w[1]*r[0]);
  }
  return rel[0]*normal[0] + rel[1]*normal[1] + rel[2]*normal[2];
}

TimestepTrimeshScan::Tally TimestepTrimeshScan::scan(NeighList *list, const Settings &s,
                                                    spacetree::TimestepVeto *veto)
{
  Tally t;
  scan_contacts(s,veto,t);
  double mine = t.contacts, all = 0.0;
  MPI_Allreduce(&mine,&all,1,MPI_DOUBLE,MPI_SUM,world);
  if (list) {
    neighbor->build_one(list->index);
    scan_near_pairs(list,s,all > 0.0,veto,t);
  }
  return t;
}

/* The pairs the pair style found in contact, at each contact point. */

void TimestepTrimeshScan::scan_contacts(const Settings &s, spacetree::TimestepVeto *veto, Tally &t)
{
  int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  in_contact_.clear();
  for (std::size_t k = 0; k < pair_->candidate_pairs(); k++) {
    const std::vector<ct::ContactPoint> &points = pair_->contacts_of(k);
    if (points.empty()) continue;
    const TrimeshCandidatePair &p = pair_->candidate_pair(k);
    const int a = p.a, b = p.b;
    in_contact_.insert(pair_key(a,b));
    if (!(mask[a] & s.groupbit) && !(mask[b] & s.groupbit)) continue;
    const double share = (a < nlocal && b < nlocal) ? 1.0 : 0.5;
    t.contacts += share;
    if (s.stable) t.stable = std::min(t.stable,pair_->stable_step(atom->type[a],atom->type[b]));
    bool critical = false;
    for (const ct::ContactPoint &c : points) {
      t.maxPenetration = std::max(t.maxPenetration,c.penetration);
      const double vn = normal_velocity(a,b,c.point.data(),c.normal.data());
      if (veto && veto->considerGap(spacetree::haloGap(c.distance,halo_,s.allowedPenetration),-vn,s.dtTest))
        critical = true;
      if (s.speeds) {
        const double *aa = s.accel + 3*size_t(a), *ab = s.accel + 3*size_t(b);
        const double an = (ab[0]-aa[0])*c.normal[0] + (ab[1]-aa[1])*c.normal[1] + (ab[2]-aa[2])*c.normal[2];
        t.speed = std::max(t.speed,spacetree::contactSpeed(vn,an,s.contactTime));
      }
    }
    if (critical) t.critical += share;
  }
}

/* The other pairs of the granular list: at least 2 eps apart; probed only when the closing-speed
   bound says the step could make them critical or let them touch. */

void TimestepTrimeshScan::scan_near_pairs(NeighList *list, const Settings &s, bool any_contact,
                                          spacetree::TimestepVeto *veto, Tally &t)
{
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  double **quat = templ_->state()->quat;
  int *mask = atom->mask, *type = atom->type, *tag = atom->tag;
  const int nlocal = atom->nlocal;
  const double P = s.allowedPenetration;
  for (int ii = 0; ii < list->inum; ii++) {
    const int i = list->ilist[ii];
    const TrimeshTypeTemplate *ti = templ_->type_template(type[i]);
    if (!ti) continue;
    const int *jlist = list->firstneigh[i];
    for (int jj = 0; jj < list->numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      if (!(mask[i] & s.groupbit) && !(mask[j] & s.groupbit)) continue;
      const TrimeshTypeTemplate *tj = templ_->type_template(type[j]);
      if (!tj || (ti->fixed && tj->fixed)) continue;
      if (in_contact_.count(pair_key(i,j))) continue;
      const Eigen::Vector3d xi(x[i][0],x[i][1],x[i][2]), xj(x[j][0],x[j][1],x[j][2]);
      // (obstacles too: moved by fix move/trimesh, at rest otherwise)
      const Eigen::Vector3d vi(v[i][0],v[i][1],v[i][2]), vj(v[j][0],v[j][1],v[j][2]);
      const Eigen::Vector3d wi(omega[i][0],omega[i][1],omega[i][2]), wj(omega[j][0],omega[j][1],omega[j][2]);
      const double w = ct::surfaceClosingSpeedBound(vi,wi,ti->boundingRadius,vj,wj,tj->boundingRadius);
      if (!(w > 0.0)) continue;
      const double reach = w*s.dtTest;
      // what is known without measuring: no contact, so d >= 2 eps; and d >= the sphere gap
      const double lower = std::max((xj-xi).norm() - ti->boundingRadius - tj->boundingRadius,2.0*halo_);
      const bool may_be_critical = veto && reach > s.safety*spacetree::haloGap(lower,halo_,P);
      // touching would lower the ceiling: the first contact, a faster one (vimpact), or one of a
      // type pair with a smaller stable step (stability ceiling)
      const double stable = s.stable ? pair_->stable_step(type[i],type[j]) : 0.0;
      const bool stiffer = s.stable && stable < t.stable;
      const bool may_touch = s.ceiling && (!any_contact || (s.speeds && w > t.speed) || stiffer) &&
                             !(t.soon && !s.speeds && !stiffer) && lower - reach < 2.0*halo_;
      if (!may_be_critical && !may_touch) continue;

      // in the pair style's canonical body order (the same on every rank)
      const TrimeshCandidatePair p = canonical_candidate_pair(i,j,*ti,*tj,tag,x,quat);
      const std::optional<ct::ContactPoint> c =
          probe_->nearest(*p.shape_a,p.pose_a,*p.shape_b,p.pose_b,2.0*halo_ + reach/s.safety);
      if (!c) continue;   // farther than the step can close: neither critical nor about to touch

      const double closing = -normal_velocity(p.a,p.b,c->point.data(),c->normal.data());
      const double share = j < nlocal ? 1.0 : 0.5;
      if (veto && veto->considerGap(spacetree::haloGap(c->distance,halo_,P),closing,s.dtTest))
        t.critical += share;
      if (s.ceiling && closing*s.dtTest > c->distance - 2.0*halo_) {
        t.soon = true;
        t.speed = std::max(t.speed,closing);
        if (s.stable) t.stable = std::min(t.stable,stable);
      }
    }
  }
}

double TimestepTrimeshScan::probes() const
{
  double mine = double(probe_->probes()), all = 0.0;
  MPI_Allreduce(&mine,&all,1,MPI_DOUBLE,MPI_SUM,world);
  return all;
}
