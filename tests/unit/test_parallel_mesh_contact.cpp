// Task-parallel pair checks through the mesh-contact search (contact/MeshContact.h): dented
// rigid spheres (three templates) in a dense random pack, their contacts found by the spacetree
// sweep as task producer on 1, 2 and 4 threads, against MeshContactFinder called serially on
// every pair: the same contacts bit for bit (after the search's own de-duplication) and
// bit-identical force sums.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/DentedSphere.h"
#include "geometry/RigidShape.h"
#include "parallel/ContactForceSum.h"
#include "parallel/MeshContactPairCheck.h"
#include "parallel/TaskParallelPairChecks.h"
#include "tree/Spacetree.h"

using namespace spacetree;
using namespace spacetree::parallel;

namespace {

constexpr double kRadius = 1e-3;
constexpr double kEpsilon = 0.01 * kRadius;

struct DentedPack {
  std::vector<geometry::RigidShape> templates;
  std::vector<const geometry::RigidShape*> shapes;
  std::vector<contact::Pose> poses;
  std::vector<std::array<double, 3>> centre;
  std::vector<double> radius;
  contact::MeshContactOptions options;
  Spacetree tree{SpacetreeOptions{kEpsilon, kMaxSpacetreeLevel}};

  explicit DentedPack(int n) {
    for (std::uint64_t seed : {1, 2, 3}) {
      geometry::DentedSphereOptions d;
      d.triangles = 60;
      d.radius = kRadius;
      d.amplitude = 0.1;
      d.seed = seed;
      templates.push_back(geometry::RigidShape::fromMesh(geometry::dentedSphere(d)));
    }
    std::mt19937_64 random(5);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    std::normal_distribution<double> gaussian;
    const int side = int(std::ceil(std::cbrt(double(n))));
    for (int p = 0; p < n; ++p) {
      const geometry::RigidShape* s = &templates[std::size_t(p % 3)];
      contact::Pose pose;
      const int i = p % side, j = (p / side) % side, k = p / (side * side);
      pose.position = Eigen::Vector3d(1.9 * kRadius * i + 0.05 * kRadius * unit(random),
                                      1.9 * kRadius * j + 0.05 * kRadius * unit(random),
                                      1.9 * kRadius * k + 0.05 * kRadius * unit(random));
      pose.orientation = Eigen::Quaterniond(gaussian(random), gaussian(random), gaussian(random),
                                            gaussian(random)).normalized();
      shapes.push_back(s);
      poses.push_back(pose);
      centre.push_back({pose.position.x(), pose.position.y(), pose.position.z()});
      radius.push_back(s->boundingRadius);
    }
    options.epsilon = kEpsilon;
    tree.build(reinterpret_cast<const double(*)[3]>(centre.data()), radius.data(), n, n);
  }
  int size() const { return int(poses.size()); }
};

std::vector<TriangleContact> serialReference(const DentedPack& pack) {
  contact::MeshContactFinder finder(pack.options);
  std::vector<TriangleContact> contacts;
  std::vector<contact::ContactPoint> points;
  for (int i = 0; i < pack.size(); ++i)
    for (int j = i + 1; j < pack.size(); ++j) {
      points.clear();
      finder.find(*pack.shapes[i], pack.poses[i], *pack.shapes[j], pack.poses[j], points);
      for (const contact::ContactPoint& p : points) {
        TriangleContact c;
        c.first = i;
        c.second = j;
        c.firstTriangle = p.firstTriangle;
        c.secondTriangle = p.secondTriangle;
        c.distance = p.distance;
        c.normal = p.normal;
        c.pointOnFirst = p.point - (0.5 * p.distance) * p.normal;
        c.pointOnSecond = p.point + (0.5 * p.distance) * p.normal;
        contacts.push_back(c);
      }
    }
  std::stable_sort(contacts.begin(), contacts.end(), canonicalContactLess);
  return contacts;
}

// Spring on the halo overlap along the contact normal (eq. (1) without damping).
std::vector<Eigen::Vector3d> forceSums(int n, const std::vector<TriangleContact>& contacts) {
  std::vector<Eigen::Vector3d> force;
  sumContactForces(contacts, n, [](const TriangleContact& c) {
    return Eigen::Vector3d(-1e4 * (kEpsilon - 0.5 * c.distance) * c.normal);
  }, force);
  return force;
}

bool sameBits(const void* a, const void* b, std::size_t n) { return std::memcmp(a, b, n) == 0; }

void expectBitIdentical(const std::vector<TriangleContact>& e, const std::vector<TriangleContact>& a,
                        const std::string& what) {
  ASSERT_EQ(e.size(), a.size()) << what;
  for (std::size_t k = 0; k < e.size(); ++k) {
    ASSERT_TRUE(e[k].first == a[k].first && e[k].second == a[k].second &&
                e[k].firstTriangle == a[k].firstTriangle &&
                e[k].secondTriangle == a[k].secondTriangle)
        << what << ": contact " << k;
    ASSERT_TRUE(sameBits(&e[k].distance, &a[k].distance, sizeof(double)) &&
                sameBits(e[k].normal.data(), a[k].normal.data(), 3 * sizeof(double)) &&
                sameBits(e[k].pointOnFirst.data(), a[k].pointOnFirst.data(), 3 * sizeof(double)))
        << what << ": contact " << k << " differs";
  }
}

}  // namespace

