// The pair check of rigid triangulated particles through the mesh-contact search of
// contact/MeshContact.h (bounding-sphere and approach prechecks, triangle pruning, hybrid
// distances, epsilon convention, de-duplication): one MeshContactFinder per thread, whole pairs
// only (de-duplication merges contacts across all triangle pairs of a pair, so a pair is not
// split at triangle level).
#pragma once

#include <oneapi/tbb/enumerable_thread_specific.h>

#include <vector>

#include "contact/MeshContact.h"
#include "geometry/RigidShape.h"
#include "parallel/PairCheck.h"

namespace spacetree::parallel {

class MeshContactPairCheck : public PairCheck {
 public:
  // shapes[p] and poses[p] of every particle p; the vectors (and shapes) must outlive the check.
  // Throws std::invalid_argument for options.epsilon <= 0, vectors of different sizes or Newton
  // step counts that validateMeshContactOptions rejects.
  MeshContactPairCheck(const std::vector<const geometry::RigidShape*>& shapes,
                       const std::vector<contact::Pose>& poses,
                       const contact::MeshContactOptions& options);

  std::size_t triangleCount(int particle) const override {
    return shapes_[std::size_t(particle)]->triangleCount();
  }
  bool splittable() const override { return false; }
  // TriangleContact from a ContactPoint: the triangles it was first found on, the surface
  // distance d, the normal, and the two surface points point -/+ normal d/2.
  void check(int first, int second, std::size_t firstBegin, std::size_t firstEnd,
             ContactSink& sink) const override;

  // Sum of every thread's search counters since construction (call between sweeps).
  contact::MeshContactStatistics statistics() const;

 private:
  struct ThreadState {
    explicit ThreadState(const contact::MeshContactOptions& options) : finder(options) {}
    contact::MeshContactFinder finder;
    std::vector<contact::ContactPoint> points;
    contact::MeshContactStatistics statistics;
  };
  const std::vector<const geometry::RigidShape*>& shapes_;
  const std::vector<contact::Pose>& poses_;
  mutable tbb::enumerable_thread_specific<ThreadState> threadStates_;
};

}  // namespace spacetree::parallel
