#include "parallel/PosedMeshPairCheck.h"

#include <algorithm>
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
  const std::size_t columns = meshes_.triangleCount(second);
  if (firstEnd <= firstBegin || columns == 0) return;
  // Rows in chunks of about kChunkTrianglePairs results: bounded scratch (one buffer per thread,
  // no allocation in steady state, nothing shared), still full batches for the kernel. The
  // kernel's lanes are independent, so the chunking does not change any result.
  constexpr std::size_t kChunkTrianglePairs = 8192;
  const std::size_t chunkRows = std::max<std::size_t>(1, kChunkTrianglePairs / columns);
  thread_local std::vector<geometry::TriangleDistanceResult> distances;
  if (distances.size() < chunkRows * columns) distances.resize(chunkRows * columns);
  for (std::size_t begin = firstBegin; begin < firstEnd; begin += chunkRows) {
    const std::size_t rows = std::min(chunkRows, firstEnd - begin);
    geometry::hybridTriangleDistancesOfAllPairs(meshes_.trianglesOf(first) + begin, rows,
                                                meshes_.trianglesOf(second), columns, options_,
                                                distances.data());
    for (std::size_t r = 0; r < rows; ++r)
      for (std::size_t c = 0; c < columns; ++c) {
        const geometry::TriangleDistanceResult& d = distances[r * columns + c];
        if (!(d.distance < options_.contactDistance)) continue;
        TriangleContact contact;
        contact.first = first;
        contact.second = second;
        contact.firstTriangle = std::int32_t(begin + r);
        contact.secondTriangle = std::int32_t(c);
        contact.distance = d.distance;
        contact.pointOnFirst = d.pointOnFirst;
        contact.pointOnSecond = d.pointOnSecond;
        if (d.distance > 0.0) contact.normal = (d.pointOnSecond - d.pointOnFirst) / d.distance;
        sink.add(contact);
      }
  }
}

}  // namespace spacetree::parallel
