// Test helper: spheres with positions, velocities and radii in the layout the tree and grid
// APIs take (double (*)[3]), shared by the adaptive-grid tests.
#pragma once

#include <array>
#include <vector>

struct MovingSpheres {
  std::vector<std::array<double, 3>> x, v;
  std::vector<double> r;
  void add(std::array<double, 3> px, std::array<double, 3> pv, double pr) {
    x.push_back(px);
    v.push_back(pv);
    r.push_back(pr);
  }
  int size() const { return int(r.size()); }
  const double (*pos() const)[3] { return reinterpret_cast<const double(*)[3]>(x.data()); }
  const double (*vel() const)[3] { return reinterpret_cast<const double(*)[3]>(v.data()); }
  void move(double dt) {  // straight lines
    for (int i = 0; i < size(); ++i)
      for (int d = 0; d < 3; ++d) x[i][d] += dt * v[i][d];
  }
};
