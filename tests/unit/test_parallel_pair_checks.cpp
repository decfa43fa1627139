// Task-parallel pair checks (paper §6.3): the spacetree sweep produces pair-check tasks, worker
// threads run the triangle comparisons. Checked against a serial brute-force reference on a
// dense pack of a few hundred triangulated spheres: the same contacts, bit for bit, for 1, 2 and
// 4 threads and for tasks split at triangle level, and bit-identical force sums.
#include <gtest/gtest.h>

#include <oneapi/tbb/global_control.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "parallel/ContactForceSum.h"
#include "parallel/PosedMeshPairCheck.h"
#include "parallel/TaskParallelPairChecks.h"
#include "parallel/TriangulatedSpherePack.h"
#include "tree/Spacetree.h"

using namespace spacetree;
using namespace spacetree::parallel;

namespace {

constexpr double kRadius = 1e-3;
constexpr double kContactDistance = 0.02 * kRadius;  // T = 2 eps

struct Scene {
  TriangulatedSpherePack pack;
  geometry::HybridOptions hybrid;
  Spacetree tree{SpacetreeOptions{kContactDistance / 2.0, kMaxSpacetreeLevel}};

  explicit Scene(int particles, int triangles = 48, std::uint32_t seed = 7) {
    TriangulatedSpherePackOptions o;
    o.particles = particles;
    o.trianglesPerParticle = triangles;
    o.radius = kRadius;
    o.seed = seed;
    pack = makeTriangulatedSpherePack(o);
    hybrid.contactDistance = kContactDistance;
    tree.build(reinterpret_cast<const double(*)[3]>(pack.centre.data()), pack.radius.data(),
               particles, particles);
  }
  int size() const { return int(pack.radius.size()); }
  bool boundingSpheresWithin(int i, int j) const {
    double d2 = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double d = pack.centre[i][c] - pack.centre[j][c];
      d2 += d * d;
    }
    const double cut = pack.radius[i] + pack.radius[j] + kContactDistance;
    return d2 <= cut * cut;
  }
};

// TBB caps its workers at the core count minus one by default; let 4 threads be 4 threads even on
// a 2-core machine, so that the 4-thread runs really interleave four workers' tasks.
void allowFourThreads() {
  static tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
}

// Serial reference: every pair of the pack by brute force, whole pairs, no tasks, no tree.
std::vector<TriangleContact> serialReference(const Scene& scene, const PairCheck& check) {
  std::vector<TriangleContact> contacts;
  ContactSink sink(contacts);
  for (int i = 0; i < scene.size(); ++i)
    for (int j = i + 1; j < scene.size(); ++j)
      if (scene.boundingSpheresWithin(i, j)) check.check(i, j, 0, check.triangleCount(i), sink);
  return contacts;  // i < j, rows, columns: already the canonical order
}

// A penalty spring along the line of centres, proportional to how far the triangles are inside
// the contact distance.
std::vector<Eigen::Vector3d> forceSums(const Scene& scene,
                                       const std::vector<TriangleContact>& contacts) {
  std::vector<Eigen::Vector3d> force;
  sumContactForces(contacts, scene.size(), [&](const TriangleContact& c) {
    const Eigen::Vector3d a(scene.pack.centre[c.first].data());
    const Eigen::Vector3d b(scene.pack.centre[c.second].data());
    return Eigen::Vector3d(1e3 * (kContactDistance - c.distance) * (a - b).normalized());
  }, force);
  return force;
}

bool sameBits(const double& a, const double& b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }
bool sameBits(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}

void expectBitIdentical(const std::vector<TriangleContact>& expected,
                        const std::vector<TriangleContact>& actual, const char* what) {
  ASSERT_EQ(expected.size(), actual.size()) << what;
  for (std::size_t k = 0; k < expected.size(); ++k) {
    const TriangleContact& e = expected[k];
    const TriangleContact& a = actual[k];
    ASSERT_TRUE(e.first == a.first && e.second == a.second && e.firstTriangle == a.firstTriangle &&
                e.secondTriangle == a.secondTriangle)
        << what << ": contact " << k << " is (" << a.first << "," << a.second << ","
        << a.firstTriangle << "," << a.secondTriangle << "), expected (" << e.first << ","
        << e.second << "," << e.firstTriangle << "," << e.secondTriangle << ")";
    ASSERT_TRUE(sameBits(e.distance, a.distance) && sameBits(e.pointOnFirst, a.pointOnFirst) &&
                sameBits(e.pointOnSecond, a.pointOnSecond) && sameBits(e.normal, a.normal))
        << what << ": contact " << k << " differs in distance or points";
  }
}

