// The de-duplication of raw contacts (contact/ContactMerging.h): copies of one contact count once,
// contacts a merge length apart count in full, and the springs the merged points carry (sum of
// weight x penetration, and its moment) do not jump when a raw contact changes points. A jump
// there kept a 1000-grain heap rocking at ~1e-8 of its peak kinetic energy: a grain resting on a
// neighbour at two raw contacts 0.39 mm apart (merge length ~0.4 mm) got a third point for one
// step every 37 steps, its normal force jumping by 1.9e-3 N (1.5 times its weight), because a
// raw contact entering the halo at the list's front seeded a point that captured a deeper one.
#include <gtest/gtest.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "contact/ContactMerging.h"
#include "contact/MeshContact.h"

using spacetree::contact::ContactMerger;
using spacetree::contact::ContactPoint;
using spacetree::contact::MeshContactOptions;
using Eigen::Vector3d;

namespace {

constexpr double kEps = 1e-4;          // halo depth [m]
constexpr double kMerge = 4e-4;        // merge length [m]
constexpr double kPenetration = 1e-5;  // [m]

ContactPoint raw(double x, double penetration, const Vector3d& normal = Vector3d::UnitZ()) {
  ContactPoint c;
  c.point = Vector3d(x, 0.0, 0.0);
  c.normal = normal.normalized();
  c.penetration = penetration;
  c.distance = 2.0 * (kEps - penetration);
  return c;
}

MeshContactOptions options() {
  MeshContactOptions o;
  o.epsilon = kEps;
  return o;
}

struct Springs {
  std::size_t points = 0;
  std::vector<ContactPoint> merged;
  double load = 0.0;             // sum of weight * penetration [m]: the springs' force / S
  Vector3d moment = Vector3d::Zero();  // sum of point x (weight * penetration * normal)
};

Springs merged(const std::vector<ContactPoint>& contacts) {
  ContactMerger merger;
  std::vector<ContactPoint> out;
  Springs s;
  s.points = merger.merge(contacts, kMerge, options(), out);
  s.merged = out;
  for (const ContactPoint& c : out) {
    s.load += c.weight * c.penetration;
    s.moment += c.point.cross(c.weight * c.penetration * c.normal);
  }
  return s;
}

}  // namespace

TEST(ContactMerging, CopiesOfOneContactCountOnce) {
  // a vertex on a face, found on each of the three triangles around the vertex
  const Springs s = merged({raw(0.0, kPenetration), raw(0.0, kPenetration), raw(0.0, kPenetration)});
  EXPECT_EQ(s.points, 1u);
  EXPECT_NEAR(s.load, kPenetration, 1e-12 * kPenetration);
  // a face lying on a face: the kernel's point lies anywhere between the face's corners; within
  // half a merge length of a corner's contact it is that contact again, not a second spring
  const Springs face = merged({raw(0.0, kPenetration), raw(0.45 * kMerge, kPenetration)});
  EXPECT_EQ(face.points, 1u);
  EXPECT_NEAR(face.load, kPenetration, 1e-12 * kPenetration);
}

TEST(ContactMerging, ContactsAMergeLengthApartCountInFull) {
  const Springs apart = merged({raw(0.0, kPenetration), raw(1.01 * kMerge, 0.5 * kPenetration)});
  EXPECT_EQ(apart.points, 2u);
  EXPECT_NEAR(apart.load, 1.5 * kPenetration, 1e-12 * kPenetration);
  // normals beyond the merge cosine (0.9): two faces of a crease, each a contact of its own
  const Springs crease = merged({raw(0.0, kPenetration, Vector3d(0, 0, 1)),
                                 raw(0.1 * kMerge, kPenetration, Vector3d(0.5, 0, 1))});
  EXPECT_EQ(crease.points, 2u);
  EXPECT_NEAR(crease.load, 2.0 * kPenetration, 1e-12 * kPenetration);
}

