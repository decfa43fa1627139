// Benchmark (not a test): triangle-pair checks per second on one core for the exact, penalty
// and hybrid triangle distances, versus triangles per particle. The workload is the paper's:
// two triangulated spheres (radius 1, random orientations) at contact distance, every triangle
// of one against every triangle of the other. The meshes are placed so that their distance is
// half the contact distance 2 eps: a few triangle pairs are in contact, most are far apart.
//
// Usage: bench_triangle_distance [--out FILE.csv] [--triangles 12,40,...] [--orientations N]
//                                [--min-pairs P] [--min-seconds S] [--contact-distance T]
//                                [--iterations 4,8] [--continuations 4] [--pipeline-out FILE.csv]
//                                [--replay-out FILE.csv] [--replay-triangles 12,20,40]
//
// Scene count rule: per triangle count, at least --orientations scenes and enough of them that
// one timed pass gives the method at least --min-pairs distinct triangle pairs. The exact
// method branches on every pair; replaying a few hundred pairs lets the CPU's branch predictor
// learn them and makes it up to 2.5x faster than on pairs it has not seen (a simulation never
// repeats pairs within thousands of checks). The branch-free penalty kernel does not care.
// --replay-out measures that effect on the same scenes: each scene repeated in a row versus
// all scenes (or the first 4, 16, ...) interleaved.
// Writes one CSV row per (triangles, method) (--out "" skips this part); for every iteration
// count K and continuation count C a two-stage hybrid row "hybrid2+C" (K stage-1 steps, C more
// for the pairs stage 1 leaves uncertified; HybridOptions::continuationIterations);
// bench/plot_triangle_distance.py plots it.
// Second part (--pipeline-out, "" to skip): the whole contact search of contact/MeshContact.h
// on the same kind of scenes (bounding-sphere precheck, triangle pruning, the method on the
// surviving pairs, contacts, local-minimum filter, de-duplication): particle pairs per second
// per method, with the pruned fraction of triangle pairs.
#include <Eigen/Geometry>

#include <algorithm>
#include <time.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "contact/MeshContact.h"
#include "geometry/HybridTriangleDistance.h"
#include "geometry/RigidShape.h"
#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/SphereMesh.h"
#include "geometry/TriangleDistance.h"

using namespace spacetree::geometry;
using Eigen::Vector3d;

namespace {

struct Settings {
  std::string out = "bench/results/triangle_distance.csv";
  std::vector<int> triangles = {12, 20, 40, 80, 160, 320, 640, 1000};
  int orientations = 4;        // at least this many random orientation pairs per triangle count
  // ... and at least this many distinct triangle pairs per timed pass (scene count rule above;
  // the pipeline counts the pairs that survive pruning). 0: exactly `orientations` scenes.
  std::size_t minPairs = 16384;
  double minSeconds = 0.5;     // per method and size: thread CPU time measured over all rounds
  double contactDistance = 0.02;  // 2 eps for spheres of radius 1
  std::vector<int> iterations = {4, 8};  // Newton steps of the penalty and hybrid runs
  std::vector<int> continuations = {4};  // stage-2 steps of the two-stage hybrid runs
  std::string pipelineOut = "bench/results/mesh_contact.csv";  // "" skips the pipeline part
  std::string replayOut;                                       // "" skips the replay part
  std::vector<int> replayTriangles = {12, 20, 40};
};

// The scene count rule for scenes of `pairsPerScene` triangle pairs each.
std::size_t sceneCount(const Settings& settings, std::size_t pairsPerScene) {
  const std::size_t forPairs = (settings.minPairs + pairsPerScene - 1) / pairsPerScene;
  return std::max<std::size_t>(std::size_t(std::max(settings.orientations, 1)), forPairs);
}

// CPU time of this thread: on a shared machine the time slices other processes take do not
// count (wall-clock time would), so per-core throughput stays comparable between runs.
double threadSeconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Scene {
  std::vector<Triangle> first, second;  // the two particles' meshes, already placed
};

std::vector<Triangle> transformed(const std::vector<Triangle>& mesh, const Eigen::Matrix3d& r,
                                  const Vector3d& shift) {
  std::vector<Triangle> out = mesh;
  for (Triangle& t : out)
    for (int i = 0; i < 3; ++i) t[i] = r * t[i] + shift;
  return out;
}

// Minimum distance of two meshes (exact method). Pairs whose bounding spheres are farther apart
// than the best distance so far cannot hold the minimum and are skipped: the same minimum as
// over all pairs, much faster for 1000-triangle meshes (scene set-up only, never timed).
double meshDistance(const std::vector<Triangle>& a, const std::vector<Triangle>& b) {
  struct Sphere {
    Vector3d centre;
    double radius;
  };
  const auto spheres = [](const std::vector<Triangle>& mesh) {
    std::vector<Sphere> out;
    for (const Triangle& t : mesh) {
      const Vector3d c = (t[0] + t[1] + t[2]) / 3.0;
      out.push_back({c, std::max({(t[0] - c).norm(), (t[1] - c).norm(), (t[2] - c).norm()})});
    }
    return out;
  };
  const std::vector<Sphere> sa = spheres(a), sb = spheres(b);
  double d = 1e300;
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) {
      const double lower = (sa[i].centre - sb[j].centre).norm() - sa[i].radius - sb[j].radius;
      if (lower > d * (1.0 + 1e-9) + 1e-12) continue;
      d = std::min(d, triangleDistance(a[i], b[j]).distance);
    }
  return d;
}

