// The multilevel ghost rule (parallel/HaloReach, HaloSizeClasses, SubdomainGrid, HaloSurface)
// without LIGGGHTS: the size classes and the owner-box distance in isolation, then a model of
// the Cartesian ghost exchange (a particle with reach c arrives in every subdomain image within
// L-infinity distance c, which is what LIGGGHTS' x, y, z swaps deliver), run class by class,
// coarse first, on random bidisperse and continuous packs in periodic and walled boxes cut
// into 1 to 8 subdomains. Every pair within (r_i + r_j) f + skin must be present on the ranks of
// both particles (owned or ghost, in the right periodic image), and the ghost count must stay
// below the single-shell rule's (r_i + r_max) f + skin.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <stdexcept>
#include <tuple>
#include <vector>

#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "parallel/HaloReach.h"
#include "parallel/HaloSizeClasses.h"
#include "parallel/HaloSurface.h"
#include "parallel/SubdomainGrid.h"

using namespace spacetree;
using namespace spacetree::parallel;
using Eigen::Vector3d;

namespace {

std::array<std::vector<double>, 3> uniformSplits(const std::array<int, 3>& n) {
  std::array<std::vector<double>, 3> s;
  for (int d = 0; d < 3; ++d) {
    for (int i = 0; i < n[std::size_t(d)]; ++i) s[std::size_t(d)].push_back(double(i) / n[std::size_t(d)]);
    s[std::size_t(d)].push_back(1.0);
  }
  return s;
}

}  // namespace

