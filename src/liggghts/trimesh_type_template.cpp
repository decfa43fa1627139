/* spacetree-dem: per-type template of triangulated rigid particles (thin layer over the core). */

#include "trimesh_type_template.h"

#include <exception>

#include <Eigen/Geometry>

#include "dynamics/RigidBody.h"
#include "geometry/DentedSphere.h"
#include "geometry/MeshIO.h"
#include "geometry/MeshValidation.h"

using namespace LAMMPS_NS;
namespace geo = spacetree::geometry;

std::unique_ptr<TrimeshTypeTemplate> TrimeshTypeTemplate::build(const TrimeshTypeSource &src,
                                                                std::string &why)
{
  auto t = std::make_unique<TrimeshTypeTemplate>();
  try {
    geo::TriangleMesh mesh;
    if (src.kind == TrimeshTypeSource::File) {
      t->name = src.path;
      mesh = geo::readMesh(src.path);
      if (src.scale != 1.0) mesh.transform(src.scale * Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero());
    } else {
      t->name = "dented sphere";
      geo::DentedSphereOptions o;
      o.triangles = src.ntri;
      o.radius = src.radius;
      o.amplitude = src.amplitude;
      o.seed = static_cast<std::uint64_t>(src.seed);
      mesh = geo::dentedSphere(o);
    }
    geo::validateMesh(mesh,t->name);
    t->shape = geo::RigidShape::fromMesh(mesh);
  } catch (const std::exception &e) {
    why = e.what();
    return nullptr;
  }
  t->fixed = src.fixed;
  t->density = src.density;
  t->mass = t->shape.mass(src.density);
  t->inertia = t->shape.principalInertia(src.density);
  t->boundingRadius = t->shape.boundingRadius;
  t->filePosition = t->shape.centreOfMassInMesh;
  t->fileOrientation = t->shape.bodyOrientationFor();
  return t;
}

void TrimeshTypeTemplate::angularMomentumFromOmega(const double *quat, const double *omega,
                                                   double *angmom) const
{
  spacetree::dynamics::RigidBody b = spacetree::dynamics::RigidBody::free(
      mass,inertia,Eigen::Vector3d::Zero(),Eigen::Quaterniond(quat[0],quat[1],quat[2],quat[3]).normalized());
  b.setAngularVelocity(Eigen::Vector3d(omega[0],omega[1],omega[2]));
  for (int k = 0; k < 3; k++) angmom[k] = b.angularMomentum[k];
}