// Two copies of the mesh, randomly turned, the second moved along x until the meshes are
// `gap` apart (a few secant steps: the distance is piecewise linear in the shift).
Scene makeScene(const std::vector<Triangle>& mesh, double gap, std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  const auto rotation = [&] {
    return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
  };
  Scene s;
  s.first = transformed(mesh, rotation(), Vector3d::Zero());
  const Eigen::Matrix3d r2 = rotation();
  double x = 2.0 + gap;
  for (int step = 0; step < 8; ++step) {
    s.second = transformed(mesh, r2, Vector3d(x, 0, 0));
    const double d = meshDistance(s.first, s.second);
    if (std::abs(d - gap) < 1e-12) break;
    x += gap - d;
  }
  return s;
}

// One sweep over all triangle pairs of a scene through `computeBlock`, a block of rows at a
// time (rows of the first mesh against the whole second mesh, about kPairsPerBlock pairs, so
// that the results stay in cache and small meshes still fill the SIMD batches). Returns the
// number of contacts (distance < threshold) and, if asked, appends every pair's decision.
constexpr std::size_t kPairsPerBlock = 1024;

std::size_t rowsPerBlock(const Scene& s) {
  return std::max<std::size_t>(1, kPairsPerBlock / s.second.size());
}

template <class ComputeBlock>
std::size_t sweep(const Scene& s, std::vector<TriangleDistanceResult>& block, double threshold,
                  std::vector<char>* decisions, ComputeBlock&& computeBlock) {
  std::size_t contacts = 0;
  const std::size_t rows = rowsPerBlock(s);
  for (std::size_t i = 0; i < s.first.size(); i += rows) {
    const std::size_t n = std::min(rows, s.first.size() - i);
    computeBlock(&s.first[i], n, block.data());
    for (std::size_t k = 0; k < n * s.second.size(); ++k) {
      const bool contact = block[k].distance < threshold;
      contacts += contact;
      if (decisions) decisions->push_back(contact);
    }
  }
  return contacts;
}

struct Method {
  std::string name;
  int newtonIterations;  // 0 for the exact method
  std::function<std::size_t(const Scene&, std::vector<TriangleDistanceResult>& block,
                            HybridStatistics& stats, std::vector<char>* decisions)>
      run;
};

