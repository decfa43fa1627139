// Deterministic reduction of contact forces: contacts in canonical order (as the task engine
// returns them), summed one after the other into per-particle forces. Floating-point addition is
// not associative, so this fixed order is what makes the sums bit-identical for any thread count.
#pragma once

#include <Eigen/Core>

#include <vector>

#include "parallel/TriangleContact.h"

namespace spacetree::parallel {

// force[p] = sum over the contacts of p of forceLaw(contact) (on `first`; the opposite on
// `second`), added in the order of `contacts`. forceLaw: Eigen::Vector3d(const TriangleContact&).
template <class ForceLaw>
void sumContactForces(const std::vector<TriangleContact>& contacts, int particleCount,
                      ForceLaw&& forceLaw, std::vector<Eigen::Vector3d>& force) {
  force.assign(std::size_t(particleCount), Eigen::Vector3d::Zero());
  for (const TriangleContact& c : contacts) {
    const Eigen::Vector3d f = forceLaw(c);
    force[std::size_t(c.first)] += f;
    force[std::size_t(c.second)] -= f;
  }
}

}  // namespace spacetree::parallel