TEST(HaloSizeClasses, ClassesHalveFromTheLargestRadius) {
  const HaloSizeClasses c(8.0, 2.0, 4);
  EXPECT_EQ(c.count(), 4);
  EXPECT_EQ(c.classOf(8.0), 0);
  EXPECT_EQ(c.classOf(4.0001), 0);
  EXPECT_EQ(c.classOf(4.0), 1);   // (2, 4]
  EXPECT_EQ(c.classOf(2.5), 1);
  EXPECT_EQ(c.classOf(1.5), 2);   // (1, 2]
  EXPECT_EQ(c.classOf(1.0), 3);   // the last class takes the rest
  EXPECT_EQ(c.classOf(0.0), 3);
  EXPECT_DOUBLE_EQ(c.upperBound(0), 8.0);
  EXPECT_DOUBLE_EQ(c.upperBound(2), 2.0);
  EXPECT_DOUBLE_EQ(c.lowerBound(2), 1.0);
  EXPECT_DOUBLE_EQ(c.lowerBound(3), 0.0);
  EXPECT_EQ(HaloSizeClasses().count(), 1);
  EXPECT_THROW(HaloSizeClasses(1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(HaloSizeClasses(1.0, 2.0, 0), std::invalid_argument);
  EXPECT_THROW(HaloSizeClasses(-1.0, 2.0), std::invalid_argument);
}

TEST(SubdomainGrid, DistanceToTheOwnerBoxAcrossCutsAndImages) {
  // x cut into [0, 1) [1, 3) [3, 4] (non-uniform), y periodic in two, z one box
  const SubdomainGrid g(Vector3d(0, 0, 0), Vector3d(4, 2, 1), {{false, true, true}},
                        {{{0.0, 0.25, 0.75, 1.0}, {0.0, 0.5, 1.0}, {0.0, 1.0}}});
  EXPECT_EQ(g.boxes(0), 3);
  // q in box (1, 0, 0); p in box (0, 0, 0): x distance to [1, 3]
  EXPECT_DOUBLE_EQ(g.distanceToOwner(Vector3d(0.2, 0.5, 0.5), Vector3d(2.0, 0.5, 0.5)), 0.8);
  // same box: 0
  EXPECT_DOUBLE_EQ(g.distanceToOwner(Vector3d(1.5, 0.5, 0.5), Vector3d(2.9, 0.9, 0.1)), 0.0);
  // q a periodic image below y = 0 (y = -0.1 is box 1 at shift -1: [-1, 0]); p at y 0.3
  EXPECT_DOUBLE_EQ(g.distanceToOwner(Vector3d(2.0, 0.3, 0.5), Vector3d(2.0, -0.1, 0.5)), 0.3);
  // q outside the non-periodic x range: the nearest box owns
  EXPECT_DOUBLE_EQ(g.distanceToOwner(Vector3d(2.0, 0.5, 0.5), Vector3d(-0.5, 0.5, 0.5)), 1.0);
  // q on a cut (within rounding): both boxes are candidates, the larger distance counts
  EXPECT_DOUBLE_EQ(g.distanceToOwner(Vector3d(3.5, 0.5, 0.5), Vector3d(3.0 - 1e-14, 0.5, 0.5)), 0.5);
  // on the periodic face y = 2 (the image of y = 0): box 0 at shift +1 ([2, 3]) or box 1 ([1, 2])
  EXPECT_DOUBLE_EQ(g.distanceToOwner(Vector3d(2.0, 0.2, 0.5), Vector3d(2.0, 2.0, 0.5)), 1.8);
  EXPECT_DOUBLE_EQ(g.distanceToBox(Vector3d(0.2, 0.5, 0.5), {{1, 0, 0}}), 0.8);
  EXPECT_NEAR(g.distanceToBox(Vector3d(0.2, 1.9, 0.5), {{0, 0, 0}}, {{0, 1, 0}}), 0.1, 1e-15);
  EXPECT_THROW(SubdomainGrid(Vector3d(0, 0, 0), Vector3d(1, 1, 1), {{false, false, false}},
                             {{{0.0, 0.6, 0.5, 1.0}, {0.0, 1.0}, {0.0, 1.0}}}),
               std::invalid_argument);
}

TEST(HaloReach, OwnReachAndServedCoarsePartner) {
  const SubdomainGrid g(Vector3d(0, 0, 0), Vector3d(10, 10, 10), {{false, false, false}},
                        uniformSplits({{2, 1, 1}}));
  HaloRule rule;
  rule.skin = 0.1;
  HaloReach h(rule, g);
  EXPECT_DOUBLE_EQ(h.ownReach(0.5, 0.5), 1.1);
  // a big ghost (r 3) owned by box 1 ([5, 10]) at x 6; a small one at x 3.4 touches it within
  // the skin (2.6 <= 3.5 + 0.1) and must reach box 1: distance 1.6 > own reach 1.1
  h.addPartner(Vector3d(6.0, 5.0, 5.0), 3.0);
  h.indexPartners(0.5);
  bool served = false;
  EXPECT_DOUBLE_EQ(h.reach(Vector3d(2.45, 5, 5), 0.5, 0.5, &served), 2.55);
  EXPECT_TRUE(served);
  // beyond the pair cut-off: only the own reach
  EXPECT_DOUBLE_EQ(h.reach(Vector3d(2.35, 5, 5), 0.5, 0.5, &served), 1.1);
  EXPECT_FALSE(served);
  // a floor for every particle (comm_modify cutoff, insertion overlap checks)
  rule.minimumShell = 2.0;
  EXPECT_DOUBLE_EQ(HaloReach(rule, g).ownReach(0.5, 0.5), 2.5);
}

TEST(HaloReach, IndexedPartnersGiveTheBruteForceReach) {
  // partners of two indexing calls (two classes), some far outside the box; queries inside,
  // next to and far from them: the indexed reach equals a loop over all partners
  const SubdomainGrid g(Vector3d(0, 0, 0), Vector3d(1, 1, 1), {{true, true, false}},
                        uniformSplits({{3, 2, 2}}));
  HaloRule rule;
  rule.skin = 0.01;
  HaloReach h(rule, g);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-0.3, 1.3);
  std::vector<std::pair<Vector3d, double>> all;
  for (int cls = 0; cls < 2; ++cls) {
    const double r = cls == 0 ? 0.2 : 0.05;
    for (int k = 0; k < (cls == 0 ? 5 : 300); ++k) {
      const Vector3d x(u(rng), u(rng), u(rng));
      h.addPartner(x, r);
      all.emplace_back(x, r);
    }
    h.indexPartners(r);
  }
  const auto expectBruteForce = [&](const HaloReach& reach, double lo, double hi) {
    std::uniform_real_distribution<double> inside(lo, hi);
    for (int q = 0; q < 3000; ++q) {
      const Vector3d x(inside(rng), inside(rng), inside(rng));
      const double r = 0.01;
      double brute = reach.ownReach(r, 0.01);
      for (std::size_t p = 0; p < all.size(); ++p)
        if ((x - all[p].first).norm() <= r + all[p].second + rule.skin)
          brute = std::max(brute, g.distanceToOwner(x, all[p].first));
      ASSERT_DOUBLE_EQ(reach.reach(x, r, 0.01), brute) << "query " << q;
    }
  };
  expectBruteForce(h, -0.3, 1.3);
  EXPECT_EQ(h.indexedPartnerCount(), all.size());
  // with an own box, partners that cannot reach it are left out, the reaches inside stay
  HaloReach boxed(rule, g);
  boxed.setOwnBox(Vector3d(0.4, 0.4, 0.4), Vector3d(0.6, 0.6, 0.6));
  for (int cls = 0; cls < 2; ++cls) {
    for (std::size_t p = (cls == 0 ? 0 : 5); p < (cls == 0 ? 5 : all.size()); ++p)
      boxed.addPartner(all[p].first, all[p].second);
    boxed.indexPartners(0.01);  // the queries' radius: the tightest valid bound
  }
  EXPECT_LT(boxed.indexedPartnerCount(), all.size() / 2);
  expectBruteForce(boxed, 0.4, 0.6);
  // a partner 0.06 outside the own box (owned by the next box, x >= 2/3), touched by a particle
  // inside (0.061 <= 0.01 + 0.05 + skin): indexed, and the particle must reach x = 2/3
  HaloReach edge(rule, g);
  edge.setOwnBox(Vector3d(0.4, 0.4, 0.4), Vector3d(0.61, 0.6, 0.6));
  edge.addPartner(Vector3d(0.67, 0.5, 0.5), 0.05);
  edge.indexPartners(0.01);
  EXPECT_EQ(edge.indexedPartnerCount(), 1u);
  bool served = false;
  EXPECT_NEAR(edge.reach(Vector3d(0.609, 0.5, 0.5), 0.01, 0.01, &served), 2.0 / 3.0 - 0.609, 1e-12);
  EXPECT_TRUE(served);
}

TEST(HaloSurface, PosedShapeReachesOnlyNearItsTriangles) {
  // a torus (R 4, r 1) tilted about x, centred at (1, 2, 3): its hole is inside its bounding
  // sphere but far from its surface
  const geometry::RigidShape torus = geometry::RigidShape::fromMesh(geometry::torusMesh(4.0, 1.0, 48, 16));
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Vector3d::UnitX()));
  const Vector3d c(1, 2, 3);
  const PosedShapeSurface s(torus, c, q);
  EXPECT_NEAR(s.extent(), 5.0, 1e-9);
  // the shape's body frame may differ from the mesh frame: place points through the mesh frame
  const Eigen::Quaterniond meshToWorld = q * Eigen::Quaterniond(torus.meshRotation).conjugate();
  const auto world = [&](const Vector3d& m) {
    return Vector3d(meshToWorld * (m - torus.centreOfMassInMesh) + c);
  };
  EXPECT_FALSE(s.within(world(Vector3d(0, 0, 0)), 2.9));   // the hole's centre: 3 from the tube
  EXPECT_TRUE(s.within(world(Vector3d(0, 0, 0)), 3.05));
  EXPECT_TRUE(s.within(world(Vector3d(4, 0, 1.2)), 0.25));  // just above the tube
  EXPECT_FALSE(s.within(world(Vector3d(4, 0, 1.2)), 0.15));
}