std::vector<Method> methods(double threshold, const std::vector<int>& iterationCounts,
                            const std::vector<int>& continuations) {
  std::vector<Method> m;
  m.push_back({"exact", 0, [threshold](const Scene& s, auto& block, auto&, auto* decisions) {
                 return sweep(s, block, threshold, decisions,
                              [&](const Triangle* rows, std::size_t n, auto* out) {
                                triangleDistancesOfAllPairs(rows, n, s.second.data(),
                                                            s.second.size(), out);
                              });
               }});
  for (int iterations : iterationCounts) {
    PenaltyOptions penalty;
    penalty.newtonIterations = iterations;
    m.push_back({"penalty", iterations,
                 [threshold, penalty](const Scene& s, auto& block, auto&, auto* decisions) {
                   return sweep(s, block, threshold, decisions,
                                [&](const Triangle* rows, std::size_t n, auto* out) {
                                  penaltyTriangleDistancesOfAllPairs(
                                      rows, n, s.second.data(), s.second.size(), penalty, out);
                                });
                 }});
    HybridOptions hybrid;
    hybrid.contactDistance = threshold;
    hybrid.newtonIterations = iterations;
    hybrid.continuationIterations = 0;  // single stage
    m.push_back({"hybrid", iterations,
                 [threshold, hybrid](const Scene& s, auto& block, HybridStatistics& stats,
                                     auto* decisions) {
                   return sweep(s, block, threshold, decisions,
                                [&](const Triangle* rows, std::size_t n, auto* out) {
                                  hybridTriangleDistancesOfAllPairs(rows, n, s.second.data(),
                                                                    s.second.size(), hybrid,
                                                                    out, &stats);
                                });
                 }});
    // Two-stage hybrid: `iterations` steps for all pairs, `continuation` more for the
    // uncertified ones.
    for (int continuation : continuations) {
    HybridOptions twoStage = hybrid;
    twoStage.continuationIterations = continuation;
    m.push_back({"hybrid2+" + std::to_string(continuation), iterations,
                 [threshold, twoStage](const Scene& s, auto& block, HybridStatistics& stats,
                                       auto* decisions) {
                   return sweep(s, block, threshold, decisions,
                                [&](const Triangle* rows, std::size_t n, auto* out) {
                                  hybridTriangleDistancesOfAllPairs(rows, n, s.second.data(),
                                                                    s.second.size(), twoStage,
                                                                    out, &stats);
                                });
                 }});
    }
  }
  return m;
}

std::vector<int> parseList(const char* text) {
  std::vector<int> v;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) v.push_back(std::atoi(item.c_str()));
  return v;
}

// The instruction set the kernels run with: chosen at run time among the clones, or fixed at
// compile time when built with -DSPACETREE_NO_ISA_DISPATCH (for per-ISA comparisons).
std::string isaInUse() {
#if defined(SPACETREE_NO_ISA_DISPATCH)
#if defined(__AVX512F__)
  return "avx512 (fixed)";
#elif defined(__AVX2__) && defined(__FMA__)
  return "avx2 (fixed)";
#else
  return "sse2 (fixed)";
#endif
#else
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx512f")) return "avx512";
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return "avx2";
  return "sse2";
#endif
}

