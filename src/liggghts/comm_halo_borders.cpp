/* spacetree-dem: Comm::borders() by size class (the hook of liggghts_patch/0006).

   The swaps keep LIGGGHTS' Cartesian pattern (per dimension, 2 maxneed swaps alternating
   left/right, ghosts of earlier dimensions forwarded in later ones, pbc shifts at the grid's
   ends, sendneed limits at non-periodic ends), once per size class, coarse classes first: the
   ghosts of a class are complete on every rank before the next finer class decides how far its
   atoms must go (MultilevelHalo / core parallel::HaloReach). An atom is sent across a face when
   it lies within its own reach of that face; the reach travels with the atom (one extra double
   in the border message) so that ranks forwarding it in later swaps use the owner's value.
   nswap becomes passes x 2 (maxneed[0] + maxneed[1] + maxneed[2]); forward and reverse comm
   run over all swaps unchanged (a pass's swaps only forward that pass's ghosts). */

#include <mpi.h>

#include <algorithm>
#include <vector>

#include "atom.h"
#include "atom_vec.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "memory.h"
#include "multilevel_halo.h"

using namespace LAMMPS_NS;

void Comm::halo_borders()
{
  MultilevelHalo &rule = *halo;
  AtomVec *avec = atom->avec;
  if (triclinic) error->all(FLERR,"Neighbor spacetree halo levels: triclinic boxes are not supported");

  rule.begin();
  const int npass = rule.passes();
  const int nbase = 2*(maxneed[0] + maxneed[1] + maxneed[2]);
  nswap = npass*nbase;
  if (nswap > maxswap) grow_swap(nswap);

  const int nlocal = atom->nlocal;
  // comm_modify group: only the group's atoms (the first atom->nfirst) are sent
  const int nowned = bordergroup ? atom->nfirst : nlocal;
  std::vector<double> &reach = rule.pass_reach();
  const int size_message = size_border + 1;   // the atom's border data and its reach
  int iswap = 0, smax = 0, rmax = 0;
  // A rank that sends in no direction (one rank, no periodic dimension) gets no ghosts either:
  // no per-atom reach, only the classes' counts.
  bool sends = false;
  for (int dim = 0; dim < 3; dim++) sends = sends || sendneed[dim][0] > 0 || sendneed[dim][1] > 0;
  if (!sends) std::vector<double>().swap(reach);

  for (int p = 0; p < npass; p++) {
    const int c = rule.pass_class(p);
    const std::vector<int> &owned = rule.owned_of_class(c,nowned,sends);
    const std::vector<double> &owned_reach = rule.owned_reach();
    const int first_ghost = nlocal + atom->nghost;   // this pass's ghosts start here
    if (sends) {
      reach.assign(first_ghost,-1.0);
      for (size_t k = 0; k < owned.size(); k++) reach[owned[k]] = owned_reach[k];
    }
    int sent = 0, received = 0;

    for (int dim = 0; dim < 3; dim++) {
      int nfirst = 0, nlast = 0;
      const double lo = domain->sublo[dim], hi = domain->subhi[dim], mid = 0.5*(lo + hi);
      for (int ineed = 0; ineed < 2*maxneed[dim]; ineed++) {
        const bool to_left = ineed % 2 == 0;
        // the swap, laid out as Comm::setup() lays out the single-shell swaps
        sendproc[iswap] = procneigh[dim][to_left ? 0 : 1];
        recvproc[iswap] = procneigh[dim][to_left ? 1 : 0];
        pbc_flag[iswap] = 0;
        for (int k = 0; k < 6; k++) pbc[iswap][k] = 0;
        if (to_left && myloc[dim] == 0) pbc_flag[iswap] = 1, pbc[iswap][dim] = 1;
        if (!to_left && myloc[dim] == procgrid[dim]-1) pbc_flag[iswap] = 1, pbc[iswap][dim] = -1;

        // first swaps of a dimension: owned atoms of the class and this pass's ghosts of the
        // earlier dimensions; later swaps: the ghosts the previous two swaps brought
        if (to_left) {
          nfirst = nlast;
          nlast = nlocal + atom->nghost;
        }
        double **x = atom->x;
        int nsend = 0;
        const auto take = [&](int i) {
          const double xi = x[i][dim], r = reach[i];
          const bool in = to_left ? ((ineed < 2 || xi >= mid) && xi <= lo + r)
                                  : (xi >= hi - r && (ineed < 2 || xi <= mid));
          if (!in) return;
          if (nsend == maxsendlist[iswap]) grow_list(iswap,nsend);
          sendlist[iswap][nsend++] = i;
        };
        if (ineed/2 < sendneed[dim][ineed % 2]) {
          if (ineed < 2) {
            for (int i : owned) take(i);
            for (int i = first_ghost; i < nlast; i++) take(i);
          } else {
            for (int i = nfirst; i < nlast; i++) take(i);
          }
        }

        // message: the reaches, then the border data
        if (nsend*size_message > maxsend) grow_send(nsend*size_message,0);
        for (int k = 0; k < nsend; k++) buf_send[k] = reach[sendlist[iswap][k]];
        int n = nsend;
        if (ghost_velocity)
          n += avec->pack_border_vel(nsend,sendlist[iswap],&buf_send[nsend],pbc_flag[iswap],pbc[iswap]);
        else
          n += avec->pack_border(nsend,sendlist[iswap],&buf_send[nsend],pbc_flag[iswap],pbc[iswap]);

        int nrecv = 0;
        double *buf = buf_send;
        if (sendproc[iswap] != me) {
          MPI_Sendrecv(&nsend,1,MPI_INT,sendproc[iswap],0,&nrecv,1,MPI_INT,recvproc[iswap],0,
                       world,MPI_STATUS_IGNORE);
          if (nrecv*size_message > maxrecv) grow_recv(nrecv*size_message);
          MPI_Request request;
          if (nrecv) MPI_Irecv(buf_recv,nrecv*size_message,MPI_DOUBLE,recvproc[iswap],0,world,&request);
          if (n) MPI_Send(buf_send,n,MPI_DOUBLE,sendproc[iswap],0,world);
          if (nrecv) MPI_Wait(&request,MPI_STATUS_IGNORE);
          buf = buf_recv;
        } else {
          nrecv = nsend;
        }

        const int first = nlocal + atom->nghost;
        if (sends) reach.resize(first + nrecv);
        for (int k = 0; k < nrecv; k++) reach[first + k] = buf[k];
        if (ghost_velocity) avec->unpack_border_vel(nrecv,first,&buf[nrecv]);
        else avec->unpack_border(nrecv,first,&buf[nrecv]);

        smax = std::max(smax,nsend);
        rmax = std::max(rmax,nrecv);
        sendnum[iswap] = nsend;
        recvnum[iswap] = nrecv;
        size_forward_recv[iswap] = nrecv*size_forward;
        size_reverse_send[iswap] = nrecv*size_reverse;
        size_reverse_recv[iswap] = nsend*size_reverse;
        firstrecv[iswap] = first;
        atom->nghost += nrecv;
        sent += nsend;
        received += nrecv;
        iswap++;
      }
    }
    rule.count_pass(c,sent,received);
    // this class's ghosts are the partners the finer classes serve
    if (p + 1 < npass) rule.add_partners(first_ghost,nlocal + atom->nghost,c);
  }

  // forward and reverse comm of every swap fit the buffers
  int max = std::max(maxforward*smax,maxreverse*rmax);
  if (max > maxsend) grow_send(max,0);
  max = std::max(maxforward*rmax,maxreverse*smax);
  if (max > maxrecv) grow_recv(max);

  if (map_style) atom->map_set();
  exchangeEventsCorrector();
}
