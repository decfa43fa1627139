// Spheres as the spacetree takes them (positions as double[3] rows, radii), for the tree tests.
#pragma once

#include <array>
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

}  // namespace spacetree::testing
