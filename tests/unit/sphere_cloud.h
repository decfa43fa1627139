// Spheres as the spacetree takes them (positions as double[3] rows, radii), for the tree tests.
#pragma once

#include <array>
#include <set>
#include <utility>
#include <vector>

namespace spacetree::testing {

struct SphereCloud {
  std::vector<std::array<double, 3>> x;
  std::vector<double> r;
  void add(double px, double py, double pz, double pr) {
    x.push_back({px, py, pz});
    r.push_back(pr);
  }
  int size() const { return int(r.size()); }
  const double (*positions() const)[3] { return reinterpret_cast<const double(*)[3]>(x.data()); }
  double distanceSquared(int i, int j) const {
    double d2 = 0.0;
    for (int d = 0; d < 3; ++d) d2 += (x[i][d] - x[j][d]) * (x[i][d] - x[j][d]);
    return d2;
  }
};

using PairSet = std::set<std::pair<int, int>>;

// Whether spheres i and j lie within the cut-off r_i + r_j + 2 eps (the tree's expression).
inline bool isPair(const SphereCloud& p, int i, int j, double eps) {
  const double cut = p.r[i] + p.r[j] + 2.0 * eps;
  return p.distanceSquared(i, j) <= cut * cut;
}

// The pairs (i < j) within the cut-off with at least one active sphere (i < nActive), O(N^2).
inline PairSet bruteForce(const SphereCloud& p, double eps, int nActive) {
  PairSet pairs;
  for (int i = 0; i < p.size(); ++i)
    for (int j = i + 1; j < p.size(); ++j)
      if ((i < nActive || j < nActive) && isPair(p, i, j, eps)) pairs.insert({i, j});
  return pairs;
}

}  // namespace spacetree::testing