TEST(ContactMerging, SpringsDoNotJumpWhenAContactLeavesAPoint) {
  // the second raw contact just inside and just outside the merge length of the first: one
  // point, then two; the springs and their moment change by O(delta), not by its penetration
  const double delta = 1e-6;
  const Springs inside = merged({raw(0.0, kPenetration), raw((1.0 - delta) * kMerge, 0.5 * kPenetration)});
  const Springs outside = merged({raw(0.0, kPenetration), raw((1.0 + delta) * kMerge, 0.5 * kPenetration)});
  EXPECT_EQ(inside.points, 1u);
  EXPECT_EQ(outside.points, 2u);
  EXPECT_NEAR(inside.load, outside.load, 1e-4 * kPenetration);
  EXPECT_LT((inside.moment - outside.moment).norm(), 1e-4 * kPenetration * kMerge);
  // the same with a pair of near contacts (A, B: 0.2 merge lengths apart, partly copies of each
  // other) that C leaves: their point's mean is 0.1 merge lengths from A
  const ContactPoint a = raw(0.0, kPenetration), b = raw(0.2 * kMerge, kPenetration);
  const Springs joined = merged({a, b, raw((1.1 - delta) * kMerge, 0.5 * kPenetration)});
  const Springs left = merged({a, b, raw((1.1 + delta) * kMerge, 0.5 * kPenetration)});
  EXPECT_EQ(joined.points, 1u);
  EXPECT_EQ(left.points, 2u);
  EXPECT_NEAR(joined.load, left.load, 1e-4 * kPenetration);
  EXPECT_LT((joined.moment - left.moment).norm(), 1e-4 * kPenetration * kMerge);
  // and nearer together the two count as less than two contacts, smoothly down to one
  double previous = merged({raw(0.0, kPenetration), raw(0.0, 0.5 * kPenetration)}).load;
  // at one place: one spring, of the mean penetration weighted by the penetrations
  EXPECT_NEAR(previous, (1.0 + 0.25) / 1.5 * kPenetration, 1e-12 * kPenetration);
  for (int k = 1; k <= 20; ++k) {
    const double load = merged({raw(0.0, kPenetration), raw(0.05 * k * kMerge, 0.5 * kPenetration)}).load;
    EXPECT_GE(load, previous - 1e-15);
    EXPECT_LT(load - previous, 0.25 * kPenetration);  // no step of the size of a contact
    previous = load;
  }
  EXPECT_NEAR(previous, 1.5 * kPenetration, 1e-12 * kPenetration);
}

TEST(ContactMerging, AContactEnteringTheHaloMovesNoForce) {
  // C and A 0.7 merge lengths apart form one point; S, entering the halo (penetration ~0),
  // lies within a merge length of A but not of C. Found first, it must not split C and A.
  const ContactPoint c = raw(0.0, 0.5 * kPenetration), a = raw(0.7 * kMerge, kPenetration),
                     s = raw(1.5 * kMerge, 1e-12 * kPenetration);
  const Springs without = merged({c, a});
  const Springs with = merged({s, c, a});
  EXPECT_NEAR(with.load, without.load, 1e-9 * kPenetration);
  EXPECT_LT((with.moment - without.moment).norm(), 1e-9 * kPenetration * kMerge);
  // nor the point of C and A (the tangential spring it keeps stays where it acts): S joins it or
  // starts a point of its own, it does not capture A
  ASSERT_EQ(without.points, 1u);
  const ContactPoint& held = without.merged[0];
  const bool kept = std::any_of(with.merged.begin(), with.merged.end(), [&](const ContactPoint& p) {
    return (p.point - held.point).norm() < 1e-6 * kMerge && std::abs(p.weight * p.penetration -
                                                                      held.weight * held.penetration) < 1e-6 * kPenetration;
  });
  EXPECT_TRUE(kept);
}

TEST(ContactMerging, TheSpringsDoNotDependOnTheOrderOfTheRawContacts) {
  std::vector<ContactPoint> contacts;
  std::mt19937 random(3);
  std::uniform_real_distribution<double> along(0.0, 3.0 * kMerge), depth(0.1, 1.0), tilt(-0.3, 0.3);
  for (int k = 0; k < 12; ++k)
    contacts.push_back(raw(along(random), depth(random) * kPenetration, Vector3d(tilt(random), 0.0, 1.0)));
  const Springs reference = merged(contacts);
  for (int shuffle = 0; shuffle < 20; ++shuffle) {
    std::shuffle(contacts.begin(), contacts.end(), random);
    const Springs s = merged(contacts);
    EXPECT_NEAR(s.load, reference.load, 1e-12 * kPenetration);
    EXPECT_LT((s.moment - reference.moment).norm(), 1e-12 * kPenetration * kMerge);
  }
}
