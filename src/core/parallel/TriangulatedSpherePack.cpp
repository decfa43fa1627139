#include "parallel/TriangulatedSpherePack.h"

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <stdexcept>

#include "geometry/SphereMesh.h"

namespace spacetree::parallel {

TriangulatedSpherePack makeTriangulatedSpherePack(const TriangulatedSpherePackOptions& options) {
  if (options.particles < 1 || options.trianglesPerParticle < 12 || !(options.spacing > 0.0))
    throw std::invalid_argument(
        "makeTriangulatedSpherePack: need particles >= 1, trianglesPerParticle >= 12 and spacing > 0");
  const std::vector<geometry::Triangle> unitSphere =
      geometry::latitudeLongitudeSphereWithAbout(options.trianglesPerParticle, 1.0);
  const int side = int(std::ceil(std::cbrt(double(options.particles))));
  const double spacing = options.spacing * options.radius;

  std::mt19937_64 random(options.seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::normal_distribution<double> gaussian;

  TriangulatedSpherePack pack;
  pack.centre.reserve(std::size_t(options.particles));
  pack.radius.reserve(std::size_t(options.particles));
  std::vector<geometry::Triangle> sphere(unitSphere.size());
  for (int p = 0; p < options.particles; ++p) {
    const int i = p % side, j = (p / side) % side, k = p / (side * side);
    const double r = options.radius * (1.0 + options.radiusJitter * unit(random));
    const double jitter = options.positionJitter * options.radius;
    const Eigen::Vector3d x(spacing * i + jitter * unit(random), spacing * j + jitter * unit(random),
                            spacing * k + jitter * unit(random));
    Eigen::Quaterniond q(gaussian(random), gaussian(random), gaussian(random), gaussian(random));
    q.normalize();
    for (std::size_t t = 0; t < unitSphere.size(); ++t)
      sphere[t] = geometry::Triangle(r * unitSphere[t][0], r * unitSphere[t][1], r * unitSphere[t][2]);
    pack.meshes.add(sphere, q.toRotationMatrix(), x);
    pack.centre.push_back({x.x(), x.y(), x.z()});
    pack.radius.push_back(r);
  }
  return pack;
}

}  // namespace spacetree::parallel
