// The template of a rigid triangulated particle: its surface in the principal body frame
// (centre of mass at the origin, axes along the principal axes of inertia), plus what the
// contact search and the integrator need per shape, computed once.
//
// Frames: x_mesh = meshRotation * x_body + centreOfMassInMesh maps the body frame back to the
// frame of the mesh it was built from (e.g. the STL's coordinates). A particle's pose
// (position p, orientation q, body -> world) places the body: x_world = q * x_body + p.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <vector>

#include "geometry/MassProperties.h"
#include "geometry/Triangle.h"
#include "geometry/TriangleBvh.h"
#include "geometry/TriangleMesh.h"

namespace spacetree::geometry {

struct RigidShape {
  TriangleMesh bodyMesh;                 // in the principal body frame
  std::vector<Triangle> bodyTriangles;   // bodyMesh.triangle(t) for every t (kernel input)
  // Bounding sphere of each body triangle (centroid, largest centroid-vertex distance): the
  // triangle-pair pruning of the contact search.
  std::vector<Eigen::Vector3d> triangleCentres;
  std::vector<double> triangleRadii;
  // Hierarchy over those spheres: the contact search finds the triangles near the other body
  // in O(log n + k) (TriangleBvh.h).
  TriangleBvh triangleIndex;

  // Adjacency: edgeApex[t][k] is the vertex opposite edge (v_k, v_{k+1}) of triangle t in the
  // neighbouring triangle across that edge (-1 if none: a boundary or non-manifold edge);
  // the neighbours of vertex v are vertexNeighbours[vertexNeighbourOffsets[v] ..
  // vertexNeighbourOffsets[v + 1]). Used by the contact search to drop triangle-pair contacts
  // that are not local minima of the surface distance (MeshContact.h).
  std::vector<std::array<int, 3>> edgeApex;
  std::vector<int> vertexNeighbourOffsets;
  std::vector<int> vertexNeighbours;

  double boundingRadius = 0.0;       // max |vertex| (about the centre of mass)
  // Axis-aligned box of the vertices in the body frame (an oriented box in the world): the
  // contact search drops the other body's triangles that stay 2 eps away from it.
  Eigen::Vector3d boundingBoxLow = Eigen::Vector3d::Zero();
  Eigen::Vector3d boundingBoxHigh = Eigen::Vector3d::Zero();
  double minimumEdgeLength = 0.0;    // the contact de-duplication length of the paper (§3)
  double volume = 0.0;
  Eigen::Vector3d principalInertiaPerUnitDensity = Eigen::Vector3d::Zero();  // ascending

  Eigen::Matrix3d meshRotation = Eigen::Matrix3d::Identity();  // principal axes in mesh axes
  Eigen::Vector3d centreOfMassInMesh = Eigen::Vector3d::Zero();

  double mass(double density) const { return density * volume; }
  Eigen::Vector3d principalInertia(double density) const {
    return density * principalInertiaPerUnitDensity;
  }
  Eigen::Vector3d principalInertiaForMass(double mass) const {
    return (mass / volume) * principalInertiaPerUnitDensity;
  }
  std::size_t triangleCount() const { return bodyTriangles.size(); }

  // Orientation (body -> world) a particle needs so that its surface coincides with the
  // source mesh placed with `meshOrientation` (mesh -> world): meshOrientation * meshRotation.
  Eigen::Quaterniond bodyOrientationFor(
      const Eigen::Quaterniond& meshOrientation = Eigen::Quaterniond::Identity()) const;

  // From a closed, outward-oriented mesh (run validateMesh() first); throws
  // std::invalid_argument when the mesh encloses no positive volume.
  static RigidShape fromMesh(const TriangleMesh& mesh);
  // A surface without mass (a wall: open, any orientation, shared vertices by index): body
  // frame = mesh axes with the origin at the centre of the mesh's bounding box
  // (centreOfMassInMesh, meshRotation identity); volume and inertia 0; an edge that is not
  // shared by exactly two triangles has no neighbour (edgeApex -1). Throws
  // std::invalid_argument for a mesh without triangles.
  static RigidShape fromSurface(const TriangleMesh& mesh);
};

}  // namespace spacetree::geometry
