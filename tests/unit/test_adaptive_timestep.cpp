// Adaptive global time step: creep, caps, veto of critical approaches, and a two-sphere
// collision integrated with the policy against the closed-form spring-dashpot solution.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "dynamics/AdaptiveTimestep.h"
#include "dynamics/TimestepRollback.h"
#include "dynamics/TimestepVeto.h"

using namespace spacetree;

namespace {
const double kOrigin[3] = {0.0, 0.0, 0.0};
const double kRest[3] = {0.0, 0.0, 0.0};
}  // namespace

TEST(AdaptiveTimestep, CreepsByTheFactorUntilTheMeshCap) {
  TimestepPolicy policy;
  policy.creep = 1.1;
  TimestepLimits limits;
  limits.finestCell = 0.01;
  limits.halo = 0.002;
  limits.maxSpeed = 2.0;  // cap (0.01 + 0.002) / 2 = 6e-3
  TimestepVeto noVeto(0.0, 0.8);
  double dt = 1e-3;
  int steps = 0;
  while (dt < 6e-3 && steps < 100) {
    const double next = nextTimestep(dt, policy, limits, noVeto.limit()).dt;
    EXPECT_DOUBLE_EQ(next, std::min(1.1 * dt, 6e-3));
    dt = next;
    ++steps;
  }
  EXPECT_DOUBLE_EQ(dt, 6e-3);
  EXPECT_EQ(steps, int(std::ceil(std::log(6.0) / std::log(1.1))));
  EXPECT_DOUBLE_EQ(nextTimestep(dt, policy, limits, noVeto.limit()).dt, 6e-3);  // stays at the cap
}

TEST(AdaptiveTimestep, SkinAndCeilingCapTheStep) {
  TimestepPolicy policy;
  TimestepLimits limits;
  limits.skin = 0.001;
  limits.maxSpeed = 10.0;  // half the skin per step: 5e-5
  TimestepVeto noVeto(0.0, 0.8);
  EXPECT_DOUBLE_EQ(nextTimestep(1.0, policy, limits, noVeto.limit()).dt, 5e-5);
  policy.dtMax = 1e-5;
  EXPECT_DOUBLE_EQ(nextTimestep(1.0, policy, limits, noVeto.limit()).dt, 1e-5);
  EXPECT_THROW(nextTimestep(0.0, policy, limits, noVeto.limit()), std::invalid_argument);
  policy.creep = 0.5;
  EXPECT_THROW(nextTimestep(1e-6, policy, limits, noVeto.limit()), std::invalid_argument);
  policy.creep = kMaxCreep;  // doubling is the most creep may do
  EXPECT_NO_THROW(nextTimestep(1e-6, policy, limits, noVeto.limit()));
  for (double creep : {2.5, 1e300, double(INFINITY), double(NAN)}) {
    policy.creep = creep;
    EXPECT_THROW(nextTimestep(1e-6, policy, limits, noVeto.limit()), std::invalid_argument) << creep;
  }
}

