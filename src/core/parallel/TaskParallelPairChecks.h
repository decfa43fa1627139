// The spacetree sweep as a task producer (paper §6.3). The thread that runs the sweep never
// checks a pair itself while sweeping: each candidate pair that passed the prechecks is put
// into the current task; a task is spawned (fire and forget) as soon as it holds enough triangle
// pairs to amortise the spawn, and a pair with more triangle pairs than that is split at
// triangle level (if the check allows it) into several tasks (row ranges of its first
// particle's triangles). Worker threads steal and run the tasks; each task writes its contacts into a buffer of its own, so
// the hot path has no lock and no atomic. At the end of the sweep the producer joins once
// (task_group::wait, which makes it help with the remaining tasks), then the buffers are
// concatenated and sorted into the canonical contact order: the result is the same, bit for
// bit, for any thread count and any task size.
#pragma once

#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "parallel/PairCheck.h"
#include "parallel/TriangleContact.h"
#include "tree/Spacetree.h"

namespace spacetree::parallel {

// A list of candidate pairs found by the caller (e.g. a neighbour list), checked as tasks: the
// check of candidate k writes its result where the caller keeps it (one slot per candidate, so
// no lock and no order to restore), work(k) sizes the tasks (nominal triangle pairs).
class CandidateCheck {
 public:
  virtual ~CandidateCheck() = default;
  virtual std::size_t work(std::size_t candidate) const = 0;
  // Called concurrently for different candidates, once per candidate per sweep.
  virtual void check(std::size_t candidate) const = 0;
};

struct TaskParallelOptions {
  int threads = 0;                       // threads of the arena; 0: TBB's default (all cores)
  std::size_t taskTrianglePairs = 4096;  // work of one task in triangle pairs (>= 1): a task
                                         // collects pairs up to this, bigger pairs are split
};

struct TaskParallelStatistics {
  std::uint64_t pairs = 0;          // candidate pairs handed to the checks
  std::uint64_t splitPairs = 0;     // of these, split into several triangle-level tasks
  std::uint64_t tasks = 0;          // tasks spawned
  std::uint64_t trianglePairs = 0;  // sum of triangleCount(i) * triangleCount(j) over the pairs
  std::uint64_t contacts = 0;       // contacts found
  double producerSeconds = 0.0;     // wall time of the traversal that spawned the tasks
  double sweepSeconds = 0.0;        // wall time of the whole sweep (produce, join, sort)
};

class TaskParallelPairChecks {
 public:
  // Throws std::invalid_argument for threads < 0 or taskTrianglePairs == 0.
  explicit TaskParallelPairChecks(TaskParallelOptions options = {});

  const TaskParallelOptions& options() const { return options_; }
  int threads() const { return arena_.max_concurrency(); }

  // One sweep: produce(emit) runs on the calling thread and calls emit(i, j) for every
  // candidate pair (i != j, each unordered pair once); the checks run as tasks meanwhile.
  // Returns when all have finished, with `contacts` replaced by all contacts in canonical order.
  template <class Producer>
  void run(Producer&& produce, const PairCheck& check, std::vector<TriangleContact>& contacts) {
    const auto start = std::chrono::steady_clock::now();
    arena_.execute([&] {
      beginSweep(check);
      auto emit = [this](int i, int j) { addPair(i, j); };
      try {
        produce(emit);
      } catch (...) {
        abandonSweep();  // no task may outlive the buffers it writes to
        throw;
      }
      stats_.producerSeconds = secondsSince(start);
      finishSweep(contacts);
    });
    stats_.sweepSeconds = secondsSince(start);
  }

  // The spacetree sweep as the producer: the pairs of tree.forEachPairWithin (bounding spheres
  // within r_i + r_j + 2 eps, the precheck) become tasks.
  void run(Spacetree& tree, const PairCheck& check, std::vector<TriangleContact>& contacts,
           double relativeTolerance = 0.0) {
    run([&](auto& emit) {
      tree.forEachPairWithin([&](int i, int j, double) { emit(i, j); }, relativeTolerance);
    }, check, contacts);
  }

  // One sweep over the candidates 0..count-1 of a list: consecutive candidates are gathered into
  // tasks of about taskTrianglePairs of work (a candidate is never split); returns when all are
  // checked. statistics(): pairs = count, tasks, trianglePairs = sum of work (contacts: 0, the
  // check keeps its own).
  void runCandidates(std::size_t count, const CandidateCheck& check);

  // Counters of the last sweep.
  const TaskParallelStatistics& statistics() const { return stats_; }

 private:
  // A pair (first < second) and the row range of first's triangles it checks.
  struct PairWork {
    std::int32_t first, second;
    std::uint32_t firstBegin, firstEnd;
  };
  // The unit of spawning; owned by the producer until spawned, by its worker afterwards.
  struct Task {
    std::vector<PairWork> pairs;
    std::vector<TriangleContact> contacts;
  };

  static double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  void beginSweep(const PairCheck& check);
  void addPair(int i, int j);
  Task& openTask();   // a fresh (recycled) task buffer
  void spawn(Task& task);
  void finishSweep(std::vector<TriangleContact>& contacts);
  void abandonSweep();

  TaskParallelOptions options_;
  tbb::task_arena arena_;
  tbb::task_group group_;
  const PairCheck* check_ = nullptr;
  // Task buffers, recycled from sweep to sweep (their vectors keep their capacity). Workers
  // hold a Task*, never an index into this vector, so growing it is safe while they run.
  std::vector<std::unique_ptr<Task>> tasks_;
  std::size_t usedTasks_ = 0;
  Task* current_ = nullptr;           // the task being filled, not yet spawned
  std::size_t currentWork_ = 0;       // its triangle pairs
  TaskParallelStatistics stats_;
};

}  // namespace spacetree::parallel
