// A contact point found by a pair check: which two triangles of which two particles are closer
// than the contact distance, how far apart they are and where. The canonical order (particle
// pair, then triangle pair) is the one deterministic order every reduction runs in, so that
// sums do not depend on which thread found which contact first.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <tuple>
#include <vector>

namespace spacetree::parallel {

struct TriangleContact {
  std::int32_t first = 0, second = 0;                  // particle ids, first < second
  std::int32_t firstTriangle = 0, secondTriangle = 0;  // triangle indices within each particle
  double distance = 0.0;                               // triangle-to-triangle distance
  Eigen::Vector3d pointOnFirst = Eigen::Vector3d::Zero();
  Eigen::Vector3d pointOnSecond = Eigen::Vector3d::Zero();
  // Unit contact normal from the first particle towards the second; zero where the check does
  // not define one (touching triangles of PosedMeshPairCheck).
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
};

// The canonical order: by (first, second, firstTriangle, secondTriangle); sorted stably, so
// that contacts of one triangle pair (a check that reports several points per triangle pair,
// e.g. MeshContact's vertex contacts, and checks whole pairs in one task) keep the order their
// check gave them.
inline bool canonicalContactLess(const TriangleContact& a, const TriangleContact& b) {
  return std::tie(a.first, a.second, a.firstTriangle, a.secondTriangle) <
         std::tie(b.first, b.second, b.firstTriangle, b.secondTriangle);
}

// Where a pair check puts its contacts: the buffer of the task it runs in, owned by that task
// alone (no lock, no atomic on the hot path).
class ContactSink {
 public:
  explicit ContactSink(std::vector<TriangleContact>& buffer) : buffer_(buffer) {}
  void add(const TriangleContact& contact) { buffer_.push_back(contact); }

 private:
  std::vector<TriangleContact>& buffer_;
};

}  // namespace spacetree::parallel
