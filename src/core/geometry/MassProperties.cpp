#include "geometry/MassProperties.h"

#include <Eigen/Eigenvalues>

#include <cmath>
#include <stdexcept>
#include <string>

namespace spacetree::geometry {
namespace {

// A deterministic choice among the valid principal axes (see the header): within a degenerate
// eigenspace the basis closest to the mesh axes, each distinct axis signed so that its largest
// component is positive, the last column fixing right-handedness.
Eigen::Matrix3d canonicalPrincipalAxes(const Eigen::Vector3d& moments, Eigen::Matrix3d axes) {
  const double tolerance = kDegenerateMomentTolerance * std::abs(moments[2]);
  const bool low = moments[1] - moments[0] <= tolerance;   // axes 0 and 1 share a moment
  const bool high = moments[2] - moments[1] <= tolerance;  // axes 1 and 2 share a moment
  if (low && high) return Eigen::Matrix3d::Identity();
  for (int k = 0; k < 3; ++k) {
    int largest;
    axes.col(k).cwiseAbs().maxCoeff(&largest);
    if (axes(largest, k) < 0.0) axes.col(k) *= -1.0;
  }
  if (low || high) {
    const int distinct = low ? 2 : 0;
    const int a = low ? 0 : 1, b = low ? 1 : 2;
    const Eigen::Vector3d axis = axes.col(distinct);
    // The mesh axis with the largest projection onto the plane orthogonal to the distinct axis.
    Eigen::Vector3d best = Eigen::Vector3d::Zero();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d projected =
          Eigen::Vector3d::Unit(k) - axis * axis.dot(Eigen::Vector3d::Unit(k));
      if (projected.squaredNorm() > best.squaredNorm() + 1e-12) best = projected;
    }
    axes.col(a) = best.normalized();
    axes.col(b) = axis.cross(axes.col(a)).normalized();
  }
  if (axes.determinant() < 0.0) axes.col(2) *= -1.0;
  return axes;
}

}  // namespace

MassProperties computeMassProperties(const TriangleMesh& mesh) {
  if (mesh.triangles.empty())
    throw std::invalid_argument("computeMassProperties: mesh has no triangles");
  // Reference point at the bounding-box centre: the integrals are then sums of terms of the
  // size of the body, not of its distance from the origin (no cancellation far away).
  const Eigen::Vector3d reference = mesh.boundingBox().center();
  double sixVolume = 0.0;
  Eigen::Vector3d firstMoment = Eigen::Vector3d::Zero();   // times 24
  Eigen::Matrix3d secondMoment = Eigen::Matrix3d::Zero();  // times 120
  for (const auto& f : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[f[0]] - reference;
    const Eigen::Vector3d b = mesh.vertices[f[1]] - reference;
    const Eigen::Vector3d c = mesh.vertices[f[2]] - reference;
    // Tetrahedron (0, a, b, c), signed volume det / 6:
    //   integral x dV = V (a + b + c) / 4,
    //   integral x x^T dV = V / 20 (a a^T + b b^T + c c^T + s s^T), s = a + b + c.
    const double det = a.dot(b.cross(c));
    const Eigen::Vector3d s = a + b + c;
    sixVolume += det;
    firstMoment += det * s;
    secondMoment += det * (a * a.transpose() + b * b.transpose() + c * c.transpose() +
                           s * s.transpose());
  }
  MassProperties p;
  p.volume = sixVolume / 6.0;
  if (!(p.volume > 0.0))
    throw std::invalid_argument("computeMassProperties: enclosed volume " +
                                std::to_string(p.volume) +
                                " is not positive (open or inward-oriented mesh?)");
  const Eigen::Vector3d centre = firstMoment / (24.0 * p.volume);  // relative to the reference
  p.centreOfMass = reference + centre;
  // Covariance about the centre of mass, then I = tr(C) Id - C.
  const Eigen::Matrix3d covariance =
      secondMoment / 120.0 - p.volume * centre * centre.transpose();
  p.inertiaPerUnitDensity =
      covariance.trace() * Eigen::Matrix3d::Identity() - covariance;
  p.inertiaPerUnitDensity = 0.5 * (p.inertiaPerUnitDensity + p.inertiaPerUnitDensity.transpose());

  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(p.inertiaPerUnitDensity);
  p.principalMomentsPerUnitDensity = solver.eigenvalues();
  p.principalAxes = canonicalPrincipalAxes(solver.eigenvalues(), solver.eigenvectors());
  return p;
}

}  // namespace spacetree::geometry
