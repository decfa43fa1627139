// Prescribed motion of obstacles (PrescribedMotion.h): the pose after whole turns is the start
// pose, a quarter turn rotates by 90 degrees, the angle follows omega t over 10^4 turns, the
// velocity field is the time derivative of the material points' trajectories (finite
// differences), the axis translates with the velocity; a fixed RigidBody carries the prescribed
// angular velocity into its point velocities.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dynamics/PrescribedMotion.h"
#include "dynamics/RigidBody.h"

using namespace spacetree::dynamics;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

const Vector3d kStart(1.5, -0.5, 0.25);
const Quaterniond kStartQ = Quaterniond(0.9, 0.1, -0.3, 0.2).normalized();

TEST(PrescribedMotion, WholeTurnsReturnAndAQuarterTurnRotates) {
  const double omega = 3.7;
  const PrescribedMotion m = PrescribedMotion::make(Vector3d::Zero(), Vector3d(1, 2, 0), Vector3d(0, 0, 2), omega);
  EXPECT_EQ(m.axis, Vector3d::UnitZ());
  Vector3d p;
  Quaterniond q;
  m.poseAt(kStart, kStartQ, 10 * 2 * M_PI / omega, p, q);
  EXPECT_LT((p - kStart).norm(), 1e-12);
  EXPECT_LT(std::abs(std::abs(q.dot(kStartQ)) - 1.0), 1e-14);
  m.poseAt(kStart, kStartQ, 0.25 * 2 * M_PI / omega, p, q);
  // (1.5, -0.5) - (1, 2) = (0.5, -2.5) turned by 90 degrees: (2.5, 0.5)
  EXPECT_LT((p - Vector3d(3.5, 2.5, 0.25)).norm(), 1e-12);
  const Vector3d bodyAxis(0.3, 0.4, -0.2);
  EXPECT_LT((q * bodyAxis - Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ()) * (kStartQ * bodyAxis)).norm(), 1e-12);
}

TEST(PrescribedMotion, AngleFollowsOmegaTimesTOverManyTurns) {
  const double omega = 2 * M_PI / 0.3;  // period 0.3 s
  const PrescribedMotion m = PrescribedMotion::make(Vector3d::Zero(), Vector3d::Zero(), Vector3d::UnitX(), omega);
  double worst = 0.0;
  for (int turn = 1; turn <= 10000; turn *= 10)
    for (double fraction : {0.0, 0.125, 0.5, 0.9}) {
      const double t = (turn + fraction) * 0.3;
      const double expected = 2 * M_PI * fraction;
      double a = m.angleAt(t);
      if (a > M_PI && expected == 0.0) a -= 2 * M_PI;  // just below a whole turn
      worst = std::max(worst, std::abs(a - expected));
    }
  EXPECT_LT(worst, 1e-9);  // 10^4 turns: omega t rounded to ~1e-11 rad
  // negative angular speed turns the other way
  const PrescribedMotion back = PrescribedMotion::make(Vector3d::Zero(), Vector3d::Zero(), Vector3d::UnitX(), -omega);
  EXPECT_NEAR(back.angleAt(0.3 / 4), 1.5 * M_PI, 1e-12);
}

TEST(PrescribedMotion, VelocityIsTheDerivativeOfTheTrajectories) {
  const PrescribedMotion m = PrescribedMotion::make(Vector3d(0.2, -0.1, 0.05), Vector3d(0.3, 0.1, -0.2),
                                                    Vector3d(1, 1, 0.5), 1.3);
  const Vector3d bodyPoint(0.05, -0.02, 0.07);  // a material point in the body frame
  for (double t : {0.0, 0.7, 5.2}) {
    const auto pointAt = [&](double s) {
      Vector3d p;
      Quaterniond q;
      m.poseAt(kStart, kStartQ, s, p, q);
      return Vector3d(q * bodyPoint + p);
    };
    const double h = 1e-5;
    const Vector3d numeric = (pointAt(t + h) - pointAt(t - h)) / (2 * h);
    EXPECT_LT((m.velocityAt(pointAt(t), t) - numeric).norm(), 1e-8) << t;
  }
  // pure translation
  const PrescribedMotion slide = PrescribedMotion::make(Vector3d(1, 2, 3), Vector3d::Zero(), Vector3d::UnitZ(), 0.0);
  Vector3d p;
  Quaterniond q;
  slide.poseAt(kStart, kStartQ, 2.0, p, q);
  EXPECT_LT((p - (kStart + Vector3d(2, 4, 6))).norm(), 1e-15);
  EXPECT_LT(std::abs(std::abs(q.dot(kStartQ)) - 1.0), 1e-15);
}

TEST(PrescribedMotion, BadArgumentsAndFixedBodyVelocities) {
  EXPECT_THROW(PrescribedMotion::make(Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero(), 1.0), std::invalid_argument);
  EXPECT_THROW(PrescribedMotion::make(Vector3d::Zero(), Vector3d::Zero(), Vector3d::UnitX(), NAN), std::invalid_argument);
  RigidBody drum = RigidBody::fixed(Vector3d(1, 0, 0));
  drum.velocity = Vector3d(0, 0, 0.5);
  drum.prescribedAngularVelocity = Vector3d(0, 0, 2.0);
  EXPECT_LT((drum.velocityAt(Vector3d(1, 1, 0)) - Vector3d(-2.0, 0, 0.5)).norm(), 1e-15);
  EXPECT_EQ(drum.kineticEnergy(), 0.0);
  drum.kick(Vector3d(1, 1, 1), Vector3d(1, 1, 1), 1.0);  // forces do not move it
  EXPECT_EQ(drum.velocity, Vector3d(0, 0, 0.5));
}

}  // namespace