TEST(TimestepVeto, CutsCriticalApproachesToASafeFractionOfTheGap) {
  TimestepVeto veto(0.001, 0.8);
  const double xj[3] = {0.03, 0.0, 0.0};      // gap 0.03 - 0.01 - 0.01 - 0.001 = 0.009
  const double vj[3] = {-3.0, 0.0, 0.0};      // approaching at 3
  veto.consider(kOrigin, kRest, 0.01, xj, vj, 0.01, 0.001);  // 3 * 0.001 < 0.009: not critical
  EXPECT_EQ(veto.criticalPairs(), 0u);
  EXPECT_TRUE(std::isinf(veto.limit()));
  veto.consider(kOrigin, kRest, 0.01, xj, vj, 0.01, 0.01);   // 0.03 > 0.009: critical
  EXPECT_EQ(veto.criticalPairs(), 1u);
  EXPECT_NEAR(veto.limit(), 0.8 * 0.009 / 3.0, 1e-15);
  const double faster[3] = {-9.0, 0.0, 0.0};
  veto.consider(kOrigin, kRest, 0.01, xj, faster, 0.01, 0.01);
  EXPECT_NEAR(veto.limit(), 0.8 * 0.009 / 9.0, 1e-15) << "the smallest safe step wins";

  TimestepVeto other(0.001, 0.8);
  const double receding[3] = {3.0, 0.0, 0.0};
  other.consider(kOrigin, kRest, 0.01, xj, receding, 0.01, 1.0);
  const double sideways[3] = {0.0, 5.0, 0.0};
  other.consider(kOrigin, kRest, 0.01, xj, sideways, 0.01, 1.0);
  const double touching[3] = {0.0205, 0.0, 0.0};  // inside the halo already
  other.consider(kOrigin, kRest, 0.01, touching, vj, 0.01, 1.0);
  EXPECT_EQ(other.criticalPairs(), 0u);
  // projection on the centre line: an oblique approach counts with its normal component
  const double oblique[3] = {0.03, 0.04, 0.0};      // distance 0.05, gap 0.029
  const double obliqueV[3] = {-3.0, -4.0, 7.0};     // normal closing speed 5
  other.consider(kOrigin, kRest, 0.01, oblique, obliqueV, 0.01, 1.0);
  EXPECT_NEAR(other.limit(), 0.8 * 0.029 / 5.0, 1e-15);
  EXPECT_THROW(TimestepVeto(-1.0, 0.5), std::invalid_argument);
  EXPECT_THROW(TimestepVeto(0.0, 1.5), std::invalid_argument);
}

TEST(AdaptiveTimestep, VetoOverridesCreepAndIsFloored) {
  TimestepPolicy policy;
  policy.dtMin = 1e-6;
  TimestepLimits limits;
  TimestepVeto veto(0.0, 0.5);
  const double xj[3] = {2.0 + 1e-6, 0.0, 0.0};  // gap 1e-6
  const double vj[3] = {-10.0, 0.0, 0.0};
  veto.consider(kOrigin, kRest, 1.0, xj, vj, 1.0, 1e-3);
  const TimestepDecision d = nextTimestep(1e-3, policy, limits, veto.limit());
  EXPECT_TRUE(d.vetoed);
  EXPECT_TRUE(d.floored);  // 0.5 * 1e-6 / 10 = 5e-8 < dtMin
  EXPECT_DOUBLE_EQ(d.dt, 1e-6);
}

namespace {
// Two equal spheres head-on with a linear spring-dashpot, velocity Verlet, the time step
// chosen by the policy before every step (veto on the current state).
struct CollisionResult {
  double restitution, contactTime, maxOverlapAtContactStart, energyRatio;
  int steps;
};

CollisionResult collide(double k, double c, double dtMaxFraction, double dtMin) {
  const double m = 1.0, r = 0.01, speed = 1.0, mEff = 0.5 * m;
  const double gamma = c / (2.0 * mEff), omega = std::sqrt(k / mEff - gamma * gamma);
  const double tc = M_PI / omega;
  TimestepPolicy policy;
  policy.creep = 1.1;
  policy.dtMin = dtMin;
  policy.dtMax = dtMaxFraction * tc;
  TimestepLimits limits;
  limits.finestCell = 2.2 * r;
  limits.maxSpeed = speed;
  double x1 = 0.0, x2 = 0.1, v1 = speed, v2 = -speed, dt = policy.dtMax;
  auto force = [&](double a, double b, double va, double vb) {  // on sphere 2
    const double overlap = 2 * r - (b - a);
    return overlap > 0.0 ? k * overlap + c * (va - vb) : 0.0;
  };
  double f = force(x1, x2, v1, v2), t = 0.0, contactStart = -1.0, contactEnd = -1.0;
  CollisionResult res{0, 0, 0, 0, 0};
  const double e0 = 0.5 * m * (v1 * v1 + v2 * v2);
  for (int step = 0; step < 2000000 && contactEnd < 0.0; ++step) {
    TimestepVeto veto(0.0, 0.8);
    const double p1[3] = {x1, 0, 0}, p2[3] = {x2, 0, 0}, u1[3] = {v1, 0, 0}, u2[3] = {v2, 0, 0};
    veto.consider(p1, u1, r, p2, u2, r, dt);
    dt = nextTimestep(dt, policy, limits, veto.limit()).dt;
    const double wasOverlap = 2 * r - (x2 - x1);
    x1 += v1 * dt - 0.5 * f / m * dt * dt;
    x2 += v2 * dt + 0.5 * f / m * dt * dt;
    // velocity-dependent damping: predict, then correct once
    const double v1p = v1 - f / m * dt, v2p = v2 + f / m * dt;
    const double fn = force(x1, x2, v1p, v2p);
    v1 -= 0.5 * (f + fn) / m * dt;
    v2 += 0.5 * (f + fn) / m * dt;
    f = fn;
    t += dt;
    res.steps = step + 1;
    const double overlap = 2 * r - (x2 - x1);
    // crossing times interpolated within the step, so the measurement is not quantised by dt
    const double crossing = t - dt * overlap / (overlap - wasOverlap);
    if (overlap > 0.0 && wasOverlap <= 0.0 && contactStart < 0.0) {
      contactStart = crossing;
      res.maxOverlapAtContactStart = overlap;
    }
    if (contactStart >= 0.0 && overlap <= 0.0) contactEnd = crossing;
  }
  res.restitution = (v2 - v1) / (2 * speed);
  res.contactTime = contactEnd - contactStart;
  res.energyRatio = 0.5 * m * (v1 * v1 + v2 * v2) / e0;
  return res;
}
}  // namespace

