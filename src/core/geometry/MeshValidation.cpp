#include "geometry/MeshValidation.h"

#include "geometry/MassProperties.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <unordered_map>
#include <vector>

namespace spacetree::geometry {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw MeshError(name + ": " + what);
}

std::string edgeText(int a, int b) {
  return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

}  // namespace

double signedVolume(const TriangleMesh& mesh) {
  if (mesh.vertices.empty()) return 0.0;
  const Eigen::Vector3d origin = mesh.vertices.front();
  double sixVolume = 0.0;
  for (const auto& f : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[f[0]] - origin, b = mesh.vertices[f[1]] - origin,
                          c = mesh.vertices[f[2]] - origin;
    sixVolume += a.dot(b.cross(c));
  }
  return sixVolume / 6.0;
}

MeshValidationReport validateMesh(TriangleMesh& mesh, const std::string& name,
                                  const MeshValidationOptions& options) {
  MeshValidationReport report;
  if (mesh.triangles.empty()) fail(name, "mesh has no triangles");
  const int vertexCount = int(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int v : mesh.triangles[t])
      if (v < 0 || v >= vertexCount)
        fail(name, "triangle " + std::to_string(t) + " refers to vertex " + std::to_string(v) +
                       " (mesh has " + std::to_string(vertexCount) + " vertices)");

  // 2. finite coordinates (of referenced vertices; unreferenced ones are removed below)
  std::vector<char> referenced(vertexCount, 0);
  for (const auto& f : mesh.triangles)
    for (int v : f) referenced[v] = 1;
  for (int v = 0; v < vertexCount; ++v)
    if (referenced[v] && !mesh.vertices[v].allFinite())
      fail(name, "vertex " + std::to_string(v) + " has a non-finite coordinate (" +
                     std::to_string(mesh.vertices[v].x()) + ", " +
                     std::to_string(mesh.vertices[v].y()) + ", " +
                     std::to_string(mesh.vertices[v].z()) + ")");

  if (options.removeUnreferencedVertices) {
    std::vector<int> renumber(vertexCount, -1);
    std::vector<Eigen::Vector3d> kept;
    for (int v = 0; v < vertexCount; ++v)
      if (referenced[v]) {
        renumber[v] = int(kept.size());
        kept.push_back(mesh.vertices[v]);
      }
    report.removedVertices = mesh.vertices.size() - kept.size();
    if (report.removedVertices) {
      for (auto& f : mesh.triangles)
        for (int& v : f) v = renumber[v];
      mesh.vertices = std::move(kept);
    }
  }

  // 2b. the size: areas (L^2) and volumes (L^3) must be representable
  Eigen::AlignedBox3d box;
  for (const auto& f : mesh.triangles)
    for (int v : f) box.extend(mesh.vertices[v]);
  const double extent = box.diagonal().stableNorm();  // no overflow or underflow on the way
  if (!(extent <= kMaxMeshExtent) || (extent > 0.0 && extent < kMinMeshExtent)) {
    std::ostringstream text;
    text << "bounding-box diagonal " << extent << " is outside [" << kMinMeshExtent << ", "
         << kMaxMeshExtent << "] (areas, volumes or moments of inertia would overflow or "
         << "underflow in double)";
    fail(name, text.str());
  }
  const double diagonal = box.diagonal().norm();

  // 3. zero-area triangles
  const double minimumArea = options.areaTolerance * diagonal * diagonal;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const double area = 0.5 * mesh.areaVector(t).norm();
    if (!(area > minimumArea))
      fail(name, "triangle " + std::to_string(t) + " has zero area (" + std::to_string(area) +
                     ", vertices " + std::to_string(mesh.triangles[t][0]) + ", " +
                     std::to_string(mesh.triangles[t][1]) + ", " +
                     std::to_string(mesh.triangles[t][2]) + ")");
  }

  // 4./5. closed, manifold, consistently oriented: count directed edges per undirected edge.
  struct EdgeUse {
    int forward = 0;   // traversed as (min, max)
    int backward = 0;  // traversed as (max, min)
    std::size_t firstTriangle = 0;
  };
  std::unordered_map<std::uint64_t, EdgeUse> edges;
  edges.reserve(mesh.triangles.size() * 2);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int i = 0; i < 3; ++i) {
      const int a = mesh.triangles[t][i], b = mesh.triangles[t][(i + 1) % 3];
      const int lo = std::min(a, b), hi = std::max(a, b);
      auto [it, inserted] = edges.try_emplace(std::uint64_t(lo) << 32 | std::uint32_t(hi));
      if (inserted) it->second.firstTriangle = t;
      ++(a == lo ? it->second.forward : it->second.backward);
    }
  for (const auto& [key, use] : edges) {
    const int lo = int(key >> 32), hi = int(key & 0xffffffffu);
    const int uses = use.forward + use.backward;
    if (uses == 1)
      fail(name, "open surface: " + edgeText(lo, hi) + " of triangle " +
                     std::to_string(use.firstTriangle) + " belongs to one triangle only");
    if (uses > 2)
      fail(name, "non-manifold " + edgeText(lo, hi) + ": shared by " + std::to_string(uses) +
                     " triangles (first " + std::to_string(use.firstTriangle) + ")");
  }
  for (const auto& [key, use] : edges)
    if (use.forward != 1)
      fail(name, "inconsistent orientation: the two triangles of " +
                     edgeText(int(key >> 32), int(key & 0xffffffffu)) +
                     " traverse it in the same direction (first triangle " +
                     std::to_string(use.firstTriangle) + ")");

  // 6. enclosed volume and orientation
  const double volume = signedVolume(mesh);
  report.signedVolumeBefore = volume;
  const double minimumVolume = options.volumeTolerance * diagonal * diagonal * diagonal;
  if (!(std::abs(volume) > minimumVolume))
    fail(name, "closed surface encloses no volume (signed volume " + std::to_string(volume) + ")");
  if (volume < 0.0) {
    if (!options.repairInwardOrientation)
      fail(name, "inward orientation (signed volume " + std::to_string(volume) +
                     " < 0): triangles must be counter-clockwise seen from outside");
    mesh.flipOrientation();
    report.flippedInwardOrientation = true;
  }

  // 7. the moments of inertia of a solid: positive, I1 + I2 >= I3 (2 int z^2 dm >= 0)
  const Eigen::Vector3d moments = computeMassProperties(mesh).principalMomentsPerUnitDensity;
  const double slack = kInertiaTolerance * moments.cwiseAbs().maxCoeff();
  if (!moments.allFinite() || !(moments[0] > 0.0) || !(moments[0] + moments[1] >= moments[2] - slack)) {
    std::ostringstream text;
    text << "principal moments of inertia per unit density (" << moments[0] << ", " << moments[1]
         << ", " << moments[2] << ") are not those of a solid (each > 0, the two smaller summing "
         << "to at least the largest): the surface intersects itself";
    fail(name, text.str());
  }
  return report;
}

TriangleMesh readValidatedMesh(const std::string& path, const MeshValidationOptions& options,
                               MeshValidationReport* report) {
  TriangleMesh mesh = readMesh(path);
  const MeshValidationReport r = validateMesh(mesh, path, options);
  if (report) *report = r;
  return mesh;
}

}  // namespace spacetree::geometry
