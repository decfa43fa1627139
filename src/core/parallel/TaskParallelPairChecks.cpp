#include "parallel/TaskParallelPairChecks.h"

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace spacetree::parallel {

namespace {
int arenaConcurrency(const TaskParallelOptions& options) {
  if (options.threads < 0)
    throw std::invalid_argument("TaskParallelPairChecks: threads must be >= 0 (0 = TBB default)");
  if (options.taskTrianglePairs == 0)
    throw std::invalid_argument("TaskParallelPairChecks: taskTrianglePairs must be >= 1");
  return options.threads > 0 ? options.threads : int(tbb::task_arena::automatic);
}
}  // namespace

TaskParallelPairChecks::TaskParallelPairChecks(TaskParallelOptions options)
    : options_(options), arena_(arenaConcurrency(options)) {}

void TaskParallelPairChecks::beginSweep(const PairCheck& check) {
  check_ = &check;
  usedTasks_ = 0;
  current_ = nullptr;
  currentWork_ = 0;
  stats_ = {};
}

TaskParallelPairChecks::Task& TaskParallelPairChecks::openTask() {
  if (usedTasks_ == tasks_.size()) tasks_.push_back(std::make_unique<Task>());
  Task& task = *tasks_[usedTasks_++];
  task.pairs.clear();
  task.contacts.clear();
  return task;
}

void TaskParallelPairChecks::spawn(Task& task) {
  ++stats_.tasks;
  Task* t = &task;
  const PairCheck* check = check_;
  group_.run([t, check] {
    ContactSink sink(t->contacts);
    for (const PairWork& w : t->pairs) check->check(w.first, w.second, w.firstBegin, w.firstEnd, sink);
  });
}

void TaskParallelPairChecks::addPair(int i, int j) {
  const int first = std::min(i, j), second = std::max(i, j);
  const std::size_t rows = check_->triangleCount(first);
  const std::size_t columns = check_->triangleCount(second);
  const std::size_t work = rows * columns;
  ++stats_.pairs;
  stats_.trianglePairs += work;
  const std::size_t grain = options_.taskTrianglePairs;

  if (work > grain && rows > 1 && check_->splittable()) {
    // Triangle-level split: row ranges of about `grain` triangle pairs each, one task each.
    const std::size_t rowsPerTask = std::max<std::size_t>(1, grain / std::max<std::size_t>(columns, 1));
    ++stats_.splitPairs;
    for (std::size_t begin = 0; begin < rows; begin += rowsPerTask) {
      Task& task = openTask();
      task.pairs.push_back({first, second, std::uint32_t(begin),
                            std::uint32_t(std::min(rows, begin + rowsPerTask))});
      spawn(task);
    }
    return;
  }
  if (current_ == nullptr) current_ = &openTask();
  current_->pairs.push_back({first, second, 0, std::uint32_t(rows)});
  // A pair without triangles still costs a call: count it as one unit of work.
  currentWork_ += std::max<std::size_t>(work, 1);
  if (currentWork_ >= grain) {
    spawn(*current_);
    current_ = nullptr;
    currentWork_ = 0;
  }
}

void TaskParallelPairChecks::finishSweep(std::vector<TriangleContact>& contacts) {
  if (current_ != nullptr) {
    spawn(*current_);
    current_ = nullptr;
    currentWork_ = 0;
  }
  // The one synchronisation of the sweep; the producer helps with the remaining tasks.
  group_.wait();
  std::size_t total = 0;
  for (std::size_t t = 0; t < usedTasks_; ++t) total += tasks_[t]->contacts.size();
  contacts.clear();
  contacts.reserve(total);
  for (std::size_t t = 0; t < usedTasks_; ++t)
    contacts.insert(contacts.end(), tasks_[t]->contacts.begin(), tasks_[t]->contacts.end());
  // Canonical order: a pair's contacts may come from several tasks, in any order. Stable: the
  // buffers are concatenated in spawn order (the producer's, deterministic), so ties keep the
  // order of the one task that found them.
  std::stable_sort(contacts.begin(), contacts.end(), canonicalContactLess);
  stats_.contacts = total;
  check_ = nullptr;
}

void TaskParallelPairChecks::runCandidates(std::size_t count, const CandidateCheck& check) {
  const auto start = std::chrono::steady_clock::now();
  stats_ = {};
  stats_.pairs = count;
  const std::size_t grain = options_.taskTrianglePairs;
  const CandidateCheck* c = &check;
  arena_.execute([&] {
    std::size_t begin = 0, work = 0;
    const auto spawnRange = [&](std::size_t end) {
      ++stats_.tasks;
      group_.run([c, begin, end] {
        for (std::size_t k = begin; k < end; ++k) c->check(k);
      });
      begin = end;
      work = 0;
    };
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t w = check.work(k);
      stats_.trianglePairs += w;
      work += std::max<std::size_t>(w, 1);  // a candidate without triangles still costs a call
      if (work >= grain) spawnRange(k + 1);
    }
    if (begin < count) spawnRange(count);
    stats_.producerSeconds = secondsSince(start);
    group_.wait();  // the one synchronisation; the caller's thread helps
  });
  stats_.sweepSeconds = secondsSince(start);
}

void TaskParallelPairChecks::abandonSweep() {
  group_.cancel();
  try {
    group_.wait();
  } catch (...) {
    // the producer's exception is the one that propagates
  }
  current_ = nullptr;
  check_ = nullptr;
}

}  // namespace spacetree::parallel