TEST(AdaptiveTimestep, TwoSphereCollisionMatchesTheClosedFormSpringDashpot) {
  const double k = 1e5, c = 40.0, mEff = 0.5;
  const double gamma = c / (2 * mEff), omega = std::sqrt(k / mEff - gamma * gamma);
  const double e = std::exp(-M_PI * gamma / omega), tc = M_PI / omega;
  const CollisionResult res = collide(k, c, 1.0 / 50.0, 1e-7);
  EXPECT_NEAR(res.restitution, e, 0.01 * e);
  EXPECT_NEAR(res.contactTime, tc, 0.01 * tc);
  // the veto keeps the first overlap to what the closing speed covers in one floored step
  EXPECT_LE(res.maxOverlapAtContactStart, 2.0 * 1e-7 * 1.0 + 1e-15);
}

TEST(AdaptiveTimestep, ElasticCollisionConservesEnergy) {
  const CollisionResult res = collide(1e5, 0.0, 1.0 / 2000.0, 1e-8);
  EXPECT_NEAR(res.energyRatio, 1.0, 1e-6);
  EXPECT_NEAR(res.restitution, 1.0, 1e-3);
}

TEST(TimestepVeto, AllowedOverlapLetsAPairEnterContactUpToEps) {
  const double eps = 1e-4;
  TimestepVeto veto(0.0, 0.5, eps);
  const double xj[3] = {0.02 + 1e-4, 0.0, 0.0};  // radii 0.01: surface gap 1e-4
  const double vj[3] = {-2.0, 0.0, 0.0};
  veto.consider(kOrigin, kRest, 0.01, xj, vj, 0.01, 4e-5);  // 8e-5 <= 0.5 (gap + eps): not critical
  EXPECT_EQ(veto.criticalPairs(), 0u);
  veto.consider(kOrigin, kRest, 0.01, xj, vj, 0.01, 1e-3);  // 2e-3 > 2e-4: critical
  EXPECT_EQ(veto.criticalPairs(), 1u);
  EXPECT_NEAR(veto.limit(), 0.5 * 2e-4 / 2.0, 1e-15);
  // in contact (overlap 5e-5 < eps) and still approaching: only eps - overlap is left
  TimestepVeto inContact(0.0, 1.0, eps);
  const double xc[3] = {0.02 - 5e-5, 0.0, 0.0};
  inContact.consider(kOrigin, kRest, 0.01, xc, vj, 0.01, 1e-3);
  EXPECT_NEAR(inContact.limit(), 5e-5 / 2.0, 1e-15);
  // deeper than eps already: not critical (a smaller step cannot undo it)
  TimestepVeto deep(0.0, 1.0, eps);
  const double xd[3] = {0.02 - 2e-4, 0.0, 0.0};
  deep.consider(kOrigin, kRest, 0.01, xd, vj, 0.01, 1e-3);
  EXPECT_EQ(deep.criticalPairs(), 0u);
  EXPECT_THROW(TimestepVeto(0.0, 0.5, -1e-3), std::invalid_argument);
}