// The contact pipeline per particle pair. Scenes as above, built from posed RigidShapes.
void runPipeline(const Settings& settings) {
  using namespace spacetree::contact;
  std::ofstream csv(settings.pipelineOut);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", settings.pipelineOut.c_str());
    std::exit(1);
  }
  csv << "triangles_per_particle,method,newton_iterations,us_per_particle_pair,"
         "triangle_pairs_checked,pruned_fraction,fallback_fraction,contacts,speedup_vs_exact,scenes\n";
  std::printf("\ncontact pipeline (MeshContactFinder), per particle pair:\n%-6s %-10s %3s %10s %9s %8s %9s %8s %8s %6s\n",
              "tri", "method", "it", "us/pair", "checked", "pruned", "fallback", "contacts", "speedup", "scenes");
  std::mt19937_64 rng(4048);
  std::normal_distribution<double> n;
  const double eps = 0.5 * settings.contactDistance;
  for (int requested : settings.triangles) {
    const RigidShape shape = RigidShape::fromMesh(latitudeLongitudeSphereMeshWithAbout(requested, 1.0));
    struct PosedPair {
      Pose first, second;
    };
    // Scenes until the rule holds for the pairs that reach the method (after pruning), counted
    // with an exact-method finder (the same pairs for every method).
    MeshContactOptions counting;
    counting.epsilon = eps;
    counting.method = TriangleDistanceMethod::Exact;
    MeshContactFinder counter(counting);
    std::vector<ContactPoint> found;
    std::vector<PosedPair> scenes;
    std::size_t checkedPairs = 0;
    constexpr std::size_t kMaxScenes = 4096;
    while (scenes.size() < kMaxScenes &&
           (scenes.size() < std::size_t(std::max(settings.orientations, 1)) ||
            checkedPairs < settings.minPairs)) {
      PosedPair p;
      p.first.orientation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
      p.second.orientation = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
      const auto place = [&](const Pose& pose) {
        return transformed(shape.bodyTriangles, pose.orientation.toRotationMatrix(), pose.position);
      };
      const std::vector<Triangle> a = place(p.first);
      double x = 2.0 + eps;
      for (int step = 0; step < 8; ++step) {  // surfaces eps apart (half of 2 eps)
        p.second.position = Vector3d(x, 0, 0);
        const double d = meshDistance(a, place(p.second));
        if (std::abs(d - eps) < 1e-12) break;
        x += eps - d;
      }
      MeshContactStatistics one;
      found.clear();
      counter.find(shape, p.first, shape, p.second, found, &one);
      checkedPairs += one.trianglePairsChecked;
      scenes.push_back(p);
    }
    struct Run {
      TriangleDistanceMethod method;
      int iterations;
    };
    std::vector<Run> runs = {{TriangleDistanceMethod::Exact, 0}};
    for (int it : settings.iterations) {
      runs.push_back({TriangleDistanceMethod::Penalty, it});
      runs.push_back({TriangleDistanceMethod::Hybrid, it});
    }
    std::vector<MeshContactFinder> finders;
    for (const Run& r : runs) {
      MeshContactOptions o;
      o.epsilon = eps;
      o.method = r.method;
      o.newtonIterations = r.iterations ? r.iterations : 8;
      o.continuationIterations = 0;  // the pipeline rows are the single-stage hybrid (docs)
      finders.emplace_back(o);
    }
    std::vector<MeshContactStatistics> stats(runs.size());
    std::vector<ContactPoint> contacts;
    for (std::size_t m = 0; m < runs.size(); ++m)
      for (const PosedPair& p : scenes) {
        contacts.clear();
        finders[m].find(shape, p.first, shape, p.second, contacts, &stats[m]);
      }
    constexpr int kRounds = 5;
    std::vector<std::vector<double>> roundUs(runs.size());
    for (int round = 0; round < kRounds; ++round)
      for (std::size_t m = 0; m < runs.size(); ++m) {
        std::size_t calls = 0;
        const double start = threadSeconds();
        double elapsed = 0.0;
        do {
          for (const PosedPair& p : scenes) {
            contacts.clear();
            finders[m].find(shape, p.first, shape, p.second, contacts);
          }
          calls += scenes.size();
          elapsed = threadSeconds() - start;
        } while (elapsed < settings.minSeconds / kRounds);
        roundUs[m].push_back(1e6 * elapsed / double(calls));
      }
    std::vector<double> us(runs.size());
    for (std::size_t m = 0; m < runs.size(); ++m) {
      std::sort(roundUs[m].begin(), roundUs[m].end());
      us[m] = roundUs[m][kRounds / 2];
    }
    for (std::size_t m = 0; m < runs.size(); ++m) {
      const MeshContactStatistics& s = stats[m];
      const double pairs = double(shape.triangleCount() * shape.triangleCount() * scenes.size());
      const double checked = double(s.trianglePairsChecked) / double(scenes.size());
      const double pruned = double(s.trianglePairsPruned) / pairs;
      const double fallback = s.trianglePairsChecked ? double(s.fallbacks) / double(s.trianglePairsChecked) : 0.0;
      const double perScene = double(s.contacts) / double(scenes.size());
      const char* name = triangleDistanceMethodName(runs[m].method);
      csv << shape.triangleCount() << ',' << name << ',' << runs[m].iterations << ',' << us[m] << ','
          << checked << ',' << pruned << ',' << fallback << ',' << perScene << ',' << us[0] / us[m] << ','
          << scenes.size() << '\n';
      std::printf("%-6zu %-10s %3d %10.2f %9.0f %7.2f%% %8.3f%% %8.2f %7.2fx %6zu\n", shape.triangleCount(), name,
                  runs[m].iterations, us[m], checked, 100 * pruned, 100 * fallback, perScene, us[0] / us[m],
                  scenes.size());
      std::fflush(stdout);
    }
  }
  std::printf("wrote %s\n", settings.pipelineOut.c_str());
}


