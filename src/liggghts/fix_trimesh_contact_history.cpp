/* spacetree-dem: see fix_trimesh_contact_history.h */

#include "fix_trimesh_contact_history.h"

#include <algorithm>
#include <cmath>

#include <mpi.h>

#include "atom.h"
#include "contact_model/ContactHistory.h"
#include "comm.h"
#include "error.h"

using namespace LAMMPS_NS;

FixTrimeshContactHistory::FixTrimeshContactHistory(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), record_size_(0), largest_(0)
{
  if (narg != 3)
    error->all(FLERR,"Illegal fix trimesh/contact_history command: created by pair_style trimesh only");
  restart_peratom = 1;
  create_attribute = 1;
  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extvector = 0;
  grow_arrays(atom->nmax);
  atom->add_callback(0);   // grow + exchange
  atom->add_callback(1);   // restart
}

FixTrimeshContactHistory::~FixTrimeshContactHistory()
{
  atom->delete_callback(id,0);
  atom->delete_callback(id,1);
}

void FixTrimeshContactHistory::set_record_size(int size)
{
  if (size == record_size_) return;
  record_size_ = size;
  for (auto &l : current_) l.clear();
  for (auto &l : next_) l.clear();
}

const double *FixTrimeshContactHistory::lookup(int i, int tag, int &count) const
{
  const std::vector<double> &l = current_[i];
  std::size_t m = 0;
  while (m + 2 <= l.size()) {
    const int n = static_cast<int>(l[m+1]);
    if (static_cast<int>(l[m]) == tag) { count = n; return l.data() + m + 2; }
    m += 2 + std::size_t(n) * std::size_t(record_size_);
  }
  count = 0;
  return NULL;
}

void FixTrimeshContactHistory::begin()
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) next_[i].clear();
}

void FixTrimeshContactHistory::store(int i, int tag, const double *records, int count)
{
  if (count <= 0) return;
  std::vector<double> &l = next_[i];
  l.push_back(tag);
  l.push_back(count);
  l.insert(l.end(),records,records + std::size_t(count) * std::size_t(record_size_));
}

void FixTrimeshContactHistory::finish()
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) {
    current_[i].swap(next_[i]);
    note_size(i);
  }
  // the exchange buffer must hold the largest list (+1 for its length)
  comm->maxexchange_fix = std::max(comm->maxexchange_fix,largest_ + 1);
}

double FixTrimeshContactHistory::compute_vector(int n)
{
  // each pair is stored on both its atoms when both are owned, on one atom per rank otherwise:
  // every record is counted with weight 1/2 per atom that holds it, and pairs with one atom
  // owned here are held there twice in total (once per rank)
  double local[2] = {0.0,0.0};
  const int history = record_size_ - spacetree::contact_model::kContactAnchorDoubles;
  for (int i = 0; i < atom->nlocal; i++) {
    const std::vector<double> &l = current_[i];
    for (std::size_t m = 0; m + 2 <= l.size(); m += 2 + std::size_t(l[m+1]) * std::size_t(record_size_)) {
      const int count = static_cast<int>(l[m+1]);
      local[0] += 0.5 * count;
      for (int r = 0; r < count; r++)
        for (int h = 0; h < history; h++)
          local[1] += 0.5 * std::fabs(l[m + 2 + std::size_t(r) * std::size_t(record_size_) +
                                       spacetree::contact_model::kContactAnchorDoubles + h]);
    }
  }
  double global[2];
  MPI_Allreduce(local,global,2,MPI_DOUBLE,MPI_SUM,world);
  return global[n];
}

void FixTrimeshContactHistory::note_size(int i)
{
  largest_ = std::max(largest_,static_cast<int>(current_[i].size()));
}

void FixTrimeshContactHistory::grow_arrays(int nmax)
{
  current_.resize(nmax);
  next_.resize(nmax);
}

void FixTrimeshContactHistory::copy_arrays(int i, int j, int)
{
  current_[j] = current_[i];
}

int FixTrimeshContactHistory::pack_exchange(int i, double *buf)
{
  const std::vector<double> &l = current_[i];
  buf[0] = static_cast<double>(l.size());
  std::copy(l.begin(),l.end(),buf + 1);
  return 1 + static_cast<int>(l.size());
}

int FixTrimeshContactHistory::unpack_exchange(int nlocal, double *buf)
{
  const int n = static_cast<int>(buf[0]);
  current_[nlocal].assign(buf + 1,buf + 1 + n);
  note_size(nlocal);
  return 1 + n;
}

