/* spacetree-dem: the core's view of one side of a contact of pair_style trimesh (kinematics
   only: pose, velocity, angular velocity, mass), for each kind of atom it meets:
     - a grain (template type): its mass and principal inertia, angular velocity as angular
       momentum (none without rotation);
     - an obstacle (fixed template type): infinite mass, moving with the velocity and angular
       velocity of its atom (zero unless fix move/trimesh prescribes them);
     - a sphere (a type without template): mass rmass, inertia 2/5 m r^2, orientation identity;
     - a wall point (fix wall/gran): infinite mass, the wall's velocity at the contact point. */

#ifndef LMP_TRIMESH_CONTACT_BODY_H
#define LMP_TRIMESH_CONTACT_BODY_H

#include <Eigen/Core>

#include "contact/MeshContact.h"
#include "dynamics/RigidBody.h"

namespace LAMMPS_NS {

struct TrimeshTypeTemplate;

// Atom i as a body: tt its template, NULL for a sphere; pose as given (grains/obstacles: their
// quaternion; spheres: centre, identity).
spacetree::dynamics::RigidBody trimesh_contact_body(const TrimeshTypeTemplate *tt,
                                                    const spacetree::contact::Pose &pose,
                                                    const double *v, const double *omega,
                                                    double rmass, double radius, bool rotation);

// A wall (or any body of infinite mass) whose material at `point` moves with `velocity`.
spacetree::dynamics::RigidBody trimesh_wall_body(const Eigen::Vector3d &point,
                                                 const Eigen::Vector3d &velocity);

}

#endif