// Replay part: the exact method, the penalty kernel and the default (two-stage) hybrid on the
// same scenes in two orders. "repeated": each scene swept kReplayRepeats times in a row (after
// kReplayWarmup untimed sweeps), so the CPU sees one scene's pairs over and over, as a
// benchmark with few scenes does; "interleaved": the first k scenes swept in turn (k = 4, the
// old benchmark's count, 16, 64, ... and all), as in a simulation, where pairs do not repeat
// within thousands of checks. Rounds as in the main part (every method and order in turn,
// median round), so ratios are side by side.
void runReplay(const Settings& settings) {
  std::ofstream csv(settings.replayOut);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", settings.replayOut.c_str());
    std::exit(1);
  }
  csv << "triangles_per_particle,method,newton_iterations,order,scenes,distinct_pairs_per_pass,"
         "ns_per_pair,speedup_vs_exact,time_over_repeated\n";
  std::printf("\nreplay: same scenes, each repeated in a row vs interleaved\n"
              "%-6s %-10s %3s %-12s %6s %9s %10s %8s %9s\n",
              "tri", "method", "it", "order", "scenes", "distinct", "ns/pair", "speedup", "/repeated");
  const HybridOptions defaults;
  std::vector<Method> chosen;
  for (Method& m : methods(settings.contactDistance, {defaults.newtonIterations},
                           {defaults.continuationIterations}))
    if (m.name != "hybrid") chosen.push_back(std::move(m));  // exact, penalty, two-stage hybrid
  constexpr int kReplayWarmup = 8, kReplayRepeats = 32, kRounds = 5;
  std::mt19937_64 rng(2024);  // the main part's seed (the same scenes for its first count)
  for (int requested : settings.replayTriangles) {
    const std::vector<Triangle> mesh = latitudeLongitudeSphereWithAbout(requested, 1.0);
    const std::size_t pairsPerScene = mesh.size() * mesh.size();
    const std::size_t count = std::max<std::size_t>(64, sceneCount(settings, pairsPerScene));
    std::vector<Scene> scenes;
    for (std::size_t o = 0; o < count; ++o)
      scenes.push_back(makeScene(mesh, 0.5 * settings.contactDistance, rng));
    std::vector<TriangleDistanceResult> block(rowsPerBlock(scenes.front()) * mesh.size());
    std::vector<std::size_t> subsets;  // scenes interleaved; 0 stands for "repeated"
    subsets.push_back(0);
    for (std::size_t k = 4; k < count; k *= 4) subsets.push_back(k);
    subsets.push_back(count);
    // ns[method][subset] per round
    std::vector<std::vector<std::vector<double>>> ns(
        chosen.size(), std::vector<std::vector<double>>(subsets.size()));
    HybridStatistics ignored;
    for (int round = 0; round < kRounds; ++round)
      for (std::size_t o = 0; o < subsets.size(); ++o)
        for (std::size_t m = 0; m < chosen.size(); ++m) {
          const Method& method = chosen[m];
          double elapsed = 0.0;
          std::size_t pairs = 0;
          if (subsets[o] == 0) {
            for (const Scene& s : scenes) {
              for (int r = 0; r < kReplayWarmup; ++r) method.run(s, block, ignored, nullptr);
              const double start = threadSeconds();
              for (int r = 0; r < kReplayRepeats; ++r) method.run(s, block, ignored, nullptr);
              elapsed += threadSeconds() - start;
              pairs += pairsPerScene * kReplayRepeats;
            }
          } else {
            const std::size_t k = subsets[o];
            for (std::size_t i = 0; i < k; ++i) method.run(scenes[i], block, ignored, nullptr);
            const double start = threadSeconds();
            do {
              for (std::size_t i = 0; i < k; ++i) method.run(scenes[i], block, ignored, nullptr);
              pairs += pairsPerScene * k;
              elapsed = threadSeconds() - start;
            } while (elapsed < settings.minSeconds / kRounds);
          }
          ns[m][o].push_back(1e9 * elapsed / double(pairs));
        }
    const auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    for (std::size_t m = 0; m < chosen.size(); ++m)
      for (std::size_t o = 0; o < subsets.size(); ++o) {
        const double t = median(ns[m][o]);
        const double exact = median(ns[0][o]);  // chosen[0] is the exact method
        const double repeated = median(ns[m][0]);
        const bool isRepeated = subsets[o] == 0;
        const char* order = isRepeated ? "repeated" : "interleaved";
        const std::size_t sceneCount = isRepeated ? scenes.size() : subsets[o];
        const std::size_t distinct = pairsPerScene * (isRepeated ? 1 : subsets[o]);
        csv << mesh.size() << ',' << chosen[m].name << ',' << chosen[m].newtonIterations << ','
            << order << ',' << sceneCount << ',' << distinct << ',' << t << ',' << exact / t << ','
            << t / repeated << '\n';
        std::printf("%-6zu %-10s %3d %-12s %6zu %9zu %10.1f %7.2fx %9.2f\n", mesh.size(),
                    chosen[m].name.c_str(), chosen[m].newtonIterations, order, sceneCount, distinct,
                    t, exact / t, t / repeated);
        std::fflush(stdout);
      }
  }
  std::printf("wrote %s\n", settings.replayOut.c_str());
}

}  // namespace