int FixTrimeshContactHistory::pack_restart(int i, double *buf)
{
  const std::vector<double> &l = current_[i];
  buf[0] = 2 + static_cast<double>(l.size());   // count including itself (LAMMPS convention)
  buf[1] = record_size_;
  std::copy(l.begin(),l.end(),buf + 2);
  return 2 + static_cast<int>(l.size());
}

void FixTrimeshContactHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int i = 0; i < nth; i++) m += static_cast<int>(extra[nlocal][m]);
  const int n = static_cast<int>(extra[nlocal][m]) - 2;
  record_size_ = static_cast<int>(extra[nlocal][m+1]);
  current_[nlocal].assign(&extra[nlocal][m+2],&extra[nlocal][m+2] + n);
  note_size(nlocal);
}

int FixTrimeshContactHistory::size_restart(int i)
{
  return 2 + static_cast<int>(current_[i].size());
}

int FixTrimeshContactHistory::maxsize_restart()
{
  // rank 0 writes the size for all: the largest over every rank
  int local = 2, global = 2;
  for (int i = 0; i < atom->nlocal; i++) local = std::max(local,2 + static_cast<int>(current_[i].size()));
  MPI_Allreduce(&local,&global,1,MPI_INT,MPI_MAX,world);
  return global;
}

double FixTrimeshContactHistory::memory_usage()
{
  double bytes = 0.0;
  for (const auto &l : current_) bytes += l.capacity() * sizeof(double);
  for (const auto &l : next_) bytes += l.capacity() * sizeof(double);
  return bytes;
}

void FixTrimeshContactHistory::save()
{
  saved_.clear();
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++) saved_[atom->tag[i]] = current_[i];
}

bool FixTrimeshContactHistory::restorable()
{
  // Atoms may have been sorted or moved to another rank since save(): the lists of saved atoms
  // that are no longer owned here go to every rank (few: those that crossed a boundary).
  const int nlocal = atom->nlocal;
  std::map<int, int> owned;
  for (int i = 0; i < nlocal; i++) owned[atom->tag[i]] = i;
  std::vector<double> shipped;
  for (const auto &s : saved_)
    if (!owned.count(s.first)) {
      shipped.push_back(s.first);
      shipped.push_back(static_cast<double>(s.second.size()));
      shipped.insert(shipped.end(),s.second.begin(),s.second.end());
    }
  const int nprocs = comm->nprocs;
  int nsend = static_cast<int>(shipped.size());
  std::vector<int> counts(nprocs), offsets(nprocs,0);
  MPI_Allgather(&nsend,1,MPI_INT,counts.data(),1,MPI_INT,world);
  for (int p = 1; p < nprocs; p++) offsets[p] = offsets[p-1] + counts[p-1];
  received_.assign(std::size_t(offsets[nprocs-1] + counts[nprocs-1]),0.0);
  MPI_Allgatherv(shipped.data(),nsend,MPI_DOUBLE,received_.data(),counts.data(),offsets.data(),
                 MPI_DOUBLE,world);
  plan_.assign(nlocal,std::make_pair((const double *) NULL,std::size_t(0)));
  std::vector<char> found(nlocal,0);
  for (std::size_t r = 0; r + 2 <= received_.size(); r += 2 + std::size_t(received_[r+1])) {
    const auto it = owned.find(static_cast<int>(received_[r]));
    if (it == owned.end()) continue;
    plan_[it->second] = std::make_pair(received_.data() + r + 2,std::size_t(received_[r+1]));
    found[it->second] = 1;
  }
  int ok = 1;
  for (int i = 0; i < nlocal; i++) {
    const auto it = saved_.find(atom->tag[i]);
    if (it != saved_.end()) plan_[i] = std::make_pair(it->second.data(),it->second.size());
    else if (!found[i]) ok = 0;   // an atom without a saved history
  }
  int counts_local[2] = {nlocal,static_cast<int>(saved_.size())}, counts_all[2];
  MPI_Allreduce(counts_local,counts_all,2,MPI_INT,MPI_SUM,world);
  if (counts_all[0] != counts_all[1]) ok = 0;   // atoms were added or deleted
  int all = 0;
  MPI_Allreduce(&ok,&all,1,MPI_INT,MPI_MIN,world);
  return all == 1;
}

void FixTrimeshContactHistory::restore()
{
  const int nlocal = atom->nlocal;
  for (int i = 0; i < nlocal; i++)
    current_[i].assign(plan_[i].first,plan_[i].first + plan_[i].second);
}
