// Benchmark (not a test): a grain against an obstacle of a few large triangles, at triangle size
// ratios 1:10 .. 1:10^6. The contact search of contact/MeshContact.h with the default hybrid, as
// it is and with its two size-ratio measures switched off (step 3's culls beyond the bounding
// spheres, MeshContactOptions::triangleCulling; the hybrid's scale-aware path,
// MeshContactOptions::clipLargeTriangles): triangle pairs handed to the distance method per body
// pair, the fraction of them that falls back to the exact method, thread CPU time per body pair,
// and whether the contacts equal the exact method's (they must, in every configuration).
//
// Scene: a dented-sphere grain (40 triangles, radius 1) over the top face of a 12-triangle slab
// of size R x 0.8 R x 0.1 R (R = the ratio), at random orientations, over the face's interior
// (50 %), near an edge (30 %) or a corner (20 %), its lowest vertex 0.02 .. 2.5 eps above the
// face (eps = 0.01: in the halo), both body orders (slab first, as pair_style trimesh orders an
// obstacle with more triangles, and grain first).
//
// Usage: bench_size_ratio_fallbacks [--out FILE.csv] [--ratios 10,100,...] [--scenes N]
//                                   [--rounds K] [--only CONFIGURATION]
// Times: median of K rounds, each running every configuration once over all scenes. --only runs
// one configuration once and writes nothing (instruction counts: valgrind --tool=callgrind).
#include <Eigen/Geometry>

#include <time.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"
#include "grain_on_slab_scenes.h"  // tests/unit

using namespace spacetree;
using namespace spacetree::contact;
using geometry::RigidShape;
using Eigen::Quaterniond;
using Eigen::Vector3d;