TEST(AdaptiveTimestep, ContactCeilingAppliesOnlyWhilePairsOverlap) {
  TimestepPolicy policy;
  policy.dtMax = 1e-3;
  policy.dtContact = 1e-5;
  TimestepLimits limits;
  EXPECT_DOUBLE_EQ(nextTimestep(1e-3, policy, limits, INFINITY).dt, 1e-3);
  limits.inContact = true;
  EXPECT_DOUBLE_EQ(nextTimestep(1e-3, policy, limits, INFINITY).dt, 1e-5);
  EXPECT_DOUBLE_EQ(nextTimestep(5e-6, policy, limits, INFINITY).dt, 5.5e-6) << "creeps up to it";
}

// The stability ceiling (fix adapt/timestep with pair_style trimesh: the largest stable step of
// the type pairs in contact) caps the step only while pairs are in contact or about to touch,
// together with a dtContact (the smaller wins), and only when the policy asks for it.
TEST(AdaptiveTimestep, StabilityCeilingCapsTheStepInContact) {
  TimestepPolicy policy;
  policy.dtMax = 1e-3;
  policy.stableCeiling = true;
  TimestepLimits limits;
  limits.stableStep = 1.2e-5;
  EXPECT_DOUBLE_EQ(nextTimestep(1e-3, policy, limits, INFINITY).dt, 1e-3) << "free flight: dtMax";
  limits.inContact = true;
  TimestepDecision d = nextTimestep(1e-3, policy, limits, INFINITY);
  EXPECT_DOUBLE_EQ(d.dt, 1.2e-5);
  EXPECT_EQ(d.limiter, TimestepLimiter::Stable);
  EXPECT_STREQ(limiterName(d.limiter), "stable");
  EXPECT_DOUBLE_EQ(nextTimestep(1e-5, policy, limits, INFINITY).dt, 1.1e-5) << "creeps up to it";
  policy.dtContact = 1e-5;   // the smaller of the two ceilings
  EXPECT_EQ(nextTimestep(1e-3, policy, limits, INFINITY).limiter, TimestepLimiter::Contact);
  policy.dtContact = 2e-5;
  EXPECT_DOUBLE_EQ(nextTimestep(1e-3, policy, limits, INFINITY).dt, 1.2e-5);
  limits.stableStep = 0.0;   // no stable step known: the other bounds
  EXPECT_DOUBLE_EQ(nextTimestep(1e-3, policy, limits, INFINITY).dt, 2e-5);
  limits.stableStep = 1.2e-5;
  policy.stableCeiling = false;
  EXPECT_DOUBLE_EQ(nextTimestep(1e-3, policy, limits, INFINITY).dt, 2e-5);
}

