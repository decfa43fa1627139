/* spacetree-dem: candidate pairs of pair_style trimesh as pair-check tasks of the core engine. */

#include "trimesh_parallel_contacts.h"

#include <oneapi/tbb/enumerable_thread_specific.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include <stdexcept>

#include "parallel/PairCheck.h"
#include "parallel/TaskParallelPairChecks.h"

using namespace LAMMPS_NS;
namespace ct = spacetree::contact;
namespace pl = spacetree::parallel;

TrimeshCandidatePair LAMMPS_NS::canonical_candidate_pair(int i, int j, const TrimeshTypeTemplate &ti,
                                                         const TrimeshTypeTemplate &tj, const int *tag,
                                                         double **x, double **quat)
{
  const std::size_t ni = ti.shape.triangleCount(), nj = tj.shape.triangleCount();
  const bool swap = nj > ni || (nj == ni && tag[j] < tag[i]);
  const int a = swap ? j : i, b = swap ? i : j;
  const TrimeshTypeTemplate &ta = swap ? tj : ti, &tb = swap ? ti : tj;
  ct::Pose pa, pb;
  pa.position = Eigen::Vector3d(x[a][0],x[a][1],x[a][2]);
  pa.orientation = Eigen::Quaterniond(quat[a][0],quat[a][1],quat[a][2],quat[a][3]);
  pb.position = Eigen::Vector3d(x[b][0],x[b][1],x[b][2]);
  pb.orientation = Eigen::Quaterniond(quat[b][0],quat[b][1],quat[b][2],quat[b][3]);
  return {a,b,&ta.shape,&tb.shape,pa,pb};
}

namespace {

// Task-level grain in nominal triangle pairs: the mesh-contact search prunes most triangle
// pairs (~10 us per grain pair instead of ~130 us all-pairs), so it wants a grain ~8x the
// engine's default of 4096 (docs/task_parallelism.md, Measured).
constexpr std::size_t kTaskTrianglePairs = 32768;

// Candidate k as engine particles 2k (body a) and 2k+1 (body b); whole pairs only.
class CandidatePairCheck : public pl::PairCheck {
 public:
  CandidatePairCheck(std::vector<std::vector<ct::ContactPoint>> &found,
                     const ct::MeshContactOptions &options)
      : found_(found), threadStates_(options) {}
  void set_pairs(const std::vector<TrimeshCandidatePair> &pairs) { pairs_ = &pairs; }

  std::size_t triangleCount(int particle) const override {
    const TrimeshCandidatePair &p = (*pairs_)[std::size_t(particle / 2)];
    return (particle % 2 == 0 ? p.shape_a : p.shape_b)->triangleCount();
  }
  bool splittable() const override { return false; }

  void check(int first, int second, std::size_t, std::size_t, pl::ContactSink &sink) const override {
    const std::size_t k = std::size_t(first / 2);
    if (first % 2 != 0 || second != first + 1)
      throw std::logic_error("trimesh parallel contacts: engine pair is not a candidate pair");
    const TrimeshCandidatePair &p = (*pairs_)[k];
    ThreadState &state = threadStates_.local();
    // found_[k] belongs to this task alone: every pair is searched by exactly one task
    std::vector<ct::ContactPoint> &out = found_[k];
    out.clear();
    state.finder.find(*p.shape_a,p.pose_a,*p.shape_b,p.pose_b,out,&state.statistics);
    for (std::size_t c = 0; c < out.size(); c++) {
      pl::TriangleContact tc;
      tc.first = first;
      tc.second = second;
      tc.firstTriangle = int(c);   // canonical order within the pair = the search's order
      tc.distance = out[c].distance;
      tc.normal = out[c].normal;
      sink.add(tc);
    }
  }

  ct::MeshContactStatistics take_statistics() {
    ct::MeshContactStatistics total;
    for (ThreadState &s : threadStates_) { total += s.statistics; s.statistics = {}; }
    return total;
  }

 private:
  struct ThreadState {
    explicit ThreadState(const ct::MeshContactOptions &options) : finder(options) {}
    ct::MeshContactFinder finder;
    ct::MeshContactStatistics statistics;
  };
  const std::vector<TrimeshCandidatePair> *pairs_ = nullptr;
  std::vector<std::vector<ct::ContactPoint>> &found_;
  mutable tbb::enumerable_thread_specific<ThreadState> threadStates_;
};

}

struct TrimeshParallelContacts::Engine {
  Engine(int threads, std::vector<std::vector<ct::ContactPoint>> &found,
         const ct::MeshContactOptions &options)
      : allow(threads > tbb::info::default_concurrency()
                  ? new tbb::global_control(tbb::global_control::max_allowed_parallelism,
                                            std::size_t(threads))
                  : nullptr),
        tasks(pl::TaskParallelOptions{threads,kTaskTrianglePairs}),
        check(found,options) {}
  // more threads than cores (e.g. threads 4 on 2 cores) needs TBB's limit raised
  std::unique_ptr<tbb::global_control> allow;
  pl::TaskParallelPairChecks tasks;
  CandidatePairCheck check;
  std::vector<pl::TriangleContact> canonical;
};

TrimeshParallelContacts::TrimeshParallelContacts(const ct::MeshContactOptions &options, int threads)
{
  if (threads < 0) throw std::invalid_argument("threads must be >= 0 (0 = TBB default)");
  if (threads == 1) serial_.reset(new ct::MeshContactFinder(options));
  else engine_.reset(new Engine(threads,found_,options));
}

TrimeshParallelContacts::~TrimeshParallelContacts() = default;

int TrimeshParallelContacts::threads() const
{
  return serial_ ? 1 : engine_->tasks.threads();
}

int TrimeshParallelContacts::defaultThreads()
{
  return tbb::info::default_concurrency();
}

std::size_t TrimeshParallelContacts::tasks() const
{
  return engine_ ? engine_->tasks.statistics().tasks : 0;
}

void TrimeshParallelContacts::search(const std::vector<TrimeshCandidatePair> &pairs,
                                     ct::MeshContactStatistics &stats)
{
  if (found_.size() < pairs.size()) found_.resize(pairs.size());
  if (serial_) {
    for (std::size_t k = 0; k < pairs.size(); k++) {
      const TrimeshCandidatePair &p = pairs[k];
      found_[k].clear();
      serial_->find(*p.shape_a,p.pose_a,*p.shape_b,p.pose_b,found_[k],&stats);
    }
    return;
  }
  engine_->check.set_pairs(pairs);
  const int n = int(pairs.size());
  engine_->tasks.run([n](auto &emit) { for (int k = 0; k < n; k++) emit(2*k,2*k+1); },
                     engine_->check,engine_->canonical);
  stats += engine_->check.take_statistics();
  // forces follow contacts(k) in k order: that must be the engine's canonical order
  std::size_t expected = 0;
  for (std::size_t k = 0; k < pairs.size(); k++) expected += found_[k].size();
  if (expected != engine_->canonical.size())
    throw std::logic_error("trimesh parallel contacts: canonical contacts != searched contacts");
  std::size_t i = 0;
  for (std::size_t k = 0; k < pairs.size(); k++)
    for (std::size_t c = 0; c < found_[k].size(); c++, i++) {
      const pl::TriangleContact &tc = engine_->canonical[i];
      if (tc.first != int(2*k) || tc.firstTriangle != int(c))
        throw std::logic_error("trimesh parallel contacts: contacts out of canonical order");
    }
}