void expectBitIdentical(const std::vector<Eigen::Vector3d>& expected,
                        const std::vector<Eigen::Vector3d>& actual, const char* what) {
  ASSERT_EQ(expected.size(), actual.size());
  for (std::size_t p = 0; p < expected.size(); ++p)
    ASSERT_TRUE(sameBits(expected[p], actual[p]))
        << what << ": force on particle " << p << " is " << actual[p].transpose()
        << ", expected " << expected[p].transpose();
}

}  // namespace

TEST(ParallelPairChecks, SameContactsAndBitIdenticalForcesFor1To4Threads) {
  allowFourThreads();
  Scene scene(343);
  PosedMeshPairCheck check(scene.pack.meshes, scene.hybrid);
  const std::vector<TriangleContact> reference = serialReference(scene, check);
  const std::vector<Eigen::Vector3d> referenceForce = forceSums(scene, reference);
  // The pack must be a real test: many touching pairs, several contacts each, and forces.
  ASSERT_GT(reference.size(), 2000u);
  int loaded = 0;
  for (const auto& f : referenceForce) loaded += f.norm() > 0.0;
  ASSERT_GT(loaded, 300);

  for (int threads : {1, 2, 4}) {
    TaskParallelPairChecks engine(TaskParallelOptions{threads, 4096});
    EXPECT_EQ(engine.threads(), threads);
    std::vector<TriangleContact> contacts;
    engine.run(scene.tree, check, contacts);
    const std::string what = std::to_string(threads) + " threads";
    expectBitIdentical(reference, contacts, what.c_str());
    expectBitIdentical(referenceForce, forceSums(scene, contacts), what.c_str());
    EXPECT_EQ(engine.statistics().contacts, reference.size());
    EXPECT_GT(engine.statistics().tasks, 50u) << "batches must be small enough to share out";
    EXPECT_EQ(engine.statistics().splitPairs, 0u);  // 48 x 48 triangles < 4096
    if (threads == 4)
      std::printf("[ info     ] %d particles: %llu candidate pairs, %llu tasks, %zu contacts, "
                  "%d particles loaded\n", scene.size(),
                  (unsigned long long)engine.statistics().pairs,
                  (unsigned long long)engine.statistics().tasks, reference.size(), loaded);
    // Run again with the recycled buffers: nothing left over from the first sweep.
    engine.run(scene.tree, check, contacts);
    expectBitIdentical(reference, contacts, (what + ", second sweep").c_str());
  }
}

TEST(ParallelPairChecks, TriangleLevelSplitGivesTheSameContacts) {
  allowFourThreads();
  Scene scene(125, 80, 11);
  PosedMeshPairCheck check(scene.pack.meshes, scene.hybrid);
  const std::vector<TriangleContact> reference = serialReference(scene, check);
  ASSERT_GT(reference.size(), 500u);
  const std::vector<Eigen::Vector3d> referenceForce = forceSums(scene, reference);
  const std::size_t trianglesPerParticle = scene.pack.meshes.triangleCount(0);
  const std::size_t kWholeSweep = std::size_t(1) << 40;

  // Grains: one row per task, a few rows per task, the whole pair in one task.
  for (std::size_t grain : {std::size_t(1), 5 * trianglesPerParticle, kWholeSweep}) {
    for (int threads : {1, 2, 4}) {
      TaskParallelPairChecks engine(TaskParallelOptions{threads, grain});
      std::vector<TriangleContact> contacts;
      engine.run(scene.tree, check, contacts);
      const std::string what = std::to_string(threads) + " threads, grain " + std::to_string(grain);
      expectBitIdentical(reference, contacts, what.c_str());
      expectBitIdentical(referenceForce, forceSums(scene, contacts), what.c_str());
      const TaskParallelStatistics& s = engine.statistics();
      if (grain == 1) {
        EXPECT_EQ(s.splitPairs, s.pairs);
        EXPECT_EQ(s.tasks, s.pairs * trianglesPerParticle) << what;
      } else if (grain < kWholeSweep) {
        EXPECT_EQ(s.splitPairs, s.pairs);
        EXPECT_EQ(s.tasks, s.pairs * ((trianglesPerParticle + 4) / 5)) << what;
      } else {
        EXPECT_EQ(s.splitPairs, 0u);
        EXPECT_EQ(s.tasks, 1u) << what;  // everything fits one batch
      }
    }
  }
}

