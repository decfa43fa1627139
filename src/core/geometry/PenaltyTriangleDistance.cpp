#include "geometry/PenaltyTriangleDistance.h"

#include <cmath>
#include <stdexcept>
#include <vector>

#include "geometry/IsaDispatch.h"
#include "geometry/TrianglePairSources.h"

// Build note: the loops below are vectorised when compiled with -O3 (or -O2) plus
// -fopenmp-simd (honours `omp simd`), -fno-math-errno (sqrt without errno) and
// -fno-trapping-math (if-conversion of the admissibility clamps); CMake sets these for the
// geometry sources. None of them changes a result; without them the kernel stays correct but
// partly scalar.

namespace spacetree::geometry {
namespace {

constexpr int kLanes = kTrianglePairBatchSize;

// By-value min/max: std::min/max return references, which on array elements turn into
// address selects that stop the vectoriser ("control flow in loop").
SPACETREE_INLINE_INTO_CLONES double smaller(double a, double b) { return a < b ? a : b; }
SPACETREE_INLINE_INTO_CLONES double larger(double a, double b) { return a > b ? a : b; }

// Plain 3-vectors and the local geometry of one lane for the final (certification) loop: small
// value types that the compiler keeps in registers, so the loop vectorises like scalar code.
struct Vec3 {
  double x, y, z;
};
SPACETREE_INLINE_INTO_CLONES Vec3 operator+(Vec3 p, Vec3 q) { return {p.x + q.x, p.y + q.y, p.z + q.z}; }
SPACETREE_INLINE_INTO_CLONES Vec3 operator-(Vec3 p, Vec3 q) { return {p.x - q.x, p.y - q.y, p.z - q.z}; }
SPACETREE_INLINE_INTO_CLONES Vec3 operator*(Vec3 p, double s) { return {p.x * s, p.y * s, p.z * s}; }
SPACETREE_INLINE_INTO_CLONES double dot(Vec3 p, Vec3 q) { return p.x * q.x + p.y * q.y + p.z * q.z; }
SPACETREE_INLINE_INTO_CLONES Vec3 cross(Vec3 p, Vec3 q) {
  return {p.y * q.z - p.z * q.y, p.z * q.x - p.x * q.z, p.x * q.y - p.y * q.x};
}
SPACETREE_INLINE_INTO_CLONES Vec3 select(bool condition, Vec3 p, Vec3 q) {
  return {condition ? p.x : q.x, condition ? p.y : q.y, condition ? p.z : q.z};
}

// A pair relative to the first triangle's vertex 0: A = {0, a1, a2}, B = b0 + {0, b1, b2}.
struct LocalPair {
  Vec3 a1, a2, b0, b1, b2;
};

// Separating-axis bound along direction m (any length): every point of A lies within
// [minA, maxA] along m / |m|, every point of B within [minB, maxB], so the triangles are at
// least max(minA - maxB, minB - maxA) apart. A zero direction (degenerate triangle, parallel
// edges, coincident points) gives 0.
SPACETREE_INLINE_INTO_CLONES double separationAlong(Vec3 m, LocalPair p) {
  const double norm = std::sqrt(dot(m, m));
  const double inverse = (norm > 0.0 ? 1.0 : 0.0) / larger(norm, 1e-300);
  const double pa1 = dot(m, p.a1) * inverse, pa2 = dot(m, p.a2) * inverse;
  const double pb0 = dot(m, p.b0) * inverse;
  const double pb1 = pb0 + dot(m, p.b1) * inverse, pb2 = pb0 + dot(m, p.b2) * inverse;
  const double minA = smaller(0.0, smaller(pa1, pa2)), maxA = larger(0.0, larger(pa1, pa2));
  const double minB = smaller(pb0, smaller(pb1, pb2)), maxB = larger(pb0, larger(pb1, pb2));
  return larger(minA - maxB, minB - maxA);
}

// The edge of a triangle (spanned by e1, e2 from vertex 0) that the point with barycentric
// parameters (s1, s2) lies on or nearest to: the constraint with the smallest slack among
// s1 >= 0 (edge e2), s2 >= 0 (edge e1) and s1 + s2 <= 1 (edge e2 - e1).
SPACETREE_INLINE_INTO_CLONES Vec3 contactEdge(double s1, double s2, Vec3 e1, Vec3 e2) {
  const double s3 = 1.0 - s1 - s2;
  return select(s1 <= s2 && s1 <= s3, e2, select(s2 <= s3, e1, e2 - e1));
}

// Penalty weight of Newton step `step` of `steps`, in units of the mean squared edge length: a
// geometric ramp from kFirstPenaltyWeight to kFinalPenaltyWeight (continuation, see the
// header). Measured on random and sphere-contact pairs, the ramp's end points hardly change
// how many pairs converge; the final weight sets the accuracy (violation ~ 1 / weight).
constexpr double kFirstPenaltyWeight = 1.0;
constexpr double kFinalPenaltyWeight = 1e12;

// weights[steps][step] for every admissible step count, computed once (thread-safe static).
struct PenaltyWeightTable {
  double weights[kMaxNewtonIterations + 1][kMaxNewtonIterations];
  PenaltyWeightTable() {
    for (int steps = 1; steps <= kMaxNewtonIterations; ++steps)
      for (int step = 0; step < steps; ++step) {
        const double t = steps > 1 ? double(step) / double(steps - 1) : 1.0;
        weights[steps][step] =
            kFirstPenaltyWeight * std::pow(kFinalPenaltyWeight / kFirstPenaltyWeight, t);
      }
  }
};

const double* penaltyWeights(int steps) {
  static const PenaltyWeightTable table;
  return table.weights[steps];
}

// Levenberg-Marquardt shift of the Newton matrix, in units of the mean squared edge length:
// |x - y|^2 alone is only positive semi-definite in the four parameters (rank 3, or 2 for
// parallel triangles). The shift changes the steps, not the fixed point (gradient zero).
constexpr double kNewtonShift = 1e-10;

// The per-lane arrays of the Newton iteration (see penaltyTriangleDistanceBatch).
struct NewtonArrays {
  const double *g11, *g12, *g13, *g14, *g22, *g23, *g24, *g33, *g34, *g44;
  const double *k1, *k2, *k3, *k4;
  const double *c11, *c12, *c13, *c21, *c22, *c23, *c31, *c32, *c33;
  double *u1, *u2, *v1, *v2;
};

// Steps with a weight up to this solve for the new iterate directly (see newtonStep).
// Measured on the benchmark's sphere pairs: up to 1e6 (the first four of eight steps) the
// fallback rate does not grow; with the fifth step (7e6) it does (1.2 -> 1.9 % at 12 triangles).
constexpr double kDirectStepWeightLimit = 1e6;

// One semi-smooth Newton step with weight rho on all lanes. On the current piece of the
// (piecewise quadratic) objective the gradient is r = (H - shift I) z + k - rho c, c = 1 for
// the components of a violated sum constraint, so the step z - H^-1 r equals
// H^-1 (shift z - k + rho c): `direct` solves for that, without the gradient (16 multiply-adds
// fewer). Its rounding error is ~eps rho |z| instead of ~eps rho |dz| (the 2x2 determinants
// cancel O(rho^2) terms), so it serves the steps with rho <= kDirectStepWeightLimit; the later
// steps, which polish the result, take the incremental form.
template <bool direct>
SPACETREE_INLINE_INTO_CLONES void newtonStep(const double rho, const NewtonArrays& a) {
  const double* __restrict g11 = a.g11; const double* __restrict g12 = a.g12;
  const double* __restrict g13 = a.g13; const double* __restrict g14 = a.g14;
  const double* __restrict g22 = a.g22; const double* __restrict g23 = a.g23;
  const double* __restrict g24 = a.g24; const double* __restrict g33 = a.g33;
  const double* __restrict g34 = a.g34; const double* __restrict g44 = a.g44;
  const double* __restrict k1 = a.k1; const double* __restrict k2 = a.k2;
  const double* __restrict k3 = a.k3; const double* __restrict k4 = a.k4;
  const double* __restrict c11 = a.c11; const double* __restrict c12 = a.c12;
  const double* __restrict c13 = a.c13; const double* __restrict c21 = a.c21;
  const double* __restrict c22 = a.c22; const double* __restrict c23 = a.c23;
  const double* __restrict c31 = a.c31; const double* __restrict c32 = a.c32;
  const double* __restrict c33 = a.c33;
  double* __restrict u1 = a.u1; double* __restrict u2 = a.u2;
  double* __restrict v1 = a.v1; double* __restrict v2 = a.v2;
#pragma omp simd
  for (int l = 0; l < kLanes; ++l) {
    const double z1 = u1[l], z2 = u2[l], z3 = v1[l], z4 = v2[l];
    const double excessU = z1 + z2 - 1.0;
    const double excessV = z3 + z4 - 1.0;
    const double pu = excessU > 0.0 ? rho : 0.0;
    const double pv = excessV > 0.0 ? rho : 0.0;
    double r1, r2, r3, r4;
    if constexpr (direct) {
      r1 = kNewtonShift * z1 - k1[l] + pu;
      r2 = kNewtonShift * z2 - k2[l] + pu;
      r3 = kNewtonShift * z3 - k3[l] + pv;
      r4 = kNewtonShift * z4 - k4[l] + pv;
    } else {
      // Gradient of 1/2 |x - y|^2 + rho/2 sum_i max(0, g_i(z))^2 (constraints g_i <= 0).
      r1 = g11[l] * z1 + g12[l] * z2 + g13[l] * z3 + g14[l] * z4 + k1[l] +
           rho * (smaller(z1, 0.0) + larger(excessU, 0.0));
      r2 = g12[l] * z1 + g22[l] * z2 + g23[l] * z3 + g24[l] * z4 + k2[l] +
           rho * (smaller(z2, 0.0) + larger(excessU, 0.0));
      r3 = g13[l] * z1 + g23[l] * z2 + g33[l] * z3 + g34[l] * z4 + k3[l] +
           rho * (smaller(z3, 0.0) + larger(excessV, 0.0));
      r4 = g14[l] * z1 + g24[l] * z2 + g34[l] * z3 + g44[l] * z4 + k4[l] +
           rho * (smaller(z4, 0.0) + larger(excessV, 0.0));
    }
    // Generalised Hessian: each violated constraint adds rho grad g_i grad g_i^T. Per block it
    // is A + p c c^T, c = (1, 1): A = G + shift + rho for each negative parameter (diagonal),
    // p = rho when the sum constraint is violated. The rank-one part is kept apart: with p =
    // 1e12 the entries of A + p c c^T agree in their first 12 digits, and a 2x2 determinant or
    // adjugate product formed from them cancels to rounding noise (0, hence inf and NaN, or a
    // wrong finite step, depending on how the compiler contracts the products). The matrix
    // determinant lemma keeps it out: det(A + p c c^T) = det(A) + p c^T adj(A) c, and
    // adj(A + p c c^T) = adj(A) + p adj(c c^T), adj(c c^T) = [[1, -1], [-1, 1]].
    const double a11 = g11[l] + (z1 < 0.0 ? rho : 0.0) + kNewtonShift;
    const double a22 = g22[l] + (z2 < 0.0 ? rho : 0.0) + kNewtonShift;
    const double a33 = g33[l] + (z3 < 0.0 ? rho : 0.0) + kNewtonShift;
    const double a44 = g44[l] + (z4 < 0.0 ? rho : 0.0) + kNewtonShift;
    const double a12 = g12[l], a34 = g34[l];
    const double h11 = a11 + pu, h22 = a22 + pu, h12 = a12 + pu;
    const double h13 = g13[l], h14 = g14[l], h23 = g23[l], h24 = g24[l];
    // H dz = r by 2x2 blocks (u, v), written with adjugates so that the step's dependency
    // chain holds one division instead of the four of an LDL^T solve:
    //   S = det(Huu) Hvv - Huv^T adj(Huu) Huv = M + det(Huu) pv c c^T   (det(Huu) times the
    //       Schur complement; the quadratic form Huv^T adj(Huu) Huv from the constant products
    //       c.. of Huv),
    //   dz_v = adj(S) (det(Huu) r_v - Huv^T adj(Huu) r_u) / det(S),
    //   dz_u = adj(Huu) (r_u - Huv dz_v) / det(Huu).
    const double detUU = (a11 * a22 - a12 * a12) + pu * (a11 + a22 - 2.0 * a12);
    const double m33 = detUU * a33 - (h22 * c11[l] + h12 * c12[l] + h11 * c13[l]);
    const double m34 = detUU * a34 - (h22 * c21[l] + h12 * c22[l] + h11 * c23[l]);
    const double m44 = detUU * a44 - (h22 * c31[l] + h12 * c32[l] + h11 * c33[l]);
    const double alpha = detUU * pv;
    const double ar1 = (a22 * r1 - a12 * r2) + pu * (r1 - r2);
    const double ar2 = (a11 * r2 - a12 * r1) + pu * (r2 - r1);
    const double rs3 = detUU * r3 - (h13 * ar1 + h23 * ar2);
    const double rs4 = detUU * r4 - (h14 * ar1 + h24 * ar2);
    // One division for both determinants (a division costs as much as a dozen FMAs and
    // sits on the step's dependency chain); the product stays far inside double range
    // (entries are O(rho) <= 1e12 in edge-length units: |detUU * detS| < 1e100).
    const double detS = (m33 * m44 - m34 * m34) + alpha * (m33 + m44 - 2.0 * m34);
    const double inverseProduct = 1.0 / (detUU * detS);
    const double inverseDetS = detUU * inverseProduct;
    const double inverseDetUU = detS * inverseProduct;
    const double dz3 = ((m44 * rs3 - m34 * rs4) + alpha * (rs3 - rs4)) * inverseDetS;
    const double dz4 = ((m33 * rs4 - m34 * rs3) + alpha * (rs4 - rs3)) * inverseDetS;
    const double t1 = r1 - h13 * dz3 - h14 * dz4, t2 = r2 - h23 * dz3 - h24 * dz4;
    const double dz1 = ((a22 * t1 - a12 * t2) + pu * (t1 - t2)) * inverseDetUU;
    const double dz2 = ((a11 * t2 - a12 * t1) + pu * (t2 - t1)) * inverseDetUU;
    if constexpr (direct) {
      u1[l] = dz1;
      u2[l] = dz2;
      v1[l] = dz3;
      v2[l] = dz4;
    } else {
      u1[l] = z1 - dz1;
      u2[l] = z2 - dz2;
      v1[l] = z3 - dz3;
      v2[l] = z4 - dz4;
    }
  }
}

}  // namespace

// The kernel body: `steps` Newton steps with weights[0, steps) from `start` (the centroids when
// null), then the admissible points and their bounds.
SPACETREE_INLINE_INTO_CLONES void runPenaltyBatch(const TrianglePairBatch& batch,
                                                  const double* weights, const int steps,
                                                  const double (*start)[kLanes],
                                                  const PenaltyOptions& options,
                                                  PenaltyBatchResult& result) {

  const auto& P = batch.coordinate;
  // Geometry relative to the first triangle's vertex 0: a1, a2 edges of A, b0 offset of B,
  // b1, b2 edges of B. With J = [a1 a2 -b1 -b2], x - y = J z - b0, and the objective's
  // Hessian G = J^T J (10 distinct entries) and linear term k = -J^T b0 are constant.
  alignas(64) double a1[3][kLanes], a2[3][kLanes], b0[3][kLanes], b1[3][kLanes], b2[3][kLanes];
  alignas(64) double g11[kLanes], g12[kLanes], g13[kLanes], g14[kLanes], g22[kLanes],
      g23[kLanes], g24[kLanes], g33[kLanes], g34[kLanes], g44[kLanes];
  alignas(64) double k1[kLanes], k2[kLanes], k3[kLanes], k4[kLanes];
  alignas(64) double u1[kLanes], u2[kLanes], v1[kLanes], v2[kLanes];
  alignas(64) double longestSquared[kLanes];

#pragma omp simd
  for (int l = 0; l < kLanes; ++l) {
    // Axes written out: an inner loop over them is not unrolled at -O2 and blocks the
    // vectoriser there.
    a1[0][l] = P[0][1][0][l] - P[0][0][0][l];
    a1[1][l] = P[0][1][1][l] - P[0][0][1][l];
    a1[2][l] = P[0][1][2][l] - P[0][0][2][l];
    a2[0][l] = P[0][2][0][l] - P[0][0][0][l];
    a2[1][l] = P[0][2][1][l] - P[0][0][1][l];
    a2[2][l] = P[0][2][2][l] - P[0][0][2][l];
    b0[0][l] = P[1][0][0][l] - P[0][0][0][l];
    b0[1][l] = P[1][0][1][l] - P[0][0][1][l];
    b0[2][l] = P[1][0][2][l] - P[0][0][2][l];
    b1[0][l] = P[1][1][0][l] - P[1][0][0][l];
    b1[1][l] = P[1][1][1][l] - P[1][0][1][l];
    b1[2][l] = P[1][1][2][l] - P[1][0][2][l];
    b2[0][l] = P[1][2][0][l] - P[1][0][0][l];
    b2[1][l] = P[1][2][1][l] - P[1][0][1][l];
    b2[2][l] = P[1][2][2][l] - P[1][0][2][l];
    const auto dot = [l](const double (&x)[3][kLanes], const double (&y)[3][kLanes]) {
      return x[0][l] * y[0][l] + x[1][l] * y[1][l] + x[2][l] * y[2][l];
    };
    // Work in units of the mean squared edge length (the minimiser z does not change), so that
    // the penalty weights are plain numbers and the block determinants below stay far from
    // overflow whatever the particle size. The floor keeps a pair of points finite.
    const double inverseScale =
        1.0 / larger(0.25 * (dot(a1, a1) + dot(a2, a2) + dot(b1, b1) + dot(b2, b2)), 1e-300);
    // Longest edge squared (the pair's length scale h), from the squared edges at hand.
    const double a3x = a2[0][l] - a1[0][l], a3y = a2[1][l] - a1[1][l], a3z = a2[2][l] - a1[2][l];
    const double b3x = b2[0][l] - b1[0][l], b3y = b2[1][l] - b1[1][l], b3z = b2[2][l] - b1[2][l];
    const double longestA =
        larger(larger(dot(a1, a1), dot(a2, a2)), a3x * a3x + a3y * a3y + a3z * a3z);
    const double longestB =
        larger(larger(dot(b1, b1), dot(b2, b2)), b3x * b3x + b3y * b3y + b3z * b3z);
    result.longestSquaredEdge[0][l] = longestA;
    result.longestSquaredEdge[1][l] = longestB;
    longestSquared[l] = larger(longestA, longestB);
    g11[l] = dot(a1, a1) * inverseScale;
    g12[l] = dot(a1, a2) * inverseScale;
    g13[l] = -dot(a1, b1) * inverseScale;
    g14[l] = -dot(a1, b2) * inverseScale;
    g22[l] = dot(a2, a2) * inverseScale;
    g23[l] = -dot(a2, b1) * inverseScale;
    g24[l] = -dot(a2, b2) * inverseScale;
    g33[l] = dot(b1, b1) * inverseScale;
    g34[l] = dot(b1, b2) * inverseScale;
    g44[l] = dot(b2, b2) * inverseScale;
    k1[l] = -dot(a1, b0) * inverseScale;
    k2[l] = -dot(a2, b0) * inverseScale;
    k3[l] = dot(b1, b0) * inverseScale;
    k4[l] = dot(b2, b0) * inverseScale;
    // Start at the centroids. (Projecting each centroid onto the other triangle was tried: it
    // saves no Newton step on random or sphere-contact pairs.)
    u1[l] = u2[l] = v1[l] = v2[l] = 1.0 / 3.0;
  }
  if (start) {
#pragma omp simd
    for (int l = 0; l < kLanes; ++l) {
      u1[l] = start[0][l];
      u2[l] = start[1][l];
      v1[l] = start[2][l];
      v2[l] = start[3][l];
    }
  }

  // Constant products of the off-diagonal block Huv = G_uv (the penalty only touches the
  // diagonal blocks): with them the Schur complement costs 12 multiply-adds per step, not 17.
  alignas(64) double c11[kLanes], c12[kLanes], c13[kLanes], c21[kLanes], c22[kLanes],
      c23[kLanes], c31[kLanes], c32[kLanes], c33[kLanes];
#pragma omp simd
  for (int l = 0; l < kLanes; ++l) {
    c11[l] = g13[l] * g13[l];
    c12[l] = -2.0 * (g13[l] * g23[l]);
    c13[l] = g23[l] * g23[l];
    c21[l] = g13[l] * g14[l];
    c22[l] = -(g13[l] * g24[l] + g23[l] * g14[l]);
    c23[l] = g23[l] * g24[l];
    c31[l] = g14[l] * g14[l];
    c32[l] = -2.0 * (g14[l] * g24[l]);
    c33[l] = g24[l] * g24[l];
  }
  const NewtonArrays arrays{g11, g12, g13, g14, g22, g23, g24, g33, g34, g44, k1, k2, k3, k4,
                            c11, c12, c13, c21, c22, c23, c31, c32, c33, u1, u2, v1, v2};
  for (int step = 0; step < steps; ++step) {
    if (weights[step] <= kDirectStepWeightLimit)
      newtonStep<true>(weights[step], arrays);
    else
      newtonStep<false>(weights[step], arrays);
  }

  // Not `omp simd` here: it would privatise the small structs of the loop body into per-lane
  // arrays and then fail on the scattered stores; the plain loops vectorise (-O2 and -O3).
  //
  // Separating-axis lower bounds (separationAlong). The direction of the two points, w, is
  // exact at the minimiser, but for nearly touching pairs it is only as accurate as
  // eps h / |w|, and so is its bound (error ~ eps h^2 / d). The contact features give
  // directions that do not degrade: the face normals (vertex-face contact) and the cross
  // product of the two edges the points lie on (edge-edge contact; the edge of a triangle is
  // the one whose barycentric constraint has the smallest slack). Every bound is rigorous for
  // its own direction, so the largest is taken. The w bound comes first; only when it leaves
  // a gap above options.tightGap (relative) + options.tightGapPerLength * h in some lane of
  // the batch are the three feature bounds computed (for every lane): pairs farther apart
  // than ~1e-3 h - most of a particle pair's - are certified by the w bound alone.
  const double tightGap = options.tightGap, tightGapPerLength = options.tightGapPerLength;
  int uncertain = 0;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
  for (int l = 0; l < kLanes; ++l) {
    // The iterate itself, for a continuation (penaltyTriangleDistanceBatchContinued).
    result.iterate[0][l] = u1[l];
    result.iterate[1][l] = u2[l];
    result.iterate[2][l] = v1[l];
    result.iterate[3][l] = v2[l];
    // Admissible parameters: clamp to the quadrant, then scale back into the simplex.
    double z1 = larger(u1[l], 0.0), z2 = larger(u2[l], 0.0);
    double z3 = larger(v1[l], 0.0), z4 = larger(v2[l], 0.0);
    const double shrinkU = 1.0 / larger(z1 + z2, 1.0);
    const double shrinkV = 1.0 / larger(z3 + z4, 1.0);
    z1 *= shrinkU;
    z2 *= shrinkU;
    z3 *= shrinkV;
    z4 *= shrinkV;
    u1[l] = z1;
    u2[l] = z2;
    v1[l] = z3;
    v2[l] = z4;
    const LocalPair pair{{a1[0][l], a1[1][l], a1[2][l]}, {a2[0][l], a2[1][l], a2[2][l]},
                         {b0[0][l], b0[1][l], b0[2][l]}, {b1[0][l], b1[1][l], b1[2][l]},
                         {b2[0][l], b2[1][l], b2[2][l]}};
    const Vec3 x = pair.a1 * z1 + pair.a2 * z2;
    const Vec3 y = pair.b0 + pair.b1 * z3 + pair.b2 * z4;
    const Vec3 w = x - y;
    const double distance = std::sqrt(dot(w, w));
    const double lowerBound = larger(separationAlong(w, pair), 0.0);
    const double longest = std::sqrt(longestSquared[l]);
    // Written so that a NaN counts as uncertain.
    uncertain |= !(distance - lowerBound <= tightGap * distance + tightGapPerLength * longest);
    result.distance[l] = distance;
    result.lowerBound[l] = lowerBound;
    result.lengthScale[l] = longest;
    result.pointOnFirst[0][l] = P[0][0][0][l] + x.x;
    result.pointOnFirst[1][l] = P[0][0][1][l] + x.y;
    result.pointOnFirst[2][l] = P[0][0][2][l] + x.z;
    result.pointOnSecond[0][l] = P[0][0][0][l] + y.x;
    result.pointOnSecond[1][l] = P[0][0][1][l] + y.y;
    result.pointOnSecond[2][l] = P[0][0][2][l] + y.z;
  }
  if (!uncertain) return;
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC ivdep
#endif
  for (int l = 0; l < kLanes; ++l) {
    const LocalPair pair{{a1[0][l], a1[1][l], a1[2][l]}, {a2[0][l], a2[1][l], a2[2][l]},
                         {b0[0][l], b0[1][l], b0[2][l]}, {b1[0][l], b1[1][l], b1[2][l]},
                         {b2[0][l], b2[1][l], b2[2][l]}};
    const Vec3 edgeA = contactEdge(u1[l], u2[l], pair.a1, pair.a2);
    const Vec3 edgeB = contactEdge(v1[l], v2[l], pair.b1, pair.b2);
    const double featureBound =
        larger(separationAlong(cross(edgeA, edgeB), pair),
               larger(separationAlong(cross(pair.a1, pair.a2), pair),
                      separationAlong(cross(pair.b1, pair.b2), pair)));
    result.lowerBound[l] = larger(result.lowerBound[l], featureBound);
  }
}

SPACETREE_DISPATCH_BY_ISA
void penaltyTriangleDistanceBatch(const TrianglePairBatch& batch, const PenaltyOptions& options,
                                  PenaltyBatchResult& result) {
  const int steps = options.newtonIterations;
  if (steps < 1 || steps > kMaxNewtonIterations)
    throw std::invalid_argument("penaltyTriangleDistanceBatch: newtonIterations out of range");
  runPenaltyBatch(batch, penaltyWeights(steps), steps, nullptr, options, result);
}

SPACETREE_DISPATCH_BY_ISA
void penaltyTriangleDistanceBatchContinued(const TrianglePairBatch& batch, const double* weights,
                                           int steps,
                                           const double (*start)[kTrianglePairBatchSize],
                                           const PenaltyOptions& options,
                                           PenaltyBatchResult& result) {
  if (steps < 1 || steps > kMaxNewtonIterations)
    throw std::invalid_argument("penaltyTriangleDistanceBatchContinued: steps out of range");
  runPenaltyBatch(batch, weights, steps, start, options, result);
}

const double* penaltyWeightSchedule(int steps) {
  if (steps < 1 || steps > kMaxNewtonIterations)
    throw std::invalid_argument("penaltyWeightSchedule: steps out of range");
  return penaltyWeights(steps);
}

namespace {

template <class PairSource>
SPACETREE_INLINE_INTO_CLONES void penaltyDistancesOf(const PairSource& pairs, const PenaltyOptions& options,
                        TriangleDistanceResult* results) {
  TrianglePairBatch batch;
  PenaltyBatchResult batchResult;
  for (std::size_t begin = 0; begin < pairs.count(); begin += kTrianglePairBatchSize) {
    const int lanes = pairs.loadBatch(batch, begin);
    penaltyTriangleDistanceBatch(batch, options, batchResult);
    for (int l = 0; l < lanes; ++l) results[begin + std::size_t(l)] = batchResult.lane(l);
  }
}

// The batching loop compiled per instruction set like the kernel (vectorised loads).
SPACETREE_DISPATCH_BY_ISA
void penaltyDistancesOfPackedAllPairs(const PackedAllPairs& pairs, const PenaltyOptions& options,
                                      TriangleDistanceResult* results) {
  penaltyDistancesOf(pairs, options, results);
}

}  // namespace

void penaltyTriangleDistances(const Triangle* first, const Triangle* second, std::size_t count,
                              const PenaltyOptions& options, TriangleDistanceResult* results) {
  penaltyDistancesOf(ElementwisePairs{first, second, count}, options, results);
}

void penaltyTriangleDistances(const Triangle& first, const Triangle* second, std::size_t count,
                              const PenaltyOptions& options, TriangleDistanceResult* results) {
  penaltyDistancesOf(OneAgainstMany{&first, second, count}, options, results);
}

void penaltyTriangleDistancesOfAllPairs(const Triangle* first, std::size_t firstCount,
                                        const Triangle* second, std::size_t secondCount,
                                        const PenaltyOptions& options,
                                        TriangleDistanceResult* results) {
  if (firstCount == 0 || secondCount == 0) return;
  thread_local std::vector<double> buffer;
  buffer.resize(9 * PackedAllPairs::strideFor(secondCount));
  PackedAllPairs::pack(second, secondCount, buffer.data());
  penaltyDistancesOfPackedAllPairs(PackedAllPairs{first, firstCount, second, secondCount,
                                                  buffer.data(),
                                                  PackedAllPairs::strideFor(secondCount)},
                                   options, results);
}

}  // namespace spacetree::geometry
