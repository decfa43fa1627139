// Benchmark (not a test): wall time of one task-parallel pair-check sweep (paper §6.3) over a
// dense pack of triangulated spheres, for several thread counts side by side. One sweep = the
// spacetree traversal producing pair-check tasks + the hybrid triangle-distance checks run by
// the arena's threads + the join and the canonical sort of the contacts. The tree is built once
// per pack (its cost is reported separately). Thread counts are interleaved repetition by
// repetition, so a load change on a shared machine hits all of them alike; medians are reported,
// with the process CPU time per sweep (all threads): equal CPU time for 1 and N threads means
// the tasks add no work, whatever share of the cores a loaded machine leaves the benchmark.
//
// Usage: bench_parallel_pair_checks [--out FILE.csv] [--particles 1000,10000] [--threads 1,2]
//                                   [--triangles 48] [--repetitions 5] [--grain 4096]
//                                   [--check all-pairs|mesh-contact]
// --check all-pairs (default): PosedMeshPairCheck, every triangle pair through the hybrid kernel.
// --check mesh-contact: MeshContactPairCheck on the same poses with dented spheres (amplitude
// 0.1, three templates): the contact search with triangle pruning and de-duplication.
// Also prints, per pack, a serial baseline: the same checks called directly from the sweep,
// no TBB at all. bench/plot_parallel_pair_checks.py plots the CSV.
#include <oneapi/tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/DentedSphere.h"
#include "geometry/RigidShape.h"
#include "parallel/MeshContactPairCheck.h"
#include "parallel/PosedMeshPairCheck.h"
#include "parallel/TaskParallelPairChecks.h"
#include "parallel/TriangulatedSpherePack.h"
#include "tree/Spacetree.h"

using namespace spacetree;
using namespace spacetree::parallel;

namespace {

struct Settings {
  std::string out = "bench/results/parallel_pair_checks.csv";
  std::vector<int> particles = {1000, 10000};
  std::vector<int> threads = {1, 2};
  int triangles = 48;
  int repetitions = 5;
  std::size_t grain = 4096;
  std::string check = "all-pairs";
};

std::vector<int> parseList(const char* s) {
  std::vector<int> v;
  std::stringstream in(s);
  std::string item;
  while (std::getline(in, item, ',')) v.push_back(std::atoi(item.c_str()));
  return v;
}

Settings parse(int argc, char** argv) {
  Settings s;
  for (int a = 1; a < argc; ++a) {
    const auto is = [&](const char* name) { return std::strcmp(argv[a], name) == 0 && a + 1 < argc; };
    if (is("--out")) s.out = argv[++a];
    else if (is("--particles")) s.particles = parseList(argv[++a]);
    else if (is("--threads")) s.threads = parseList(argv[++a]);
    else if (is("--triangles")) s.triangles = std::atoi(argv[++a]);
    else if (is("--repetitions")) s.repetitions = std::atoi(argv[++a]);
    else if (is("--grain")) s.grain = std::size_t(std::atoll(argv[++a]));
    else if (is("--check")) s.check = argv[++a];
    else {
      std::fprintf(stderr, "bench_parallel_pair_checks: unknown or incomplete option '%s'\n", argv[a]);
      std::exit(2);
    }
  }
  if (s.check != "all-pairs" && s.check != "mesh-contact") {
    std::fprintf(stderr, "bench_parallel_pair_checks: --check must be all-pairs or mesh-contact\n");
    std::exit(2);
  }
  return s;
}

// The mesh-contact scene: dented spheres at the pack's centres and orientations.
struct DentedScene {
  std::vector<geometry::RigidShape> templates;
  std::vector<const geometry::RigidShape*> shapes;
  std::vector<contact::Pose> poses;
};

DentedScene dentedScene(const TriangulatedSpherePack& pack, int triangles, double radius,
                        std::uint32_t seed) {
  DentedScene scene;
  for (std::uint64_t t = 1; t <= 3; ++t) {
    geometry::DentedSphereOptions d;
    d.triangles = triangles;
    d.radius = radius;
    d.amplitude = 0.1;
    d.seed = t;
    scene.templates.push_back(geometry::RigidShape::fromMesh(geometry::dentedSphere(d)));
  }
  std::mt19937_64 random(seed);
  std::normal_distribution<double> gaussian;
  for (std::size_t p = 0; p < pack.centre.size(); ++p) {
    contact::Pose pose;
    pose.position = Eigen::Vector3d(pack.centre[p].data());
    pose.orientation = Eigen::Quaterniond(gaussian(random), gaussian(random), gaussian(random),
                                          gaussian(random)).normalized();
    scene.shapes.push_back(&scene.templates[p % 3]);
    scene.poses.push_back(pose);
  }
  return scene;
}

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// 1-minute load average (Linux), -1 where unknown: the benchmark's context on a shared machine.
double loadAverage() {
  std::ifstream in("/proc/loadavg");
  double load = -1.0;
  in >> load;
  return load;
}

}  // namespace

