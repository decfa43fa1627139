// One semi-smooth Newton step of the penalty kernel when the sum constraint of a triangle is
// violated with the final weight (1e12): the block of that triangle is A + rho c c^T, whose
// entries agree in their first 12 digits. Formed naively, its 2x2 determinants cancel to
// rounding noise: the step came out 4 % (here) to 30 % (triangles swapped) off in the release
// build, and as NaN (detS = 0) in -O0/-O1 builds, where 53 pairs of the adversarial sets gave a
// NaN distance. The step must match the same Newton system solved in exact arithmetic.
//
// Pair: lane "random 8907" of test_triangle_distance's sets; start: its iterate after the
// first three of four steps. Reference: the kernel's Newton system (G = J^T J / s, k, shift
// 1e-10, the active constraints of the start) built and solved in exact rational arithmetic
// (Python fractions) from the same double coordinates, rounded to double.
#include <gtest/gtest.h>

#include <cmath>

#include "geometry/PenaltyTriangleDistance.h"

using namespace spacetree::geometry;

namespace {

constexpr int kLanes = kTrianglePairBatchSize;

const double kFirst[3][3] = {{-0x1.24aafd670cd96p+8, 0x1.520c1906cb5d5p+8, 0x1.8fee0ab8d2e9dp+7},
                             {-0x1.28f61cc527804p+6, 0x1.9f773f621b404p+7, 0x1.a744112258472p+7},
                             {-0x1.586a221280a1cp+7, 0x1.37daf05a80d3p+8, 0x1.cf6dc18cedb33p+6}};
const double kSecond[3][3] = {{-0x1.ca9e3034e620cp+5, 0x1.c484601de6b3cp+8, 0x1.3cb40cd476ca1p+6},
                              {-0x1.2903a260c2c44p+7, 0x1.95b70d02f07bbp+8, 0x1.f2335200e1c62p+6},
                              {-0x1.4c67b58b4e0e1p+6, 0x1.48a8262e248e8p+8, 0x1.a53068524996fp+7}};

// The iterate after one step of weight 1e12 from `start`, in every lane.
void stepFrom(const double (&first)[3][3], const double (&second)[3][3], const double (&start)[4],
              double (&iterate)[4]) {
  TrianglePairBatch batch;
  double z[4][kLanes];
  for (int l = 0; l < kLanes; ++l) {
    for (int v = 0; v < 3; ++v)
      for (int c = 0; c < 3; ++c) {
        batch.coordinate[0][v][c][l] = first[v][c];
        batch.coordinate[1][v][c][l] = second[v][c];
      }
    for (int i = 0; i < 4; ++i) z[i][l] = start[i];
  }
  const double weight[1] = {1e12};
  PenaltyBatchResult result;
  penaltyTriangleDistanceBatchContinued(batch, weight, 1, z, PenaltyOptions(), result);
  for (int i = 0; i < 4; ++i) {
    iterate[i] = result.iterate[i][0];
    for (int l = 1; l < kLanes; ++l) EXPECT_EQ(result.iterate[i][l], iterate[i]) << "lane " << l;
  }
}

void expectNear(const double (&got)[4], const double (&want)[4]) {
  for (int i = 0; i < 4; ++i) {
    ASSERT_TRUE(std::isfinite(got[i])) << "component " << i;
    EXPECT_NEAR(got[i], want[i], 1e-9 * std::abs(want[i])) << "component " << i;
  }
}

TEST(PenaltyNewtonStep, MatchesExactArithmeticWhenTheSecondSumConstraintDominates) {
  // v1 + v2 = 1 + 1.5e-9: violated, weight 1e12 on the second triangle's block
  const double start[4] = {0.55453573890426555, 0.38871420869469026, 7.9274864450695759e-11,
                           1.0000000015088206};
  const double exact[4] = {-24.703974452608726, 29.167974943639788, 31.984970328529542,
                           -30.984970328529542};
  double got[4];
  stepFrom(kFirst, kSecond, start, got);
  expectNear(got, exact);
}

TEST(PenaltyNewtonStep, MatchesExactArithmeticWhenTheFirstSumConstraintDominates) {
  // The same pair with the triangles swapped: the first block carries the weight (det(Huu)).
  const double start[4] = {7.9274864450695759e-11, 1.0000000015088206, 0.55453573890426555,
                           0.38871420869469026};
  const double exact[4] = {31.984970328529542, -30.984970328529542, -24.703974452608726,
                           29.167974943639788};
  double got[4];
  stepFrom(kSecond, kFirst, start, got);
  expectNear(got, exact);
}

}  // namespace
