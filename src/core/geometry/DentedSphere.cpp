#include "geometry/DentedSphere.h"

#include <random>
#include <stdexcept>
#include <string>

#include "geometry/SphereMesh.h"

namespace spacetree::geometry {

TriangleMesh dentedSphere(const DentedSphereOptions& options) {
  if (options.triangles < 12 || options.triangles > kMaxSphereMeshTriangles)
    throw std::invalid_argument("dentedSphere: need 12 to " +
                                std::to_string(kMaxSphereMeshTriangles) + " triangles");
  if (!(options.radius > 0.0)) throw std::invalid_argument("dentedSphere: radius must be > 0");
  if (!(options.amplitude >= 0.0 && options.amplitude < 1.0))
    throw std::invalid_argument("dentedSphere: amplitude must be in [0, 1)");
  TriangleMesh mesh = latitudeLongitudeSphereMeshWithAbout(options.triangles, 1.0);
  std::mt19937_64 random(options.seed);
  for (auto& v : mesh.vertices) {
    // 53 random bits -> [0, 1) -> [-1, 1)
    const double u = 2.0 * (double(random() >> 11) * 0x1.0p-53) - 1.0;
    v *= options.radius * (1.0 + options.amplitude * u) / v.norm();
  }
  return mesh;
}

}  // namespace spacetree::geometry
