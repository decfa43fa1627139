// Where the time of one `neighbor ... spacetree` list build goes in the core, on a LIGGGHTS
// data file (bench/neighbor_vs_lammps.py writes them to bench/work/): the tree build (levels,
// vertices, look-up tables) and the sweep (pairs within r_i + r_j + skin), medians over the
// repeats, with the tree's counters per level (vertices, real particles, virtual links). The
// LIGGGHTS list filling (per-atom arrays, pages, contact history) is not included. Times are
// CPU time of the process (on a shared machine: not the time it waited for a core).
//   bench_neighbor_phases <data file> <skin> [repeats] [shuffled] [general]
// shuffled: the atoms in a random order (as exchanges leave them in a run) instead of the
// file's; general: the tree's general path even where the dense one-level path applies (the
// same cube, given as a caller's geometry).
#include <algorithm>
#include <array>
#include <cstring>
#include <random>
#include <ctime>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "tree/Spacetree.h"

using namespace spacetree;
namespace {
double cpuMs() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * double(t.tv_sec) + 1e-6 * double(t.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

// Atoms (id type diameter density x y z) of a LIGGGHTS data file.
bool readAtoms(const char* path, std::vector<std::array<double, 3>>& x, std::vector<double>& r) {
  std::ifstream in(path);
  if (!in) return false;
  std::string line, section;
  while (std::getline(in, line)) {
    if (!line.empty() && std::isalpha(static_cast<unsigned char>(line[0]))) {
      section = line.substr(0, line.find(' '));
      continue;
    }
    if (section != "Atoms") continue;
    std::istringstream s(line);
    long id;
    int type;
    double d, rho, p[3];
    if (s >> id >> type >> d >> rho >> p[0] >> p[1] >> p[2]) {
      x.push_back({p[0], p[1], p[2]});
      r.push_back(0.5 * d);
    }
  }
  return !x.empty();
}
}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s <data file> <skin> [repeats]\n", argv[0]);
    return 1;
  }
  const double skin = std::stod(argv[2]);
  const int repeats = argc > 3 ? std::stoi(argv[3]) : 7;
  bool shuffle = false, general = false;
  for (int a = 4; a < argc; ++a) {
    shuffle = shuffle || std::strcmp(argv[a], "shuffled") == 0;
    general = general || std::strcmp(argv[a], "general") == 0;
  }
  std::vector<std::array<double, 3>> x;
  std::vector<double> r;
  if (!readAtoms(argv[1], x, r)) {
    std::fprintf(stderr, "cannot read atoms from %s\n", argv[1]);
    return 1;
  }
  if (shuffle) {
    std::vector<std::size_t> order(r.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::shuffle(order.begin(), order.end(), std::mt19937_64(2024));
    std::vector<std::array<double, 3>> xs(x.size());
    std::vector<double> rs(r.size());
    for (std::size_t i = 0; i < order.size(); ++i) {
      xs[i] = x[order[i]];
      rs[i] = r[order[i]];
    }
    x.swap(xs);
    r.swap(rs);
  }
  const int n = int(r.size());
  const auto* xs = reinterpret_cast<const double(*)[3]>(x.data());
  SpacetreeOptions options;
  options.epsilon = 0.5 * skin;
  Spacetree tree(options);
  GridGeometry geometry;  // general: the cube the tree picks for itself
  if (general) {
    tree.build(xs, r.data(), n, n);
    geometry.origin = tree.origin();
    geometry.rootSize = tree.rootSize();
    geometry.depth = tree.levelCount() - 1;
  }
  std::vector<double> build, sweep;
  std::uint64_t pairs = 0;
  for (int k = 0; k < repeats; ++k) {
    const double t0 = cpuMs();
    if (general)
      tree.build(xs, r.data(), n, n, geometry, nullptr);
    else
      tree.build(xs, r.data(), n, n);
    const double t1 = cpuMs();
    pairs = 0;
    tree.forEachPairWithin([&](int, int, double) { ++pairs; });
    const double t2 = cpuMs();
    build.push_back(t1 - t0);
    sweep.push_back(t2 - t1);
  }
  const SpacetreeStatistics& s = tree.statistics();
  std::printf("atoms,%d\npairs,%llu\ncandidates,%llu\nbuild_ms,%.3f\nsweep_ms,%.3f\nus_per_atom,%.4f\nmemory_mb,%.2f\npath,%s\n",
              n, (unsigned long long)pairs, (unsigned long long)s.candidatePairs, median(build), median(sweep),
              1e3 * (median(build) + median(sweep)) / n, s.memoryBytes / 1048576.0,
              tree.usesDenseLevel() ? "dense one-level" : "general");
  std::printf("level,mesh_size,vertices,real_particles,virtual_links,link_tests\n");
  for (std::size_t l = 0; l < s.levels.size(); ++l)
    if (s.levels[l].realParticles || s.levels[l].virtualLinks)
      std::printf("%zu,%.4g,%llu,%llu,%llu,%llu\n", l, s.levels[l].meshSize, (unsigned long long)s.levels[l].vertices,
                  (unsigned long long)s.levels[l].realParticles, (unsigned long long)s.levels[l].virtualLinks,
                  (unsigned long long)s.levels[l].linkTests);
  return 0;
}
