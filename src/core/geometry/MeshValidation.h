// Checks that a mesh bounds a solid, so that mass properties and contacts are meaningful.
// validateMesh() checks, in this order, and throws MeshError ("<name>: <problem> ...", naming
// the first offending triangle, edge or vertex) on the first failure:
//   1. at least one triangle; every index in range;
//   2. every vertex coordinate finite (no inf / nan), and the bounding-box diagonal L (0 is
//      left to 3.) in [kMinMeshExtent, kMaxMeshExtent] = [1e-50, 1e50] (any length unit), so
//      that the squared areas (L^4) and the moments of inertia (L^5) neither overflow nor
//      underflow in double;
//   3. no zero-area triangle: |(v1 - v0) x (v2 - v0)| / 2 > areaTolerance * L^2, L the diagonal
//      of the bounding box (this also rejects triangles with a repeated vertex);
//   4. closed (watertight and manifold): every undirected edge belongs to exactly two
//      triangles ("open surface" for one, "non-manifold edge" for three or more);
//   5. consistently oriented: the two triangles of every edge traverse it in opposite
//      directions;
//   6. enclosed volume (signed, divergence theorem) > volumeTolerance * L^3;
//   7. principal moments of inertia (after 6.'s repair) those of a solid: each > 0 and
//      I1 + I2 >= I3 (within kInertiaTolerance of I3). A closed, consistently oriented surface
//      that intersects itself (a bow-tie polygon, overlapping parts of one component) can
//      violate them - the integrator would then turn with a negative moment. This is a
//      necessary condition only: self-intersections that keep the moments physical pass.
// Documented repairs (reported in MeshValidationReport), each switchable off to get an error:
//   - inward orientation: a consistently oriented closed mesh with negative signed volume is
//     turned inside out (every triangle flipped) - the usual result of a mirrored export;
//   - unreferenced vertices (e.g. OBJ texture cages) are removed and the indices renumbered.
// Several closed components are allowed (each checked as above); genus > 0 (a torus) is fine.
#pragma once

#include <cstddef>
#include <string>

#include "geometry/MeshIO.h"
#include "geometry/TriangleMesh.h"

namespace spacetree::geometry {

inline constexpr double kInertiaTolerance = 1e-9;  // relative to the largest moment
inline constexpr double kMinMeshExtent = 1e-50;
inline constexpr double kMaxMeshExtent = 1e50;

struct MeshValidationOptions {
  double areaTolerance = 1e-14;    // relative to L^2 (L: bounding-box diagonal)
  double volumeTolerance = 1e-14;  // relative to L^3
  bool repairInwardOrientation = true;
  bool removeUnreferencedVertices = true;
};

struct MeshValidationReport {
  bool flippedInwardOrientation = false;
  std::size_t removedVertices = 0;
  double signedVolumeBefore = 0.0;  // before any flip
};

// Checks (and repairs, as documented above) `mesh`; `name` (usually the file) starts every
// error message.
MeshValidationReport validateMesh(TriangleMesh& mesh, const std::string& name,
                                  const MeshValidationOptions& options = {});

// readMesh() followed by validateMesh() with the path as the name.
TriangleMesh readValidatedMesh(const std::string& path, const MeshValidationOptions& options = {},
                               MeshValidationReport* report = nullptr);

// Signed volume enclosed by the surface (positive for outward orientation): sum over the
// triangles of det(v0, v1, v2) / 6, relative to the first vertex for accuracy.
double signedVolume(const TriangleMesh& mesh);

}  // namespace spacetree::geometry
