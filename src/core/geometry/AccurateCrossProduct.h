// Cross product with every component accurate to a few ulps of itself (Kahan's FMA-compensated
// difference of products). The naive a_y b_z - a_z b_y loses all relative accuracy when the two
// products nearly cancel, which is exactly the case for the normal of a sliver triangle (aspect
// ratio 1e6: |a x b| ~ 1e-6 |a||b|): its direction would be off by ~1e-10 rad and distances to
// its plane by ~1e-10 of the edge length. With compensation the normal is as accurate as its
// input edges, so a nearly degenerate triangle behaves like the slightly perturbed exact one.
#pragma once

#include <Eigen/Core>

#include <cmath>

#include "geometry/IsaDispatch.h"

namespace spacetree::geometry {

// a*b - c*d with an error of at most ~1.5 ulp of the result (Jeannerod, Louvet, Muller 2013).
SPACETREE_INLINE_INTO_CLONES double accurateDifferenceOfProducts(double a, double b, double c, double d) {
  const double cd = c * d;
  const double roundingErrorOfCd = std::fma(-c, d, cd);
  const double abMinusCd = std::fma(a, b, -cd);
  return abMinusCd + roundingErrorOfCd;
}

SPACETREE_INLINE_INTO_CLONES Eigen::Vector3d accurateCross(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return {accurateDifferenceOfProducts(a.y(), b.z(), a.z(), b.y()),
          accurateDifferenceOfProducts(a.z(), b.x(), a.x(), b.z()),
          accurateDifferenceOfProducts(a.x(), b.y(), a.y(), b.x())};
}

}  // namespace spacetree::geometry