TEST(ParallelPairChecks, GenericProducerMatchesTheTreeSweep) {
  Scene scene(125);
  PosedMeshPairCheck check(scene.pack.meshes, scene.hybrid);
  TaskParallelPairChecks engine(TaskParallelOptions{2, 1000});
  std::vector<TriangleContact> fromTree, fromList;
  engine.run(scene.tree, check, fromTree);
  const std::uint64_t treePairs = engine.statistics().pairs;
  // Pairs in reverse order and reversed (j, i): the engine orders them itself.
  engine.run([&](auto& emit) {
    for (int i = scene.size() - 1; i >= 0; --i)
      for (int j = scene.size() - 1; j > i; --j)
        if (scene.boundingSpheresWithin(i, j)) emit(j, i);
  }, check, fromList);
  EXPECT_EQ(engine.statistics().pairs, treePairs);
  ASSERT_FALSE(fromTree.empty());
  expectBitIdentical(fromTree, fromList, "reversed list vs tree");
}

// Fire and forget: the producer never runs a check while it is still producing, with one
// thread (all checks run in the final join) or several.
namespace {
class WatchingCheck : public PairCheck {
 public:
  WatchingCheck(const PairCheck& inner, const std::atomic<bool>& produced, std::thread::id producer)
      : inner_(inner), produced_(produced), producer_(producer) {}
  std::size_t triangleCount(int p) const override { return inner_.triangleCount(p); }
  void check(int i, int j, std::size_t b, std::size_t e, ContactSink& sink) const override {
    if (std::this_thread::get_id() == producer_) {
      ++onProducer;
      if (!produced_.load()) ++onProducerDuringSweep;
    } else {
      ++onWorkers;
    }
    inner_.check(i, j, b, e, sink);
  }
  mutable std::atomic<int> onProducer{0}, onProducerDuringSweep{0}, onWorkers{0};

 private:
  const PairCheck& inner_;
  const std::atomic<bool>& produced_;
  std::thread::id producer_;
};
}  // namespace

TEST(ParallelPairChecks, ProducerNeverRunsChecksDuringTheSweep) {
  Scene scene(216);
  PosedMeshPairCheck inner(scene.pack.meshes, scene.hybrid);
  for (int threads : {1, 2}) {
    std::atomic<bool> produced{false};
    // task_arena::execute runs the producer on the calling thread.
    const std::thread::id producer = std::this_thread::get_id();
    WatchingCheck check(inner, produced, producer);
    TaskParallelPairChecks engine(TaskParallelOptions{threads, 2304});
    std::vector<TriangleContact> contacts;
    engine.run([&](auto& emit) {
      EXPECT_EQ(std::this_thread::get_id(), producer);
      scene.tree.forEachPairWithin([&](int i, int j, double) { emit(i, j); });
      produced = true;
    }, check, contacts);
    EXPECT_EQ(check.onProducerDuringSweep.load(), 0) << threads << " threads";
    EXPECT_EQ(std::uint64_t(check.onProducer + check.onWorkers), engine.statistics().pairs);
    if (threads == 1) {
      EXPECT_EQ(check.onWorkers.load(), 0);
    }
    EXPECT_FALSE(contacts.empty());
  }
}

TEST(ParallelPairChecks, ProducerExceptionPropagatesAndEngineStaysUsable) {
  Scene scene(64);
  PosedMeshPairCheck check(scene.pack.meshes, scene.hybrid);
  TaskParallelPairChecks engine(TaskParallelOptions{2, 100});
  std::vector<TriangleContact> contacts;
  EXPECT_THROW(engine.run([&](auto& emit) {
    scene.tree.forEachPairWithin([&](int i, int j, double) { emit(i, j); });
    throw std::runtime_error("producer failed");
  }, check, contacts), std::runtime_error);
  engine.run(scene.tree, check, contacts);
  expectBitIdentical(serialReference(scene, check), contacts, "after an exception");
}

