/* spacetree-dem: see timestep_atom_state.h */

#include "timestep_atom_state.h"

#include <mpi.h>

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "neighbor.h"
#include "update.h"

using namespace LAMMPS_NS;

namespace {
// record: tag, image, x, v, omega, f, torque, then the values of each TimestepAtomValues
const int kTag = 0, kImage = 1, kX = 2, kV = 5, kOmega = 8, kF = 11, kTorque = 14, kValues = 17;
}

int TimestepAtomState::record_size() const
{
  int n = kValues;
  for (const TimestepAtomValues *v : values_) n += v->count();
  return n;
}

void TimestepAtomState::save()
{
  const int nlocal = atom->nlocal;
  const size_t R = record_size();
  nsaved_ = nlocal;
  saved_step_ = update->ntimestep;
  records_.resize(R*nlocal);
  for (int i = 0; i < nlocal; i++) {
    double *r = &records_[R*i];
    r[kTag] = atom->tag[i];
    r[kImage] = atom->image[i];
    for (int d = 0; d < 3; d++) {
      r[kX+d] = atom->x[i][d];
      r[kV+d] = atom->v[i][d];
      r[kOmega+d] = atom->omega[i][d];
      r[kF+d] = atom->f[i][d];
      r[kTorque+d] = atom->torque[i][d];
    }
    int o = kValues;
    for (const TimestepAtomValues *v : values_) {
      v->pack(i,r+o);
      o += v->count();
    }
  }
}

bool TimestepAtomState::restorable()
{
  const int nlocal = atom->nlocal;
  const size_t R = record_size();
  const bool rebuilt = neighbor->lastcall > saved_step_;
  std::vector<double> shipped;
  received_.clear();
  // plan: the record each current local atom takes (nothing is changed before all ranks agree)
  plan_.assign(nlocal,(const double*)NULL);
  int ok = (saved_step_ == update->ntimestep - 1) ? 1 : 0;
  if (ok && !rebuilt) {
    // no re-neighbouring: same atoms, same order
    ok = (nlocal == nsaved_);
    for (int k = 0; ok && k < nsaved_; k++) {
      if (atom->tag[k] != int(records_[R*k+kTag])) ok = 0;
      else plan_[k] = &records_[R*k];
    }
  } else if (ok) {
    // re-neighboured: atoms sorted and possibly moved to another rank; find them by ID and send
    // the records of atoms that left to every rank (few: only those that crossed a boundary)
    if (!atom->map_style) ok = 0;
    for (int k = 0; ok && k < nsaved_; k++) {
      const int i = atom->map(int(records_[R*k+kTag]));
      if (i >= 0 && i < nlocal && !plan_[i]) plan_[i] = &records_[R*k];
      else shipped.insert(shipped.end(),&records_[R*k],&records_[R*k] + R);
    }
  }
  if (rebuilt) {   // collective: every rank takes part, whatever its own verdict
    int nsend = int(shipped.size()), nprocs = comm->nprocs;
    std::vector<int> counts(nprocs), offsets(nprocs,0);
    MPI_Allgather(&nsend,1,MPI_INT,counts.data(),1,MPI_INT,world);
    for (int p = 1; p < nprocs; p++) offsets[p] = offsets[p-1] + counts[p-1];
    received_.resize(size_t(offsets[nprocs-1] + counts[nprocs-1]));
    MPI_Allgatherv(shipped.data(),nsend,MPI_DOUBLE,received_.data(),counts.data(),offsets.data(),
                   MPI_DOUBLE,world);
    for (size_t r = 0; ok && r < received_.size(); r += R) {
      const int i = atom->map(int(received_[r+kTag]));
      if (i >= 0 && i < nlocal && !plan_[i]) plan_[i] = &received_[r];
    }
    for (int i = 0; ok && i < nlocal; i++) if (!plan_[i]) ok = 0;   // an atom without a saved state
  }
  int counts_local[2] = {nlocal,nsaved_}, counts_all[2];
  MPI_Allreduce(counts_local,counts_all,2,MPI_INT,MPI_SUM,world);
  if (counts_all[0] != counts_all[1]) ok = 0;                // atoms were added or deleted
  return ok;
}

void TimestepAtomState::restore()
{
  for (int i = 0; i < atom->nlocal; i++) {
    const double *r = plan_[i];
    // a re-neighbouring step may have wrapped the atom through a periodic boundary: keep its
    // current image and shift the saved position into that image
    double unwrapped[3], shift[3], zero[3] = {0.0,0.0,0.0};
    domain->unmap(const_cast<double*>(r+kX),tagint(r[kImage]),unwrapped);
    domain->unmap(zero,atom->image[i],shift);
    for (int d = 0; d < 3; d++) {
      atom->x[i][d] = unwrapped[d] - shift[d];
      atom->v[i][d] = r[kV+d];
      atom->omega[i][d] = r[kOmega+d];
      atom->f[i][d] = r[kF+d];
      atom->torque[i][d] = r[kTorque+d];
    }
    int o = kValues;
    for (TimestepAtomValues *v : values_) {
      v->unpack(i,r+o);
      o += v->count();
    }
  }
  comm->forward_comm();   // ghosts take the restored positions and velocities
}
