#include "geometry/PrimitiveMeshes.h"

#include <array>
#include <cmath>
#include <map>
#include <stdexcept>

namespace spacetree::geometry {
namespace {

// Adds quad (a, b, c, d) as two triangles, ordered so that their normal points along `outward`.
void addQuad(TriangleMesh& mesh, int a, int b, int c, int d, const Eigen::Vector3d& outward) {
  const Eigen::Vector3d n =
      (mesh.vertices[b] - mesh.vertices[a]).cross(mesh.vertices[c] - mesh.vertices[a]);
  if (n.dot(outward) >= 0.0) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
  } else {
    mesh.triangles.push_back({a, c, b});
    mesh.triangles.push_back({a, d, c});
  }
}

}  // namespace

TriangleMesh boxMesh(const Eigen::Vector3d& size) {
  if (!(size.minCoeff() > 0.0)) throw std::invalid_argument("boxMesh: edge lengths must be > 0");
  TriangleMesh mesh;
  // Vertex k has coordinate +size/2 along axis c where bit c of k is set, -size/2 otherwise.
  for (int k = 0; k < 8; ++k)
    mesh.vertices.emplace_back((k & 1 ? 0.5 : -0.5) * size.x(), (k & 2 ? 0.5 : -0.5) * size.y(),
                               (k & 4 ? 0.5 : -0.5) * size.z());
  for (int axis = 0; axis < 3; ++axis) {
    const int u = 1 << ((axis + 1) % 3), v = 1 << ((axis + 2) % 3), w = 1 << axis;
    for (int side = 0; side < 2; ++side) {
      const int base = side ? w : 0;
      Eigen::Vector3d outward = Eigen::Vector3d::Zero();
      outward[axis] = side ? 1.0 : -1.0;
      addQuad(mesh, base, base + u, base + u + v, base + v, outward);
    }
  }
  return mesh;
}

TriangleMesh gridBoxMesh(const Eigen::Vector3d& size, const Eigen::Vector3i& cells) {
  if (!(size.minCoeff() > 0.0)) throw std::invalid_argument("gridBoxMesh: edge lengths must be > 0");
  if (cells.minCoeff() < 1) throw std::invalid_argument("gridBoxMesh: cell counts must be >= 1");
  TriangleMesh mesh;
  // One vertex per lattice point (i, j, k) on the box surface, shared by the faces meeting there.
  std::map<std::array<int, 3>, int> index;
  const auto vertex = [&](std::array<int, 3> p) {
    const auto found = index.find(p);
    if (found != index.end()) return found->second;
    Eigen::Vector3d x;
    for (int c = 0; c < 3; ++c) x[c] = size[c] * (double(p[c]) / cells[c] - 0.5);
    mesh.vertices.push_back(x);
    return index[p] = int(mesh.vertices.size()) - 1;
  };
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side = 0; side < 2; ++side) {
      Eigen::Vector3d outward = Eigen::Vector3d::Zero();
      outward[axis] = side ? 1.0 : -1.0;
      for (int i = 0; i < cells[u]; ++i)
        for (int j = 0; j < cells[v]; ++j) {
          const auto at = [&](int a, int b) {
            std::array<int, 3> p{};
            p[axis] = side ? cells[axis] : 0;
            p[u] = a;
            p[v] = b;
            return vertex(p);
          };
          addQuad(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1), outward);
        }
    }
  }
  return mesh;
}

TriangleMesh torusMesh(double majorRadius, double minorRadius, int majorSegments,
                       int minorSegments) {
  if (!(minorRadius > 0.0 && majorRadius > minorRadius))
    throw std::invalid_argument("torusMesh: need 0 < minorRadius < majorRadius");
  if (majorSegments < 3 || minorSegments < 3)
    throw std::invalid_argument("torusMesh: need at least 3 segments each way");
  const double pi = std::acos(-1.0);
  TriangleMesh mesh;
  const auto index = [&](int i, int j) {
    return (i % majorSegments) * minorSegments + j % minorSegments;
  };
  for (int i = 0; i < majorSegments; ++i) {
    const double u = 2.0 * pi * i / majorSegments;
    for (int j = 0; j < minorSegments; ++j) {
      const double v = 2.0 * pi * j / minorSegments;
      mesh.vertices.emplace_back((majorRadius + minorRadius * std::cos(v)) * std::cos(u),
                                 (majorRadius + minorRadius * std::cos(v)) * std::sin(u),
                                 minorRadius * std::sin(v));
    }
  }
  for (int i = 0; i < majorSegments; ++i)
    for (int j = 0; j < minorSegments; ++j) {
      // Outward: away from the tube's centre line, at the quad's middle.
      const double u = 2.0 * pi * (i + 0.5) / majorSegments;
      const double v = 2.0 * pi * (j + 0.5) / minorSegments;
      const Eigen::Vector3d outward(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u),
                                    std::sin(v));
      addQuad(mesh, index(i, j), index(i + 1, j), index(i + 1, j + 1), index(i, j + 1), outward);
    }
  return mesh;
}

}  // namespace spacetree::geometry