// The decision names the bound that set the step (fix adapt/timestep's `limit` column): each
// bound in turn made the smallest.
TEST(AdaptiveTimestep, DecisionNamesTheBoundThatSetTheStep) {
  TimestepPolicy policy;
  policy.dtMax = 1e-3;
  policy.dtContact = 1e-5;
  policy.dtMin = 1e-8;
  TimestepLimits limits;
  auto limiter = [&](double dt, double veto = INFINITY) { return nextTimestep(dt, policy, limits, veto).limiter; };
  EXPECT_EQ(limiter(1e-4), TimestepLimiter::Creep);
  EXPECT_EQ(limiter(1e-3), TimestepLimiter::Ceiling);
  limits.inContact = true;
  EXPECT_EQ(limiter(1e-3), TimestepLimiter::Contact);
  EXPECT_EQ(limiter(5e-6), TimestepLimiter::Creep) << "creeping back up to the contact ceiling";
  // a slow contact under the contact-speed ceiling: dtRest applies
  policy.impactSpeed = 1.0;
  policy.contactTime = 1e-3;
  policy.dtRest = 1e-4;
  limits.contactSpeed = 0.01;  // dtContact * 1 / 0.01 = 1e-3 > dtRest
  EXPECT_EQ(limiter(1e-3), TimestepLimiter::Rest);
  limits.contactSpeed = 2.0;   // 5e-6
  EXPECT_EQ(limiter(1e-3), TimestepLimiter::Contact);
  EXPECT_DOUBLE_EQ(nextTimestep(1e-3, policy, limits, INFINITY).dt, 5e-6);
  limits.inContact = false;
  limits.maxSpeed = 1.0;
  limits.finestCell = 1e-4;   // (1e-4 + 0) / 1 = 1e-4
  EXPECT_EQ(limiter(1e-3), TimestepLimiter::Mesh);
  limits.skin = 1e-4;          // 5e-5
  EXPECT_EQ(limiter(1e-3), TimestepLimiter::Skin);
  limits.listMargin = 4e-5;    // 2e-5
  EXPECT_EQ(limiter(1e-3), TimestepLimiter::ListMargin);
  const TimestepDecision vetoed = nextTimestep(1e-3, policy, limits, 3e-6);
  EXPECT_EQ(vetoed.limiter, TimestepLimiter::Veto);
  EXPECT_TRUE(vetoed.vetoed);
  const TimestepDecision floored = nextTimestep(1e-3, policy, limits, 1e-9);
  EXPECT_EQ(floored.limiter, TimestepLimiter::Floor);
  EXPECT_TRUE(floored.vetoed && floored.floored);
  EXPECT_DOUBLE_EQ(floored.dt, 1e-8);
  EXPECT_STREQ(limiterName(TimestepLimiter::Contact), "contact");
  EXPECT_STREQ(limiterName(TimestepLimiter::ListMargin), "margin");
  EXPECT_STREQ(limiterName(TimestepLimiter::Floor), "dtmin");
}

TEST(TimestepRollback, RedoesOnlyStepsThatCausedTooDeepAnOverlap) {
  RollbackPolicy policy;  // fraction 0.5, shrink 0.5, 20 retries
  const double eps = 1e-3;
  EXPECT_FALSE(judgeStep(policy, eps, 0.0, 4e-4, 1e-3, 1e-6, 0).redo);  // within 0.5 eps
  RollbackDecision d = judgeStep(policy, eps, 0.0, 6e-4, 1e-3, 1e-6, 0);
  EXPECT_TRUE(d.redo);
  EXPECT_DOUBLE_EQ(d.dt, 5e-4);
  EXPECT_FALSE(judgeStep(policy, eps, 6e-4, 7e-4, 1e-3, 1e-6, 0).redo) << "already deep before the step";
  d = judgeStep(policy, eps, 0.0, 6e-4, 1.5e-6, 1e-6, 0);
  EXPECT_TRUE(d.redo);
  EXPECT_DOUBLE_EQ(d.dt, 1e-6) << "never below dtMin";
  d = judgeStep(policy, eps, 0.0, 6e-4, 1e-6, 1e-6, 0);
  EXPECT_FALSE(d.redo);
  EXPECT_TRUE(d.exhausted);
  EXPECT_TRUE(judgeStep(policy, eps, 0.0, 6e-4, 1e-3, 1e-6, 20).exhausted);
  EXPECT_THROW(judgeStep(policy, 0.0, 0.0, 1.0, 1e-3, 1e-6, 0), std::invalid_argument);
}