namespace {

constexpr double kEps = 0.01;

double threadSeconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

using grain_on_slab::Scene;

struct Configuration {
  const char* name;
  TriangleDistanceMethod method;
  bool culling, clip;
};

struct Outcome {
  MeshContactStatistics stats;
  std::vector<std::size_t> contactCounts;  // per body pair
  double seconds = 0.0;
};

Outcome run(const Configuration& c, const RigidShape& slab, const RigidShape& g,
            const std::vector<Scene>& all) {
  MeshContactOptions o;
  o.epsilon = kEps;
  o.method = c.method;
  o.triangleCulling = c.culling;
  o.clipLargeTriangles = c.clip;
  MeshContactFinder finder(o);
  Outcome out;
  std::vector<ContactPoint> contacts;
  const double start = threadSeconds();
  for (const Scene& s : all) {
    contacts.clear();
    out.contactCounts.push_back(finder.find(slab, s.slab, g, s.grain, contacts, &out.stats));
    contacts.clear();
    out.contactCounts.push_back(finder.find(g, s.grain, slab, s.slab, contacts, &out.stats));
  }
  out.seconds = threadSeconds() - start;
  return out;
}

std::vector<double> numbers(const char* s) {
  std::vector<double> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::atof(item.c_str()));
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  std::string out = "bench/results/size_ratio_fallbacks.csv";
  std::vector<double> ratios = {1e1, 1e2, 1e4, 1e6};
  int sceneCount = 400, rounds = 5;
  std::string only;  // one configuration (for instruction counts under callgrind), no CSV
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) out = argv[++i];
    else if (a == "--ratios" && i + 1 < argc) ratios = numbers(argv[++i]);
    else if (a == "--scenes" && i + 1 < argc) sceneCount = std::atoi(argv[++i]);
    else if (a == "--rounds" && i + 1 < argc) rounds = std::atoi(argv[++i]);
    else if (a == "--only" && i + 1 < argc) only = argv[++i];
    else {
      std::fprintf(stderr, "usage: %s [--out FILE.csv] [--ratios 10,100,...] [--scenes N] "
                   "[--rounds K] [--only CONFIGURATION]\n", argv[0]);
      return 2;
    }
  }
  const RigidShape grain = grain_on_slab::grain();
  const std::vector<Configuration> configurations = {
      {"hybrid", TriangleDistanceMethod::Hybrid, true, true},
      {"hybrid_no_clip", TriangleDistanceMethod::Hybrid, true, false},
      {"hybrid_no_culling", TriangleDistanceMethod::Hybrid, false, true},
      {"hybrid_neither", TriangleDistanceMethod::Hybrid, false, false},
      {"exact", TriangleDistanceMethod::Exact, true, true},
      {"exact_no_culling", TriangleDistanceMethod::Exact, false, true},
  };
  if (!only.empty()) {
    for (double ratio : ratios) {
      const Vector3d size(ratio, 0.8 * ratio, 0.1 * ratio);
      const RigidShape slab = RigidShape::fromMesh(geometry::boxMesh(size));
      const std::vector<Scene> all = grain_on_slab::scenes(grain, size, kEps, sceneCount, 5);
      for (const Configuration& c : configurations)
        if (only == c.name) {
          const Outcome o = run(c, slab, grain, all);
          std::printf("%g %s: %zu body pairs, %zu triangle pairs, %zu fallbacks\n", ratio, c.name,
                      o.stats.bodyPairs, o.stats.trianglePairsChecked, o.stats.fallbacks);
        }
    }
    return 0;
  }
  std::ofstream csv(out);
  csv << "ratio,configuration,body_pairs,triangle_pairs_per_body_pair,fallback_percent,contacts,"
         "body_pairs_with_other_contact_count_than_exact,ns_per_body_pair\n";
  std::printf("%-9s %-18s %10s %12s %10s %9s %9s %12s\n", "ratio", "configuration", "body pairs",
              "tri/body", "fallback%", "contacts", "differing", "ns/body");
  for (double ratio : ratios) {
    const Vector3d size(ratio, 0.8 * ratio, 0.1 * ratio);
    const RigidShape slab = RigidShape::fromMesh(geometry::boxMesh(size));
    const std::vector<Scene> all = grain_on_slab::scenes(grain, size, kEps, sceneCount, 5);
    std::vector<Outcome> first(configurations.size());
    std::vector<std::vector<double>> times(configurations.size());
    for (int r = 0; r < rounds; ++r)
      for (std::size_t c = 0; c < configurations.size(); ++c) {
        Outcome o = run(configurations[c], slab, grain, all);
        times[c].push_back(o.seconds);
        if (r == 0) first[c] = std::move(o);
      }
    const Outcome& exact = first[5];  // exact, bounding spheres only: the reference
    for (std::size_t c = 0; c < configurations.size(); ++c) {
      const Outcome& o = first[c];
      std::size_t differing = 0;
      for (std::size_t k = 0; k < o.contactCounts.size(); ++k)
        differing += o.contactCounts[k] != exact.contactCounts[k];
      std::vector<double> t = times[c];
      std::sort(t.begin(), t.end());
      const double bodyPairs = double(o.stats.bodyPairs);
      const double perBody = double(o.stats.trianglePairsChecked) / bodyPairs;
      const double fallback =
          o.stats.trianglePairsChecked
              ? 100.0 * double(o.stats.fallbacks) / double(o.stats.trianglePairsChecked)
              : 0.0;
      const double ns = 1e9 * t[t.size() / 2] / bodyPairs;
      std::printf("%-9.0e %-18s %10zu %12.1f %10.2f %9zu %9zu %12.0f\n", ratio,
                  configurations[c].name, o.stats.bodyPairs, perBody, fallback, o.stats.contacts,
                  differing, ns);
      csv << ratio << ',' << configurations[c].name << ',' << o.stats.bodyPairs << ',' << perBody
          << ',' << fallback << ',' << o.stats.contacts << ',' << differing << ',' << ns << '\n';
    }
  }
  std::printf("wrote %s\n", out.c_str());
  return 0;
}