namespace {
// Throws on one pair: a failing check must reach the caller, not vanish in a worker.
class FailingCheck : public PairCheck {
 public:
  explicit FailingCheck(const PairCheck& inner) : inner_(inner) {}
  std::size_t triangleCount(int p) const override { return inner_.triangleCount(p); }
  void check(int i, int j, std::size_t b, std::size_t e, ContactSink& sink) const override {
    if (i == 10 || j == 10) throw std::domain_error("check failed");
    inner_.check(i, j, b, e, sink);
  }

 private:
  const PairCheck& inner_;
};
}  // namespace

TEST(ParallelPairChecks, CheckExceptionPropagatesAndEngineStaysUsable) {
  Scene scene(64);
  PosedMeshPairCheck check(scene.pack.meshes, scene.hybrid);
  FailingCheck failing(check);
  for (int threads : {1, 2}) {
    TaskParallelPairChecks engine(TaskParallelOptions{threads, 100});
    std::vector<TriangleContact> contacts;
    EXPECT_THROW(engine.run(scene.tree, failing, contacts), std::domain_error);
    engine.run(scene.tree, check, contacts);
    expectBitIdentical(serialReference(scene, check), contacts, "after a failed check");
  }
}

TEST(ParallelPairChecks, BadOptionsAreRejected) {
  EXPECT_THROW(TaskParallelPairChecks(TaskParallelOptions{-1, 10}), std::invalid_argument);
  EXPECT_THROW(TaskParallelPairChecks(TaskParallelOptions{1, 0}), std::invalid_argument);
  PosedMeshes none;
  geometry::HybridOptions zero;  // contact distance 0
  EXPECT_THROW(PosedMeshPairCheck(none, zero), std::invalid_argument);
  EXPECT_GE(TaskParallelPairChecks().threads(), 1);  // TBB default
}

namespace {
// Candidate k's result: a deterministic function of k, written to its own slot; counts calls.
class SquareCandidates : public spacetree::parallel::CandidateCheck {
 public:
  explicit SquareCandidates(std::size_t n) : result(n, 0.0), calls(n) {}
  std::size_t work(std::size_t k) const override { return k % 7 == 0 ? 0 : 100 * (k % 5 + 1); }
  void check(std::size_t k) const override {
    double x = 0.0;
    for (std::size_t i = 0; i <= k % 97; ++i) x += std::sqrt(double(k + i));
    result[k] = x;
    calls[k].fetch_add(1);
  }
  mutable std::vector<double> result;
  mutable std::vector<std::atomic<int>> calls;
};
}  // namespace

TEST(ParallelPairChecks, CandidateListEveryCandidateOnceSameResultsForAnyThreadsAndGrain) {
  static tbb::global_control allow(tbb::global_control::max_allowed_parallelism, 4);
  const std::size_t n = 5000;
  SquareCandidates reference(n);
  for (std::size_t k = 0; k < n; ++k) reference.check(k);
  std::size_t work = 0;
  for (std::size_t k = 0; k < n; ++k) work += reference.work(k);
  for (int threads : {1, 2, 4})
    for (std::size_t grain : {std::size_t(1), std::size_t(1000), std::size_t(1) << 40}) {
      SquareCandidates check(n);
      TaskParallelPairChecks engine(TaskParallelOptions{threads, grain});
      engine.runCandidates(n, check);
      for (std::size_t k = 0; k < n; ++k) {
        ASSERT_EQ(check.calls[k].load(), 1) << k;
        ASSERT_EQ(std::memcmp(&check.result[k], &reference.result[k], sizeof(double)), 0) << k;
      }
      EXPECT_EQ(engine.statistics().pairs, n);
      EXPECT_EQ(engine.statistics().trianglePairs, work);
      if (grain == 1) EXPECT_EQ(engine.statistics().tasks, n);          // one task per candidate
      if (grain == (std::size_t(1) << 40)) EXPECT_EQ(engine.statistics().tasks, 1u);
    }
  TaskParallelPairChecks engine(TaskParallelOptions{2, 10});
  SquareCandidates none(0);
  engine.runCandidates(0, none);
  EXPECT_EQ(engine.statistics().tasks, 0u);
}