// ---------------------------------------------------------------------------------------------
// The exchange model

namespace {

struct Particle {
  Vector3d x;
  double r;
  int surface = -1;  // index into Scene::surfaces (an obstacle), -1: a sphere
};

struct Scene {
  Vector3d lo{0, 0, 0}, hi{1, 1, 1};
  std::array<bool, 3> periodic{{true, true, true}};
  std::array<int, 3> procs{{1, 1, 1}};
  double skin = 0.0, factor = 1.0;
  std::vector<Particle> particles;
  std::vector<std::unique_ptr<geometry::RigidShape>> shapes;
  std::vector<std::unique_ptr<PosedShapeSurface>> surfaces;

  // built at the first use, after the scene is set up
  const SubdomainGrid& grid() const {
    if (!grid_) grid_.reset(new SubdomainGrid(lo, hi, periodic, uniformSplits(procs)));
    return *grid_;
  }
  mutable std::unique_ptr<SubdomainGrid> grid_;
  double length(int d) const { return hi[d] - lo[d]; }
  std::array<int, 3> ownerBox(const Vector3d& x) const {
    std::array<int, 3> b{};
    const SubdomainGrid& g = grid();
    for (int d = 0; d < 3; ++d) {
      int i = 0;
      while (i + 1 < procs[std::size_t(d)] && g.cut(d, i + 1) <= x[d]) ++i;
      b[std::size_t(d)] = i;
    }
    return b;
  }
  int rank(const std::array<int, 3>& b) const { return (b[2] * procs[1] + b[1]) * procs[0] + b[0]; }
  int ranks() const { return procs[0] * procs[1] * procs[2]; }
};

// A copy of particle `id` held by a rank: shift = the image (in box lengths) of its coordinates.
using Copy = std::tuple<int, int, int, int>;  // id, shift x, y, z

struct Exchange {
  std::vector<std::set<Copy>> held;  // per rank: owned (shift 0) and ghosts
  std::size_t ghosts = 0;
};

std::vector<std::array<int, 3>> imageShifts(const Scene& s) {
  std::vector<std::array<int, 3>> out;
  for (int a = -1; a <= 1; ++a)
    for (int b = -1; b <= 1; ++b)
      for (int c = -1; c <= 1; ++c) {
        const std::array<int, 3> t{{a, b, c}};
        bool ok = true;
        for (int d = 0; d < 3; ++d) ok = ok && (s.periodic[std::size_t(d)] || t[std::size_t(d)] == 0);
        if (ok) out.push_back(t);
      }
  return out;
}

Vector3d shifted(const Scene& s, const Vector3d& x, const std::array<int, 3>& t) {
  return x + Vector3d(t[0] * s.length(0), t[1] * s.length(1), t[2] * s.length(2));
}

// Sends particle p with reach c from its owner to every subdomain image within L-infinity
// distance c (the Cartesian exchange; reaches stay below a box length, so images +-1 suffice).
void deliver(const Scene& s, int p, double c, Exchange& e) {
  const SubdomainGrid& g = s.grid();
  const Particle& q = s.particles[std::size_t(p)];
  const std::array<int, 3> home = s.ownerBox(q.x);
  for (const auto& t : imageShifts(s))
    for (int i = 0; i < s.procs[0]; ++i)
      for (int j = 0; j < s.procs[1]; ++j)
        for (int k = 0; k < s.procs[2]; ++k) {
          const std::array<int, 3> box{{i, j, k}};
          if (box == home && t == std::array<int, 3>{{0, 0, 0}}) continue;
          if (g.distanceToBox(q.x, box, t) > c) continue;
          // the box in image t holds the particle at x - t L
          if (e.held[std::size_t(s.rank(box))].insert(Copy{p, -t[0], -t[1], -t[2]}).second) ++e.ghosts;
        }
}

// The multilevel rule: classes coarse first; each rank computes its owned particles' reaches
// from the coarser ghosts it holds.
Exchange multilevel(const Scene& s, double ratio) {
  Exchange e;
  e.held.resize(std::size_t(s.ranks()));
  double rmax = 0.0;
  for (const Particle& p : s.particles) rmax = std::max(rmax, p.r);
  const HaloSizeClasses classes(rmax, ratio);
  std::vector<double> largest(std::size_t(classes.count()), -1.0);
  for (const Particle& p : s.particles) {
    double& l = largest[std::size_t(classes.classOf(p.r))];
    l = std::max(l, p.r);
  }
  for (std::size_t p = 0; p < s.particles.size(); ++p)
    e.held[std::size_t(s.rank(s.ownerBox(s.particles[p].x)))].insert(Copy{int(p), 0, 0, 0});

  HaloRule rule;
  rule.skin = s.skin;
  rule.contactFactor = s.factor;
  rule.slack = 1e-12;
  std::vector<HaloReach> rankReach(std::size_t(s.ranks()), HaloReach(rule, s.grid()));
  for (int i = 0; i < s.procs[0]; ++i)
    for (int j = 0; j < s.procs[1]; ++j)
      for (int k = 0; k < s.procs[2]; ++k) {
        const SubdomainGrid& g = s.grid();
        rankReach[std::size_t(s.rank({{i, j, k}}))].setOwnBox(
            Vector3d(g.cut(0, i), g.cut(1, j), g.cut(2, k)),
            Vector3d(g.cut(0, i + 1), g.cut(1, j + 1), g.cut(2, k + 1)));
      }
  std::vector<std::unique_ptr<PosedShapeSurface>> ghostSurfaces;  // obstacles at their images
  std::vector<std::size_t> ghostsBefore(std::size_t(s.ranks()), 0);
  for (int k = 0; k < classes.count(); ++k) {
    if (largest[std::size_t(k)] < 0.0) continue;
    // reaches first (from what each rank holds now), then the sends of this pass
    std::vector<std::pair<int, double>> sends;
    for (std::size_t p = 0; p < s.particles.size(); ++p) {
      const Particle& q = s.particles[p];
      if (classes.classOf(q.r) != k) continue;
      const HaloReach& h = rankReach[std::size_t(s.rank(s.ownerBox(q.x)))];
      sends.emplace_back(int(p), h.reach(q.x, q.r, largest[std::size_t(k)]));
    }
    for (const auto& sr : sends) deliver(s, sr.first, sr.second, e);
    // the ghosts of this class become partners of the finer classes on their rank
    for (int rank = 0; rank < s.ranks(); ++rank) {
      HaloReach& h = rankReach[std::size_t(rank)];
      for (const Copy& c : e.held[std::size_t(rank)]) {
        const int id = std::get<0>(c);
        const Particle& q = s.particles[std::size_t(id)];
        const bool ghost = std::get<1>(c) != 0 || std::get<2>(c) != 0 || std::get<3>(c) != 0 ||
                           s.rank(s.ownerBox(q.x)) != rank;
        if (!ghost || classes.classOf(q.r) != k) continue;
        const Vector3d x = shifted(s, q.x, {{std::get<1>(c), std::get<2>(c), std::get<3>(c)}});
        const HaloSurface* surface = nullptr;
        if (q.surface >= 0) {
          ghostSurfaces.emplace_back(
              new PosedShapeSurface(*s.shapes[std::size_t(q.surface)], x, Eigen::Quaterniond::Identity()));
          surface = ghostSurfaces.back().get();
        }
        h.addPartner(x, q.r, surface);
      }
      h.indexPartners(largest[std::size_t(k)]);
    }
  }
  return e;
}

// LIGGGHTS' single shell: every particle reaches (r_i + r_max) f + skin.
Exchange singleShell(const Scene& s) {
  Exchange e;
  e.held.resize(std::size_t(s.ranks()));
  double rmax = 0.0;
  for (const Particle& p : s.particles) rmax = std::max(rmax, p.r);
  for (std::size_t p = 0; p < s.particles.size(); ++p) {
    e.held[std::size_t(s.rank(s.ownerBox(s.particles[p].x)))].insert(Copy{int(p), 0, 0, 0});
    deliver(s, int(p), (s.particles[p].r + rmax) * s.factor + s.skin, e);
  }
  return e;
}

// Every pair that can touch is on both particles' ranks. For an obstacle (a surface), the
// particle's rank needs it by its bounding sphere (the neighbour list pairs them so), the
// obstacle's rank needs the particle only near the surface. Returns the pairs checked.
std::size_t expectComplete(const Scene& s, const Exchange& e) {
  std::size_t pairs = 0;
  double rmax = 0.0;
  for (const Particle& p : s.particles) rmax = std::max(rmax, p.r);
  const double cutmax = 2.0 * rmax * s.factor + s.skin;
  for (std::size_t i = 0; i < s.particles.size(); ++i) {
    const Particle& a = s.particles[i];
    const auto& held = e.held[std::size_t(s.rank(s.ownerBox(a.x)))];
    for (std::size_t j = 0; j < s.particles.size(); ++j) {
      const Particle& b = s.particles[j];
      if (a.surface >= 0 && b.surface >= 0) continue;  // obstacles never meet
      // the images of b that can be within the largest cut-off of a, per dimension
      int near[3][3], count[3] = {0, 0, 0};
      for (int d = 0; d < 3; ++d)
        for (int t = -1; t <= 1; ++t)
          if ((t == 0 || s.periodic[std::size_t(d)]) &&
              std::abs(b.x[d] + t * s.length(d) - a.x[d]) <= cutmax)
            near[d][count[d]++] = t;
      for (int ix = 0; ix < count[0]; ++ix)
        for (int iy = 0; iy < count[1]; ++iy)
          for (int iz = 0; iz < count[2]; ++iz) {
            const int tx = near[0][ix], ty = near[1][iy], tz = near[2][iz];
            if (i == j && tx == 0 && ty == 0 && tz == 0) continue;
            const Vector3d xb = shifted(s, b.x, {{tx, ty, tz}});
            const double dist = (a.x - xb).norm();
            bool needed;
            if (a.surface >= 0) {  // a is the obstacle (posed at a.x): its rank needs b near its surface
              const HaloSurface& surface = *s.surfaces[std::size_t(a.surface)];
              const double halo = a.r - surface.extent();
              needed = surface.within(xb, (b.r + 2 * halo) * s.factor + s.skin);
            } else {
              needed = dist <= (a.r + b.r) * s.factor + s.skin;
            }
            if (!needed) continue;
            ++pairs;
            EXPECT_TRUE(held.count(Copy{int(j), tx, ty, tz}))
                << "particle " << j << " (r " << b.r << ") image (" << tx << "," << ty << "," << tz
                << ") missing next to " << i << " (r " << a.r << "), distance " << dist;
            if (::testing::Test::HasFailure()) return pairs;
          }
    }
  }
  return pairs;
}

void addSpheres(Scene& s, std::mt19937_64& rng, int n, double rmin, double rmax, bool logUniform) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int i = 0; i < n; ++i) {
    Particle p;
    for (int d = 0; d < 3; ++d) p.x[d] = s.lo[d] + u(rng) * s.length(d);
    p.r = logUniform ? rmin * std::pow(rmax / rmin, u(rng)) : (u(rng) < 0.5 ? rmin : rmax);
    s.particles.push_back(p);
  }
}

