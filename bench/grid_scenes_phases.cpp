// Where the time of one neighbour-list build goes, per grid type, on a scene data file of
// bench/grid_scenes.py (build/bench_grid_scenes/<scene>.data): the grid update, the Spacetree
// build on its levels, the sweep (pairs within the cut-off) and, for the reluctant grid, the
// refinement for the sweep's pairs. Same halo (skin 2e-4) and step (2e-6 s, free flight) as
// the LIGGGHTS deck; the LIGGGHTS list filling is not included. refine_for_pairs_ms is
// refineForPairs: for the reluctant grid the refinement and the coarsening after the sweep.
//   bench_grid_scenes_phases <data file> [steps] > phases.csv
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tree/AdaptiveGrid.h"
#include "tree/Spacetree.h"

using namespace spacetree;
using Clock = std::chrono::steady_clock;

namespace {
double ms(Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double, std::milli>(b - a).count(); }

// Atoms (id type diameter density x y z) and Velocities (id vx vy vz ...) of a LIGGGHTS data file.
bool readData(const char* path, std::vector<std::array<double, 3>>& x, std::vector<std::array<double, 3>>& v,
              std::vector<double>& r) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line, section;
  while (std::getline(in, line)) {
    if (line == "Atoms" || line == "Velocities") {
      section = line;
      continue;
    }
    std::istringstream s(line);
    long id;
    if (!(s >> id)) continue;
    if (section == "Atoms") {
      int type;
      double d, rho, p[3];
      if (s >> type >> d >> rho >> p[0] >> p[1] >> p[2]) {
        x.push_back({p[0], p[1], p[2]});
        r.push_back(0.5 * d);
      }
    } else if (section == "Velocities") {
      double w[3];
      if (s >> w[0] >> w[1] >> w[2]) v.push_back({w[0], w[1], w[2]});
    }
  }
  return !x.empty() && x.size() == v.size();
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s <data file> [steps]\n", argv[0]);
    return 1;
  }
  const int steps = argc > 2 ? std::stoi(argv[2]) : 40;
  std::vector<std::array<double, 3>> x0, v;
  std::vector<double> r;
  if (!readData(argv[1], x0, v, r)) {
    std::fprintf(stderr, "cannot read atoms and velocities from %s\n", argv[1]);
    return 1;
  }
  const int n = int(x0.size());
  const double eps = 1e-4, dt = 2e-6;  // skin 2e-4 as in inputs/bench/in.grid_bench
  std::printf("grid,atoms,steps,update_ms,build_ms,sweep_ms,refine_for_pairs_ms,total_ms,pairs,comparisons,cells,"
              "rehosted\n");
  for (GridType type : {GridType::Regular, GridType::Adaptive, GridType::Reluctant}) {
    std::vector<std::array<double, 3>> x = x0;
    AdaptiveGridOptions options;
    options.type = type;
    options.epsilon = eps;
    options.pairsFromCaller = true;  // as fix spacetree does
    AdaptiveGrid grid(options);
    Spacetree tree(SpacetreeOptions{eps, kMaxSpacetreeLevel});
    std::vector<int> first, second;
    double t[4] = {0, 0, 0, 0};
    std::uint64_t rehosted = 0;
    for (int step = 0; step <= steps; ++step) {
      for (int i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d) x[i][d] += dt * v[i][d];
      const double(*xs)[3] = reinterpret_cast<const double(*)[3]>(x.data());
      const double(*vs)[3] = reinterpret_cast<const double(*)[3]>(v.data());
      const auto t0 = Clock::now();
      grid.update(xs, vs, r.data(), n);
      const auto t1 = Clock::now();
      grid.buildSpacetree(tree, xs, r.data(), n, n);
      const auto t2 = Clock::now();
      first.clear();
      second.clear();
      tree.forEachPairWithin([&](int i, int j, double) {
        first.push_back(i);
        second.push_back(j);
      });
      const auto t3 = Clock::now();
      grid.refineForPairs(xs, vs, r.data(), n, first.data(), second.data(), first.size());
      const auto t4 = Clock::now();
      if (step == 0) continue;  // the first update builds the grid from scratch (setup)
      t[0] += ms(t0, t1);
      t[1] += ms(t1, t2);
      t[2] += ms(t2, t3);
      t[3] += ms(t3, t4);
      rehosted += grid.statistics().rehosted;
    }
    for (double& s : t) s /= steps;
    std::printf("%s,%d,%d,%.4f,%.4f,%.4f,%.4f,%.4f,%zu,%llu,%llu,%.1f\n", gridTypeName(type), n, steps, t[0], t[1],
                t[2], t[3], t[0] + t[1] + t[2] + t[3], first.size(),
                (unsigned long long)tree.statistics().candidatePairs, (unsigned long long)grid.statistics().cells,
                double(rehosted) / steps);
  }
  return 0;
}