TEST(ParallelMeshContact, SameContactsAndBitIdenticalForcesFor1To4Threads) {
  static tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
  DentedPack pack(216);
  const std::vector<TriangleContact> reference = serialReference(pack);
  ASSERT_GT(reference.size(), 300u);  // a real pack: hundreds of de-duplicated contacts
  const std::vector<Eigen::Vector3d> referenceForce = forceSums(pack.size(), reference);
  int loaded = 0;
  for (const auto& f : referenceForce) loaded += f.norm() > 0.0;
  EXPECT_GT(loaded, 150);
  std::printf("[ info     ] %d dented spheres: %zu contacts (de-duplicated), %d particles loaded\n",
              pack.size(), reference.size(), loaded);

  for (int threads : {1, 2, 4})
    for (std::size_t grain : {std::size_t(1), std::size_t(20000)}) {
      MeshContactPairCheck check(pack.shapes, pack.poses, pack.options);
      EXPECT_FALSE(check.splittable());
      TaskParallelPairChecks engine(TaskParallelOptions{threads, grain});
      std::vector<TriangleContact> contacts;
      engine.run(pack.tree, check, contacts);
      const std::string what = std::to_string(threads) + " threads, grain " + std::to_string(grain);
      expectBitIdentical(reference, contacts, what);
      const std::vector<Eigen::Vector3d> force = forceSums(pack.size(), contacts);
      for (int p = 0; p < pack.size(); ++p)
        ASSERT_TRUE(sameBits(force[p].data(), referenceForce[p].data(), 3 * sizeof(double)))
            << what << ": particle " << p;
      EXPECT_EQ(engine.statistics().splitPairs, 0u) << what;  // de-duplication: whole pairs
      if (grain == 1) {
        EXPECT_EQ(engine.statistics().tasks, engine.statistics().pairs) << what;
      }
      // The search saw every candidate pair once, and de-duplicated something.
      const contact::MeshContactStatistics s = check.statistics();
      EXPECT_EQ(s.bodyPairs, engine.statistics().pairs) << what;
      EXPECT_GT(s.rawContacts, s.contacts) << what;
    }
}

TEST(ParallelMeshContact, RejectsBadInputAndRowRanges) {
  DentedPack pack(8);
  contact::MeshContactOptions zero;
  EXPECT_THROW(MeshContactPairCheck(pack.shapes, pack.poses, zero), std::invalid_argument);
  std::vector<contact::Pose> fewer(pack.poses.begin(), pack.poses.end() - 1);
  EXPECT_THROW(MeshContactPairCheck(pack.shapes, fewer, pack.options), std::invalid_argument);
  MeshContactPairCheck check(pack.shapes, pack.poses, pack.options);
  std::vector<TriangleContact> out;
  ContactSink sink(out);
  EXPECT_THROW(check.check(0, 1, 0, 1, sink), std::logic_error);
}