struct Case {
  const char* name;
  std::array<int, 3> procs;
  std::array<bool, 3> periodic;
  bool continuous;
  double ghostRatio;  // at most this fraction of the single shell's ghosts
};

}  // namespace

class HaloExchangeModel : public ::testing::TestWithParam<Case> {};

TEST_P(HaloExchangeModel, EveryTouchablePairOnBothRanksWithFewerGhosts) {
  const Case& c = GetParam();
  Scene s;
  s.hi = Vector3d(1.0, 0.9, 0.8);
  s.procs = c.procs;
  s.periodic = c.periodic;
  s.skin = 0.004;
  s.factor = 1.0;
  std::mt19937_64 rng(4242);
  if (c.continuous) {
    addSpheres(s, rng, 3000, 0.006, 0.08, true);  // 1 : 13, log-uniform
  } else {
    addSpheres(s, rng, 4000, 0.01, 0.01, false);  // small ones
    addSpheres(s, rng, 12, 0.12, 0.12, false);     // big ones (1 : 12)
  }
  const Exchange ml = multilevel(s, 2.0);
  const std::size_t pairs = expectComplete(s, ml);
  const Exchange single = singleShell(s);
  EXPECT_GT(pairs, 1000u);
  EXPECT_LE(ml.ghosts, single.ghosts);
  // the point of the rule: on these packs far fewer ghosts than the single shell
  EXPECT_LT(double(ml.ghosts), c.ghostRatio * double(single.ghosts))
      << c.name << ": multilevel " << ml.ghosts << " vs single shell " << single.ghosts;
  std::printf("  %-26s pairs %zu, ghosts multilevel %zu, single shell %zu\n", c.name, pairs,
              ml.ghosts, single.ghosts);
}

