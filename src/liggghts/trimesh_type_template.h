/* spacetree-dem: the template of one atom type of triangulated rigid particles: a core
   RigidShape (mesh in the principal body frame) plus density, mass and the obstacle flag.
   Built from a mesh file (MeshIO + MeshValidation) or a generated dented sphere. */

#ifndef LMP_TRIMESH_TYPE_TEMPLATE_H
#define LMP_TRIMESH_TYPE_TEMPLATE_H

#include <memory>
#include <string>

#include <Eigen/Core>

#include "geometry/RigidShape.h"

namespace LAMMPS_NS {

struct TrimeshTypeSource {
  enum Kind { File, Dented } kind = File;
  std::string path;          // File
  double scale = 1.0;        // File: coordinates are multiplied by this
  int ntri = 0;              // Dented
  double radius = 0.0, amplitude = 0.0;
  int seed = 0;
  double density = 2500.0;
  bool fixed = false;        // obstacle: infinite mass, never integrated
};

struct TrimeshTypeTemplate {
  spacetree::geometry::RigidShape shape;
  std::string name;           // file path or "dented sphere", for messages
  bool fixed = false;
  double density = 0.0;
  double mass = 0.0;          // density * volume
  Eigen::Vector3d inertia = Eigen::Vector3d::Zero();   // principal moments, body frame
  double boundingRadius = 0.0;
  // Placement of a fixed obstacle that reproduces the file's coordinates.
  Eigen::Vector3d filePosition = Eigen::Vector3d::Zero();
  Eigen::Quaterniond fileOrientation = Eigen::Quaterniond::Identity();

  // NULL and `why` set on bad input (unreadable file, open surface, ...).
  static std::unique_ptr<TrimeshTypeTemplate> build(const TrimeshTypeSource &src, std::string &why);

  // L_world = R diag(I) R^T omega_world for orientation quat (w,x,y,z).
  void angularMomentumFromOmega(const double *quat, const double *omega, double *angmom) const;
};

}

#endif
