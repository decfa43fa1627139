/* spacetree-dem: candidate pairs of pair_style trimesh as pair-check tasks of the core engine. */

#include "trimesh_parallel_contacts.h"

#include <oneapi/tbb/enumerable_thread_specific.h>
#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/info.h>

#include <stdexcept>

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

// Candidate k of the list as one unit of the engine's candidate sweep; its contacts go to
// found_[k], written by the one task that checks it.
class CandidatePairCheck : public pl::CandidateCheck {
 public:
  CandidatePairCheck(std::vector<std::vector<ct::ContactPoint>> &found,
                     const ct::MeshContactOptions &options)
      : found_(found), threadStates_(options) {}
  void set_pairs(const std::vector<TrimeshCandidatePair> &pairs) { pairs_ = &pairs; }

  std::size_t work(std::size_t k) const override {
    const TrimeshCandidatePair &p = (*pairs_)[k];
    return p.shape_a->triangleCount() * p.shape_b->triangleCount();
  }

  void check(std::size_t k) const override {
    const TrimeshCandidatePair &p = (*pairs_)[k];
    ThreadState &state = threadStates_.local();
    std::vector<ct::ContactPoint> &out = found_[k];
    out.clear();
    state.finder.find(*p.shape_a,p.pose_a,*p.shape_b,p.pose_b,out,&state.statistics);
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
  engine_->tasks.runCandidates(pairs.size(),engine_->check);
  stats += engine_->check.take_statistics();
}
