#include "parallel/MeshContactPairCheck.h"

#include <stdexcept>

namespace spacetree::parallel {

MeshContactPairCheck::MeshContactPairCheck(const std::vector<const geometry::RigidShape*>& shapes,
                                           const std::vector<contact::Pose>& poses,
                                           const contact::MeshContactOptions& options)
    : shapes_(shapes), poses_(poses), threadStates_(options) {
  if (!(options.epsilon > 0.0))
    throw std::invalid_argument("MeshContactPairCheck: epsilon must be > 0");
  if (shapes.size() != poses.size())
    throw std::invalid_argument("MeshContactPairCheck: one shape and one pose per particle");
  contact::validateMeshContactOptions(options);  // here, not in the first task's finder
}

void MeshContactPairCheck::check(int first, int second, std::size_t firstBegin,
                                 std::size_t firstEnd, ContactSink& sink) const {
  if (firstBegin != 0 || firstEnd != triangleCount(first))
    throw std::logic_error("MeshContactPairCheck: pairs are not splittable");
  ThreadState& state = threadStates_.local();
  state.points.clear();
  state.finder.find(*shapes_[std::size_t(first)], poses_[std::size_t(first)],
                    *shapes_[std::size_t(second)], poses_[std::size_t(second)], state.points,
                    &state.statistics);
  for (const contact::ContactPoint& p : state.points) {
    TriangleContact c;
    c.first = first;
    c.second = second;
    c.firstTriangle = p.firstTriangle;
    c.secondTriangle = p.secondTriangle;
    c.distance = p.distance;
    c.normal = p.normal;
    c.pointOnFirst = p.point - (0.5 * p.distance) * p.normal;
    c.pointOnSecond = p.point + (0.5 * p.distance) * p.normal;
    sink.add(c);
  }
}

contact::MeshContactStatistics MeshContactPairCheck::statistics() const {
  contact::MeshContactStatistics total;
  for (const ThreadState& s : threadStates_) total += s.statistics;
  return total;
}

}  // namespace spacetree::parallel
