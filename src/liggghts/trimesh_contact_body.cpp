/* spacetree-dem: one side of a contact of pair_style trimesh as a core RigidBody. */

#include "trimesh_contact_body.h"

#include "trimesh_type_template.h"

using namespace LAMMPS_NS;
namespace dy = spacetree::dynamics;

dy::RigidBody LAMMPS_NS::trimesh_contact_body(const TrimeshTypeTemplate *tt,
                                              const spacetree::contact::Pose &pose,
                                              const double *v, const double *omega, double rmass,
                                              double radius, bool rotation)
{
  const Eigen::Vector3d velocity(v[0],v[1],v[2]), w(omega[0],omega[1],omega[2]);
  if (tt && tt->fixed) {
    dy::RigidBody b = dy::RigidBody::fixed(pose.position,pose.orientation);
    b.velocity = velocity;
    if (rotation) b.prescribedAngularVelocity = w;
    return b;
  }
  const Eigen::Vector3d inertia = tt ? Eigen::Vector3d(tt->inertia * (rmass / tt->mass))
                                     : Eigen::Vector3d::Constant(0.4 * rmass * radius * radius);
  dy::RigidBody b = dy::RigidBody::free(rmass,inertia,pose.position,pose.orientation);
  b.velocity = velocity;
  if (rotation) b.setAngularVelocity(w);
  else b.inverseInertia.setZero();   // rotation no: the contact point's mass is the body's
  return b;
}

dy::RigidBody LAMMPS_NS::trimesh_wall_body(const Eigen::Vector3d &point,
                                           const Eigen::Vector3d &velocity)
{
  dy::RigidBody b = dy::RigidBody::fixed(point);
  b.velocity = velocity;
  return b;
}