TEST(TimestepRollback, BoundsTheEntryOverlapOfAFastCollisionWithoutVeto) {
  // two spheres (m = 1, r = 0.01) closing at 2 m/s; the fixed step 2e-4 is far too coarse to
  // enter contact gently (the first overlap can reach 4e-4). Integrate up to the first contact.
  const double k = 1e7, m = 1.0, r = 0.01, eps = 2e-4, dtBig = 2e-4, dtMin = 1e-9;
  RollbackPolicy policy;
  auto entryOverlap = [&](bool withRollback, int& redos) {
    double x1 = 0.0, x2 = 0.1 - 1.234e-4, v1 = 1.0, v2 = -1.0, f = 0.0;
    redos = 0;
    for (int step = 0; step < 1000; ++step) {
      const double before = std::max(0.0, 2 * r - (x2 - x1));
      const double s1 = x1, s2 = x2, w1 = v1, w2 = v2, sf = f;  // state at the step's start
      double dt = dtBig;
      for (int retries = 0;; ++retries) {
        x1 = s1 + w1 * dt - 0.5 * sf / m * dt * dt;
        x2 = s2 + w2 * dt + 0.5 * sf / m * dt * dt;
        const double overlap = 2 * r - (x2 - x1);
        const double fn = overlap > 0 ? k * overlap : 0.0;
        v1 = w1 - 0.5 * (sf + fn) / m * dt;
        v2 = w2 + 0.5 * (sf + fn) / m * dt;
        f = fn;
        const RollbackDecision d = judgeStep(policy, eps, before, std::max(0.0, overlap), dt, dtMin, retries);
        if (!withRollback || !d.redo) break;
        dt = d.dt;
        ++redos;
      }
      if (2 * r - (x2 - x1) > 0.0) return 2 * r - (x2 - x1);
    }
    return -1.0;
  };
  int redos = 0;
  const double without = entryOverlap(false, redos);
  EXPECT_GT(without, policy.fraction * eps) << "the coarse step does penetrate too deep";
  EXPECT_EQ(redos, 0);
  const double with = entryOverlap(true, redos);
  EXPECT_GT(with, 0.0);
  EXPECT_LE(with, policy.fraction * eps);
  EXPECT_GT(redos, 0);
}

TEST(AdaptiveTimestep, ListMarginKeepsUnlistedPairsApartForTheStep) {
  TimestepPolicy policy;
  policy.dtMax = 1.0;
  TimestepLimits limits;
  limits.skin = 0.002;
  limits.maxSpeed = 0.5;  // skin cap: 0.5 * 0.002 / 0.5 = 2e-3
  EXPECT_DOUBLE_EQ(nextTimestep(1.0, policy, limits, INFINITY).dt, 2e-3);
  // particles moved 6e-4 since the build: unlisted pairs are >= 8e-4 apart, closing at <= 1 m/s
  limits.listMargin = 0.002 - 2 * 6e-4;
  EXPECT_DOUBLE_EQ(nextTimestep(1.0, policy, limits, INFINITY).dt, 8e-4);
}

TEST(AdaptiveTimestep, ContactCeilingFollowsTheContactSpeed) {
  TimestepPolicy policy;
  policy.dtContact = 1e-5;
  EXPECT_DOUBLE_EQ(contactCeiling(policy, 3.0), 1e-5) << "off: one ceiling for every contact";
  policy.impactSpeed = 1.0;
  policy.dtRest = 1e-4;
  EXPECT_DOUBLE_EQ(contactCeiling(policy, 1.0), 1e-5);
  EXPECT_DOUBLE_EQ(contactCeiling(policy, 4.0), 2.5e-6) << "faster than the reference: finer";
  EXPECT_DOUBLE_EQ(contactCeiling(policy, 0.5), 2e-5);
  EXPECT_DOUBLE_EQ(contactCeiling(policy, 1e-3), 1e-4) << "enduring contact: the stability ceiling";
  EXPECT_DOUBLE_EQ(contactCeiling(policy, 0.0), 1e-4);
  // contact speed: the velocity amplitude of the contact's normal oscillation
  const double tc = 1e-3, omega = M_PI / tc;
  EXPECT_DOUBLE_EQ(contactSpeed(-2.0, 0.0, tc), 2.0) << "no acceleration: |vn|";
  // undamped impact at 1.5 m/s, at any phase: vn = v0 cos(wt), an = -v0 w sin(wt)
  for (double phase : {0.0, 0.4, M_PI / 2, 2.5})
    EXPECT_NEAR(contactSpeed(1.5 * std::cos(phase), -1.5 * omega * std::sin(phase), tc), 1.5, 1e-12);
  EXPECT_DOUBLE_EQ(contactSpeed(0.0, 0.0, tc), 0.0) << "steady load: at rest however deep";
  EXPECT_THROW(contactSpeed(1.0, 1e-4, 0.0), std::invalid_argument);
}

