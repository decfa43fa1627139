#include "parallel/PosedMeshPairCheck.h"

#include <stdexcept>
#include <vector>

namespace spacetree::parallel {

PosedMeshPairCheck::PosedMeshPairCheck(const PosedMeshes& meshes,
                                       const geometry::HybridOptions& options)
    : meshes_(meshes), options_(options) {
  if (!(options.contactDistance > 0.0))
    throw std::invalid_argument("PosedMeshPairCheck: contactDistance must be > 0");
}

void PosedMeshPairCheck::check(int first, int second, std::size_t firstBegin,
                               std::size_t firstEnd, ContactSink& sink) const {
  const std::size_t rows = firstEnd - firstBegin;
  const std::size_t columns = meshes_.triangleCount(second);
  if (rows == 0 || columns == 0) return;
  // One scratch buffer per thread, grown to the largest task it ran: no allocation in steady
  // state, nothing shared between threads.
  thread_local std::vector<geometry::TriangleDistanceResult> distances;
  if (distances.size() < rows * columns) distances.resize(rows * columns);
  geometry::hybridTriangleDistancesOfAllPairs(meshes_.trianglesOf(first) + firstBegin, rows,
                                              meshes_.trianglesOf(second), columns, options_,
                                              distances.data());
  for (std::size_t r = 0; r < rows; ++r)
    for (std::size_t c = 0; c < columns; ++c) {
      const geometry::TriangleDistanceResult& d = distances[r * columns + c];
      if (!(d.distance < options_.contactDistance)) continue;
      TriangleContact contact;
      contact.first = first;
      contact.second = second;
      contact.firstTriangle = std::int32_t(firstBegin + r);
      contact.secondTriangle = std::int32_t(c);
      contact.distance = d.distance;
      contact.pointOnFirst = d.pointOnFirst;
      contact.pointOnSecond = d.pointOnSecond;
      sink.add(contact);
    }
}

}  // namespace spacetree::parallel