int main(int argc, char** argv) {
  Settings settings;
  for (int i = 1; i < argc; ++i) {
    const auto value = [&](const char* flag) {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", flag);
        std::exit(2);
      }
      return argv[++i];
    };
    if (!std::strcmp(argv[i], "--out")) settings.out = value("--out");
    else if (!std::strcmp(argv[i], "--triangles")) settings.triangles = parseList(value("--triangles"));
    else if (!std::strcmp(argv[i], "--orientations")) settings.orientations = std::atoi(value("--orientations"));
    else if (!std::strcmp(argv[i], "--min-pairs")) settings.minPairs = std::strtoull(value("--min-pairs"), nullptr, 10);
    else if (!std::strcmp(argv[i], "--replay-out")) settings.replayOut = value("--replay-out");
    else if (!std::strcmp(argv[i], "--replay-triangles")) settings.replayTriangles = parseList(value("--replay-triangles"));
    else if (!std::strcmp(argv[i], "--min-seconds")) settings.minSeconds = std::atof(value("--min-seconds"));
    else if (!std::strcmp(argv[i], "--contact-distance")) settings.contactDistance = std::atof(value("--contact-distance"));
    else if (!std::strcmp(argv[i], "--iterations")) settings.iterations = parseList(value("--iterations"));
    else if (!std::strcmp(argv[i], "--continuations")) settings.continuations = parseList(value("--continuations"));
    else if (!std::strcmp(argv[i], "--pipeline-out")) settings.pipelineOut = value("--pipeline-out");
    else {
      std::fprintf(stderr, "usage: %s [--out FILE] [--triangles a,b,...] [--orientations N] "
                           "[--min-pairs P] [--min-seconds S] [--contact-distance T] [--iterations 4,8] "
                           "[--continuations 4] [--pipeline-out FILE] [--replay-out FILE] "
                           "[--replay-triangles a,b,...]\n", argv[0]);
      return 2;
    }
  }

  if (!settings.replayOut.empty()) runReplay(settings);
  if (settings.out.empty()) {  // pipeline (and replay) part only
    if (!settings.pipelineOut.empty()) runPipeline(settings);
    return 0;
  }
  std::ofstream csv(settings.out);
  if (!csv) {
    std::fprintf(stderr, "cannot write %s\n", settings.out.c_str());
    return 1;
  }
  const std::string isa = isaInUse();
  csv << "triangles_per_particle,method,newton_iterations,pairs_per_scene,ns_per_pair,"
         "pairs_per_second,fallback_fraction,contacts_per_scene,decisions_equal_exact,"
         "speedup_vs_exact,isa,scenes,distinct_pairs\n";
  std::printf("%-6s %-10s %3s %10s %10s %14s %10s %8s %8s %6s\n", "tri", "method", "it", "pairs",
              "ns/pair", "pairs/s", "fallback", "contacts", "speedup", "scenes");

  const std::vector<Method> all = methods(settings.contactDistance, settings.iterations, settings.continuations);
  std::mt19937_64 rng(2024);
  for (int requested : settings.triangles) {
    const std::vector<Triangle> mesh = latitudeLongitudeSphereWithAbout(requested, 1.0);
    const std::size_t pairsPerScene = mesh.size() * mesh.size();
    std::vector<Scene> scenes;
    for (std::size_t o = 0, count = sceneCount(settings, pairsPerScene); o < count; ++o)
      scenes.push_back(makeScene(mesh, 0.5 * settings.contactDistance, rng));
    std::vector<TriangleDistanceResult> block(rowsPerBlock(scenes.front()) * mesh.size());

    // Bookkeeping first (one untimed sweep per method): contacts, per-pair decisions, fallbacks.
    std::vector<HybridStatistics> stats(all.size());
    std::vector<std::vector<char>> decisions(all.size());
    std::vector<std::size_t> contacts(all.size(), 0);
    for (std::size_t m = 0; m < all.size(); ++m)
      for (const Scene& s : scenes) contacts[m] += all[m].run(s, block, stats[m], &decisions[m]);
    // Timing: kRounds rounds, each running every method in turn for minSeconds / kRounds of
    // thread CPU time (whole sweeps over all scenes); the median round per method. Interleaving
    // the methods exposes them to the same machine load, so their ratios are like for like.
    constexpr int kRounds = 5;
    std::vector<std::vector<double>> roundNs(all.size());
    for (int round = 0; round < kRounds; ++round)
      for (std::size_t m = 0; m < all.size(); ++m) {
        std::size_t pairs = 0;
        HybridStatistics ignored;
        const double start = threadSeconds();
        double elapsed = 0.0;
        do {
          for (const Scene& s : scenes) all[m].run(s, block, ignored, nullptr);
          pairs += pairsPerScene * scenes.size();
          elapsed = threadSeconds() - start;
        } while (elapsed < settings.minSeconds / kRounds);
        roundNs[m].push_back(1e9 * elapsed / double(pairs));
      }
    const auto median = [](std::vector<double> v) {
      std::sort(v.begin(), v.end());
      return v[v.size() / 2];
    };
    double exactNs = 0.0;
    std::size_t exactIndex = 0;
    for (std::size_t m = 0; m < all.size(); ++m)
      if (all[m].newtonIterations == 0) {
        exactNs = median(roundNs[m]);
        exactIndex = m;
      }
    for (std::size_t m = 0; m < all.size(); ++m) {
      const Method& method = all[m];
      const double ns = median(roundNs[m]);
      const bool decisionsEqual = decisions[m] == decisions[exactIndex];
      const double contactsPerScene = double(contacts[m]) / double(scenes.size());
      const bool isHybrid = method.name.compare(0, 6, "hybrid") == 0;
      const double fallback = isHybrid ? stats[m].fallbackFraction() : 0.0;
      csv << mesh.size() << ',' << method.name << ',' << method.newtonIterations << ','
          << pairsPerScene << ',' << ns << ',' << 1e9 / ns << ',' << fallback << ','
          << contactsPerScene << ',' << (decisionsEqual ? "yes" : "no") << ','
          << exactNs / ns << ',' << isa << ',' << scenes.size() << ','
          << pairsPerScene * scenes.size() << '\n';
      std::printf("%-6zu %-10s %3d %10zu %10.1f %14.3e %9.3f%% %8.1f %7.2fx %6zu%s\n", mesh.size(),
                  method.name.c_str(), method.newtonIterations, pairsPerScene, ns, 1e9 / ns,
                  100 * fallback, contactsPerScene, exactNs / ns, scenes.size(),
                  isHybrid && !decisionsEqual ? "  DECISIONS DIFFER FROM EXACT" : "");
      std::fflush(stdout);
    }
  }
  std::printf("wrote %s (isa %s)\n", settings.out.c_str(), isa.c_str());
  if (!settings.pipelineOut.empty()) runPipeline(settings);
  return 0;
}