namespace {
// A sphere dropped on a linear elastic floor under gravity, velocity Verlet, the step chosen
// before every step by the policy from the current state (contact or about to touch). Returns
// the largest relative error of the total energy (kinetic + gravity + spring) over the run, the
// largest step taken while in contact near the peak of the first impact, and the step at the end
// (the sphere has come to rest on the floor only if damping were present; here it keeps
// bouncing, so the end state is after the last bounce's flight).
struct BounceResult {
  double maxEnergyError, peakStep, steps;
};

BounceResult bounce(const TimestepPolicy& policy, double k, double tEnd, double drop, double v0 = 0.0) {
  const double m = 1e-3, g = 9.81, r = 0.01, tc = M_PI * std::sqrt(m / k);
  double z = r + drop, v = v0, dt = policy.dtContact, t = 0.0;
  auto force = [&](double zz) { return (zz < r ? k * (r - zz) : 0.0) - m * g; };
  auto energy = [&](double zz, double vv) {
    const double d = std::max(r - zz, 0.0);
    return 0.5 * m * vv * vv + m * g * zz + 0.5 * k * d * d;
  };
  const double e0 = energy(z, v);
  double f = force(z);
  BounceResult res{0.0, 0.0, 0.0};
  TimestepLimits limits;
  while (t < tEnd) {
    const double overlap = r - z, approach = -v;
    limits.inContact = overlap > 0.0 || approach * policy.creep * dt > -overlap;
    limits.contactSpeed = contactSpeed(v, f / m, tc);   // floor at rest: relative = absolute
    dt = nextTimestep(dt, policy, limits, INFINITY).dt;
    z += v * dt + 0.5 * f / m * dt * dt;
    const double fn = force(z);
    v += 0.5 * (f + fn) / m * dt;
    f = fn;
    t += dt;
    res.steps += 1;
    if (r - z > 0.0 && std::fabs(v) < 0.2 * std::sqrt(2 * g * drop)) res.peakStep = std::max(res.peakStep, dt);
    res.maxEnergyError = std::max(res.maxEnergyError, std::fabs(energy(z, v) - e0) / e0);
  }
  return res;
}
}  // namespace

TEST(AdaptiveTimestep, StateDependentCeilingResolvesImpactsAndRelaxesRestingContacts) {
  const double k = 1e4, m = 1e-3, tc = M_PI * std::sqrt(m / k), drop = 0.05;
  const double vImpact = std::sqrt(2 * 9.81 * drop);
  TimestepPolicy fixedContact;           // the state-independent ceiling tc/100
  fixedContact.creep = 1.1;
  fixedContact.dtMax = 1e-3;
  fixedContact.dtMin = 1e-9;
  fixedContact.dtContact = tc / 100;
  TimestepPolicy state = fixedContact;   // the same ceiling for an impact at the drop speed
  state.impactSpeed = vImpact;
  state.contactTime = tc;
  state.dtRest = tc / 10;
  const double tEnd = 0.25;               // two bounces
  const BounceResult a = bounce(fixedContact, k, tEnd, drop), b = bounce(state, k, tEnd, drop);
  // impacts at the reference speed: the peak of the impact is resolved as finely as before
  // (the contact speed stays at the approach speed through the impact, no jump at v_n = 0)
  EXPECT_LE(b.peakStep, 1.05 * tc / 100);
  EXPECT_LE(b.maxEnergyError, 2.0 * a.maxEnergyError) << "same order: the entry phase differs";
  // a sphere resting on the floor (released at its static overlap, at rest): its contact speed is
  // omega * m g / k = g / omega, so the step goes to dtRest; energy still conserved closely
  const double rest = m * 9.81 / k;
  TimestepPolicy r = state;
  const BounceResult resting = bounce(r, k, 0.05, -rest);
  const BounceResult restingFixed = bounce(fixedContact, k, 0.05, -rest);
  EXPECT_LT(resting.steps, 0.15 * restingFixed.steps);
  EXPECT_LT(resting.maxEnergyError, 1e-9);
}