int main(int argc, char** argv) {
  const Settings s = parse(argc, argv);
  const int maxThreads = *std::max_element(s.threads.begin(), s.threads.end());
  // Let the arenas have as many threads as asked, even beyond TBB's default worker cap.
  tbb::global_control allow(tbb::global_control::max_allowed_parallelism,
                            std::size_t(std::max(maxThreads, 1)));
  std::ofstream csv(s.out);
  csv << "particles,triangles_per_particle,threads,median_seconds_per_sweep,min_seconds_per_sweep,"
         "serial_seconds_per_sweep,speedup_vs_1_thread,candidate_pairs,triangle_pairs,tasks,"
         "contacts,producer_seconds_median,producer_fraction,tree_build_seconds,repetitions,"
         "hardware_threads,load_average_1min,cpu_seconds_per_sweep,serial_cpu_seconds_per_sweep,"
         "check\n";

  for (int n : s.particles) {
    TriangulatedSpherePackOptions o;
    o.particles = n;
    o.trianglesPerParticle = s.triangles;
    TriangulatedSpherePack pack = makeTriangulatedSpherePack(o);
    geometry::HybridOptions hybrid;
    hybrid.contactDistance = 0.02 * o.radius;
    DentedScene dented;
    std::unique_ptr<PairCheck> checkPointer;
    if (s.check == "mesh-contact") {
      dented = dentedScene(pack, s.triangles, o.radius, 5);
      for (std::size_t p = 0; p < pack.radius.size(); ++p)
        pack.radius[p] = dented.shapes[p]->boundingRadius;
      contact::MeshContactOptions mo;
      mo.epsilon = hybrid.contactDistance / 2.0;
      checkPointer = std::make_unique<MeshContactPairCheck>(dented.shapes, dented.poses, mo);
    } else {
      checkPointer = std::make_unique<PosedMeshPairCheck>(pack.meshes, hybrid);
    }
    const PairCheck& check = *checkPointer;
    Spacetree tree(SpacetreeOptions{hybrid.contactDistance / 2.0, kMaxSpacetreeLevel});
    auto t0 = std::chrono::steady_clock::now();
    tree.build(reinterpret_cast<const double(*)[3]>(pack.centre.data()), pack.radius.data(), n, n);
    const double buildSeconds = seconds(t0);

    std::vector<std::unique_ptr<TaskParallelPairChecks>> engines;
    for (int t : s.threads) engines.push_back(std::make_unique<TaskParallelPairChecks>(
                                TaskParallelOptions{t, s.grain}));
    std::vector<std::vector<double>> times(s.threads.size()), producerTimes(s.threads.size()),
        cpuTimes(s.threads.size());
    std::vector<double> serialTimes, serialCpuTimes;
    std::vector<TriangleContact> contacts, reference;
    std::size_t referenceContacts = 0;
    for (int r = 0; r < s.repetitions; ++r) {
      // Serial baseline: every check called in the sweep itself.
      t0 = std::chrono::steady_clock::now();
      const std::clock_t serialCpu0 = std::clock();
      std::vector<TriangleContact> serial;
      ContactSink sink(serial);
      tree.forEachPairWithin([&](int i, int j, double) {
        const int a = std::min(i, j), b = std::max(i, j);
        check.check(a, b, 0, check.triangleCount(a), sink);
      });
      serialTimes.push_back(seconds(t0));
      serialCpuTimes.push_back(double(std::clock() - serialCpu0) / CLOCKS_PER_SEC);
      referenceContacts = serial.size();
      for (std::size_t k = 0; k < engines.size(); ++k) {
        t0 = std::chrono::steady_clock::now();
        const std::clock_t c0 = std::clock();
        engines[k]->run(tree, check, contacts);
        times[k].push_back(seconds(t0));
        cpuTimes[k].push_back(double(std::clock() - c0) / CLOCKS_PER_SEC);
        producerTimes[k].push_back(engines[k]->statistics().producerSeconds);
        if (contacts.size() != referenceContacts) {
          std::fprintf(stderr, "contact count differs: %zu threads-engine vs %zu serial\n",
                       contacts.size(), referenceContacts);
          return 1;
        }
      }
    }
    double oneThread = 0.0;  // the 1-thread median, if 1 is among the thread counts
    for (std::size_t k = 0; k < engines.size(); ++k)
      if (s.threads[k] == 1) oneThread = median(times[k]);
    for (std::size_t k = 0; k < engines.size(); ++k) {
      const TaskParallelStatistics& st = engines[k]->statistics();
      const double m = median(times[k]);
      const double speedup = oneThread > 0.0 ? oneThread / m : 0.0;
      csv << n << ',' << check.triangleCount(0) << ',' << engines[k]->threads() << ',' << m
          << ',' << *std::min_element(times[k].begin(), times[k].end()) << ','
          << median(serialTimes) << ',' << speedup << ',' << st.pairs << ',' << st.trianglePairs
          << ',' << st.tasks << ',' << st.contacts << ',' << median(producerTimes[k]) << ','
          << median(producerTimes[k]) / m << ',' << buildSeconds << ',' << s.repetitions << ','
          << std::thread::hardware_concurrency() << ',' << loadAverage() << ','
          << median(cpuTimes[k]) << ',' << median(serialCpuTimes) << ',' << s.check << '\n';
      std::printf("%s: %6d particles (%zu triangles each), %d thread(s): %.4f s per sweep (median of "
                  "%d), serial %.4f s, speed-up vs 1 thread %.2f; %llu pairs, %llu triangle pairs, "
                  "%llu tasks, %llu contacts; producer %.4f s; CPU %.4f s (serial %.4f s); load %.2f\n",
                  s.check.c_str(), n, check.triangleCount(0), engines[k]->threads(), m, s.repetitions,
                  median(serialTimes), speedup, (unsigned long long)st.pairs,
                  (unsigned long long)st.trianglePairs, (unsigned long long)st.tasks,
                  (unsigned long long)st.contacts, median(producerTimes[k]), median(cpuTimes[k]), median(serialCpuTimes),
                  loadAverage());
    }
  }
  std::printf("wrote %s\n", s.out.c_str());
  return 0;
}
