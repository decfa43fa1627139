// The pair check of triangulated particles in world coordinates with the hybrid triangle
// distance (geometry/HybridTriangleDistance.h): every triangle pair of a row range, in batches
// of the vectorised penalty kernel, exact fallback where it cannot be trusted; a triangle pair
// is a contact when its distance is below the contact distance T (the paper's 2 eps).
#pragma once

#include "geometry/HybridTriangleDistance.h"
#include "parallel/PairCheck.h"
#include "parallel/PosedMeshes.h"

namespace spacetree::parallel {

class PosedMeshPairCheck : public PairCheck {
 public:
  // `meshes` must outlive the check; options.contactDistance is T and must be > 0.
  // Throws std::invalid_argument otherwise.
  PosedMeshPairCheck(const PosedMeshes& meshes, const geometry::HybridOptions& options);

  std::size_t triangleCount(int particle) const override { return meshes_.triangleCount(particle); }
  void check(int first, int second, std::size_t firstBegin, std::size_t firstEnd,
             ContactSink& sink) const override;

 private:
  const PosedMeshes& meshes_;
  geometry::HybridOptions options_;
};

}  // namespace spacetree::parallel
