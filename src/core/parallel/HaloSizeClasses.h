// Size classes of the multilevel ghost rule (paper §8: not one halo layer but a cascade, each
// layer thin). Class 0 holds the largest radii, r > rmax / q; class k the radii in
// (rmax / q^(k+1), rmax / q^k]; the last class everything smaller (radius 0 included). Every
// rank builds the same classes from the same global rmax, so that the classes, and with them
// the exchange passes (coarse classes first), agree on all ranks.
#pragma once

#include <vector>

namespace spacetree::parallel {

class HaloSizeClasses {
 public:
  static constexpr int kMaxClasses = 16;

  HaloSizeClasses() = default;  // a single class
  // largestRadius >= 0, ratio > 1, 1 <= classes <= kMaxClasses (std::invalid_argument otherwise).
  HaloSizeClasses(double largestRadius, double ratio, int classes = kMaxClasses);

  int count() const { return int(lower_.size()) + 1; }
  double ratio() const { return ratio_; }
  // 0 = coarsest; the same result for the same radius on every rank (plain comparisons).
  int classOf(double radius) const;
  // Radii of class k are <= upperBound(k) (= rmax / q^k) and > lowerBound(k) (0 for the last).
  double upperBound(int k) const;
  double lowerBound(int k) const;

 private:
  double largest_ = 0.0, ratio_ = 2.0;
  std::vector<double> lower_;  // lower_[k] = rmax / q^(k+1), k < count() - 1
};

}  // namespace spacetree::parallel