INSTANTIATE_TEST_SUITE_P(
    Packs, HaloExchangeModel,
    ::testing::Values(Case{"bi_periodic_1rank", {{1, 1, 1}}, {{true, true, true}}, false, 0.4},
                      Case{"bi_periodic_2x2x2", {{2, 2, 2}}, {{true, true, true}}, false, 0.4},
                      Case{"bi_walled_2x2x1", {{2, 2, 1}}, {{false, false, false}}, false, 0.4},
                      Case{"cont_periodic_3x2x1", {{3, 2, 1}}, {{true, true, false}}, true, 0.9},
                      Case{"cont_walled_2x1x2", {{2, 1, 2}}, {{false, false, false}}, true, 0.9}),
    [](const ::testing::TestParamInfo<Case>& info) { return std::string(info.param.name); });

TEST(HaloExchangeModel, ObstaclesReachByTheirSurface) {
  // a torus obstacle spanning most of a 2 x 2 x 1 periodic box (its bounding sphere reaches
  // every small particle) among small spheres: the small ones next to its tube must reach the
  // obstacle's rank, those in its hole or far above it need not
  Scene s;
  s.hi = Vector3d(1.0, 1.0, 0.6);
  s.procs = {{2, 2, 1}};
  s.periodic = {{true, true, false}};
  s.skin = 0.004;
  s.shapes.emplace_back(new geometry::RigidShape(
      geometry::RigidShape::fromMesh(geometry::torusMesh(0.3, 0.06, 48, 12))));
  const double eps = 0.001;
  const Vector3d centre(0.52, 0.47, 0.3);
  s.surfaces.emplace_back(new PosedShapeSurface(*s.shapes[0], centre, Eigen::Quaterniond::Identity()));
  Particle obstacle;
  obstacle.x = centre;
  obstacle.r = s.shapes[0]->boundingRadius + eps;
  obstacle.surface = 0;
  s.particles.push_back(obstacle);
  std::mt19937_64 rng(7);
  addSpheres(s, rng, 4000, 0.008, 0.008, false);
  const Exchange ml = multilevel(s, 2.0);
  const std::size_t pairs = expectComplete(s, ml);
  EXPECT_GT(pairs, 2000u);
  // how many small ones reach the obstacle's rank as ghosts, against the bounding-sphere rule
  const int obstacleRank = s.rank(s.ownerBox(centre));
  std::size_t onObstacleRank = 0, boundingNeeds = 0;
  for (std::size_t p = 1; p < s.particles.size(); ++p) {
    const Particle& q = s.particles[p];
    if (s.rank(s.ownerBox(q.x)) == obstacleRank) continue;
    for (const Copy& c : ml.held[std::size_t(obstacleRank)]) onObstacleRank += std::get<0>(c) == int(p);
    boundingNeeds += (q.x - centre).norm() <= obstacle.r + q.r + s.skin;
  }
  EXPECT_LT(onObstacleRank, boundingNeeds / 2) << onObstacleRank << " vs " << boundingNeeds;
  std::printf("  torus: pairs %zu, small ghosts on the obstacle's rank %zu (bounding sphere: %zu)\n",
              pairs, onObstacleRank, boundingNeeds);
}
