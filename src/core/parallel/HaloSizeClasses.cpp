#include "parallel/HaloSizeClasses.h"

#include <cmath>
#include <stdexcept>

namespace spacetree::parallel {

HaloSizeClasses::HaloSizeClasses(double largestRadius, double ratio, int classes)
    : largest_(largestRadius), ratio_(ratio) {
  if (!(largestRadius >= 0.0) || !std::isfinite(largestRadius))
    throw std::invalid_argument("halo size classes: the largest radius must be finite and >= 0");
  if (!(ratio > 1.0) || !std::isfinite(ratio))
    throw std::invalid_argument("halo size classes: the ratio must be > 1");
  if (classes < 1 || classes > kMaxClasses)
    throw std::invalid_argument("halo size classes: between 1 and 16 classes");
  double bound = largestRadius;
  for (int k = 0; k + 1 < classes; ++k) {
    bound /= ratio;
    lower_.push_back(bound);
  }
}

int HaloSizeClasses::classOf(double radius) const {
  for (std::size_t k = 0; k < lower_.size(); ++k)
    if (radius > lower_[k]) return int(k);
  return int(lower_.size());
}

double HaloSizeClasses::upperBound(int k) const {
  return k == 0 ? largest_ : lower_[std::size_t(k - 1)];
}

double HaloSizeClasses::lowerBound(int k) const {
  return std::size_t(k) < lower_.size() ? lower_[std::size_t(k)] : 0.0;
}

}  // namespace spacetree::parallel
