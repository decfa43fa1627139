/* spacetree-dem: the `neighbor <skin> spacetree` granular list builder.
   Produces exactly the list granular_bin_no_newton produces (pairs with
   |xi-xj| <= (ri+rj)*contact_distance_factor + skin, own/own pairs once under
   the lower index, own/ghost pairs always, contact history copied from
   fix contacthistory), but finds the candidates with the multilevel
   spacetree instead of bins sized by the biggest particle. Four steps:
   find the pairs (core NeighbourSearch, counted per owned atom), the largest
   count, page sizing for crowded particles, LIGGGHTS' pages with the contact
   history. */

#include <algorithm>
#include <climits>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_contact_history.h"
#include "force.h"
#include "modify.h"
#include "my_page.h"
#include "neigh_list.h"
#include "neigh_spacetree.h"
#include "neighbor.h"

using namespace LAMMPS_NS;

/* ----------------------------------------------------------------------
   keywords after `neighbor <skin> spacetree`
------------------------------------------------------------------------- */

void Neighbor::spacetree_settings(int narg, char **arg)
{
  if (!spacetree) spacetree = new NeighSpacetree;
  spacetree::NeighbourSearch &search = spacetree->search;
  if (!spacetree->halo) spacetree->halo.reset(new MultilevelHalo(lmp));
  spacetree->halo->reset_settings();

  char msg[512];
  int maxlevel = spacetree::kMaxSpacetreeLevel;
  for (int iarg = 0; iarg < narg; iarg += 2) {
    if (strcmp(arg[iarg],"maxlevel") == 0) {
      if (iarg+1 >= narg)
        error->all(FLERR,"Illegal neighbor spacetree command: keyword 'maxlevel' needs a value");
      maxlevel = force->inumeric(FLERR,arg[iarg+1]);
      if (maxlevel < 0 || maxlevel > spacetree::kMaxSpacetreeLevel) {
        snprintf(msg,sizeof(msg),"Illegal neighbor spacetree command: maxlevel %d is outside [0,%d]",
                 maxlevel,spacetree::kMaxSpacetreeLevel);
        error->all(FLERR,msg);
      }
    } else if (spacetree->halo->set_keyword(arg[iarg],iarg+1 < narg ? arg[iarg+1] : NULL)) {
      // halo levels|single, halo_ratio Q: multilevel_halo.cpp
    } else {
      snprintf(msg,sizeof(msg),"Illegal neighbor spacetree command: unknown keyword '%s' "
               "(known keywords: maxlevel, halo, halo_ratio)",arg[iarg]);
      error->all(FLERR,msg);
    }
  }
  try {
    search.setMaxLevel(maxlevel);
    search.setSkin(skin);  // fix spacetree's init (before Neighbor::init) reads eps
  } catch (const std::exception &e) {
    error->all(FLERR,e.what());
  }
}

namespace {

// Modify::max_min_rad's largest radius without the types of fixed obstacles.
double max_movable_radius(Modify *modify, Atom *atom, MPI_Comm world)
{
  const int ntypes = atom->ntypes;
  const int *obstacle = NULL;
  for (int i = 0; i < modify->nfix && !obstacle; i++) {
    int dim = 0;
    obstacle = static_cast<const int *>(modify->fix[i]->extract("obstacle_types",dim));
  }
  const auto movable = [&](int t) { return !obstacle || !obstacle[t]; };
  double maxrad = 0.0;
  for (int i = 0; i < modify->nfix; i++)
    for (int t = 1; t <= ntypes; t++)
      if (movable(t)) maxrad = std::max(maxrad,modify->fix[i]->max_rad(t));
  if (atom->radius)
    for (int i = 0; i < atom->nlocal; i++)
      if (movable(atom->type[i])) maxrad = std::max(maxrad,atom->radius[i]);
  double all = 0.0;
  MPI_Allreduce(&maxrad,&all,1,MPI_DOUBLE,MPI_MAX,world);
  return all;
}

}

/* ----------------------------------------------------------------------
   checks at each run's Neighbor::init()
------------------------------------------------------------------------- */

void Neighbor::spacetree_init()
{
  if (!spacetree) spacetree = new NeighSpacetree;
  char msg[512];

  if (!atom->radius_flag)
    error->all(FLERR,"Neighbor spacetree requires an atom style with a per-atom radius "
               "(e.g. atom_style granular or sphere)");
  if (includegroup)
    error->all(FLERR,"Neighbor spacetree does not support neigh_modify include");
  if (domain->triclinic)
    error->all(FLERR,"Neighbor spacetree does not support triclinic boxes");

  // A particle must not reach its own periodic image, nor be wider than a fixed box. Fixed
  // obstacles (types a fix names through extract("obstacle_types"): fix trimesh/template ...
  // fixed) are exempt from the fixed-box test: they never move, their reach is their surface,
  // and the tree's cube is sized from the particles, not the box.
  double maxrad,minrad;
  modify->max_min_rad(maxrad,minrad);
  const double movable = max_movable_radius(modify,atom,world);
  const double reach = 2.0*maxrad*contactDistanceFactor + skin;
  const char dimname[3] = {'x','y','z'};
  for (int d = 0; d < domain->dimension; d++) {
    const double length = domain->prd[d];
    if (domain->periodicity[d] && length < reach) {
      snprintf(msg,sizeof(msg),"Neighbor spacetree: domain too small for the largest particle: "
               "its diameter (times contact_distance_factor) plus skin, %g, exceeds the periodic "
               "box length %g in %c",reach,length,dimname[d]);
      error->all(FLERR,msg);
    }
    if (domain->boundary[d][0] == 1 && domain->boundary[d][1] == 1 && length < 2.0*movable) {
      snprintf(msg,sizeof(msg),"Neighbor spacetree: domain too small for the largest particle: "
               "its diameter %g exceeds the fixed box length %g in %c",2.0*movable,length,dimname[d]);
      error->all(FLERR,msg);
    }
  }

  try {
    spacetree->search.setSkin(skin);
  } catch (const std::exception &e) {
    error->all(FLERR,e.what());
  }
  // A fix spacetree chose the grid in its init() (before this one); without one, the tree
  // builds on a cube of its own.
  if (!modify->find_fix_style_strict("spacetree",0)) spacetree->search.dropGrid();

  // Mesh walls (fix neighlist/mesh) read the regular bins filled by the pair builder.
  spacetree->bins_for_meshes = false;
  for (int i = 0; i < modify->nfix; i++)
    if (strstr(modify->fix[i]->style,"neighlist/mesh"))
      spacetree->bins_for_meshes = true;

  // Ghost atoms per size class (Comm::halo_borders), or NULL: the stock shell.
  if (!spacetree->halo) spacetree->halo.reset(new MultilevelHalo(lmp));
  comm->halo = spacetree->halo->install();
}

void Neighbor::spacetree_free()
{
  if (spacetree && comm && comm->halo == spacetree->halo.get()) comm->halo = NULL;
  delete spacetree;
  spacetree = NULL;
}

/* ----------------------------------------------------------------------
   the four steps of the granular list build
------------------------------------------------------------------------- */

namespace {

// 2. The largest neighbour count of an owned atom (the judge counted them).
int largest_count(const int *numneigh, int nlocal)
{
  int maxcount = 0;
  for (int i = 0; i < nlocal; i++) maxcount = std::max(maxcount,numneigh[i]);
  return maxcount;
}

// 3. A big particle among thousands of small ones may exceed neigh_modify one: size the pages
//    (of the list and of its contact-history list) from the tree instead of failing. Returns
//    the new `one` (0: the pages were big enough).
int size_pages(NeighList *list, int maxcount, int nthreads)
{
  if (maxcount <= list->oneatom) return 0;
  const int one = maxcount + maxcount/4 + 16;
  const int page = std::max(list->pgsize,10*one);
  list->oneatom = one;
  list->pgsize = page;
  for (int t = 0; t < nthreads; t++) list->ipage[t].init(one,page,1);
  NeighList *history = list->fix_history ? list->listgranhistory : NULL;
  if (history) {
    const int dnum = history->dnum;
    history->oneatom = one;
    history->pgsize = page;
    for (int t = 0; t < nthreads; t++) {
      history->ipage[t].init(one,page,1);
      if (dnum) history->dpage[t].init(dnum*one,dnum*page,1);
    }
  }
  return one;
}

// The touching partners of each owned atom and their history (fix contacthistory's arrays,
// read by Neighbor, its friend).
struct Partners {
  int *count;
  int **tag;
  double **history;
};

// Zeroes [b, e). A stretch bigger than a core's cache (the contact history of a scene of
// 100 000s of pairs: MBs) is written with streaming stores: these zeros are read back only for
// the pairs that come to touch, and through the cache each line would be read before being
// written and would evict what the build still needs. Smaller stretches stay in the cache.
template <class T>
void zero(T *b, T *e)
{
#ifdef __SSE2__
  const std::size_t kStreamingBytes = std::size_t(1) << 20;
  if (static_cast<std::size_t>(e - b)*sizeof(T) > kStreamingBytes) {
    char *p = reinterpret_cast<char *>(b), *const end = reinterpret_cast<char *>(e);
    for (; reinterpret_cast<std::uintptr_t>(p) & 15; p++) *p = 0;
    const __m128i zeros = _mm_setzero_si128();
    for (; p + 16 <= end; p += 16) _mm_stream_si128(reinterpret_cast<__m128i *>(p),zeros);
    std::fill(p,end,char(0));
    return;
  }
#endif
  std::fill(b,e,T(0));
}

// A stretch of consecutive chunks of one page kind, zeroed when the next chunk starts
// elsewhere (on a new page) or at the end.
template <class T>
struct StretchToZero {
  T *begin = NULL, *end = NULL;
  void add(T *b, T *e)
  {
    if (b != end) {
      zero(begin,end);
      begin = b;
    }
    end = e;
  }
  void finish()
  {
    zero(begin,end);
    begin = end = NULL;
  }
};

// a <= b afterwards, without a data-dependent branch (the difference taken in 64 bits cannot
// overflow).
inline void compare_exchange(int &a, int &b)
{
  const long long d = static_cast<long long>(b) - a;
  const int shift = static_cast<int>(d & (d >> 63));  // min(b - a, 0)
  a += shift;
  b -= shift;
}

// Clears the judge's touching mark (~j -> j); returns 1 if it was set.
inline int unmark(int &v)
{
  const int marked = static_cast<int>(static_cast<unsigned>(v) >> 31);
  v ^= v >> 31;
  return marked;
}

// One atom's neighbours in the canonical order whatever the sweep order: ascending, with the
// touching ones (marked as ~j < 0 by the judge) first; then the marks are cleared. Returns how
// many touch. Keys are distinct (one entry per pair), so every sort gives the same order. Lists
// of up to 2 (nine atoms in ten of a dense one-size pack) and of 3 or 4 (most atoms beside a big
// particle) are ordered without data-dependent branches: an insertion sort mispredicts about
// once per list, which costs more than the sort itself.
inline int order_neighbours(int *js, int n)
{
  if (n <= 2) {  // n = 1 reads and writes its entry twice; n = 0 a scratch entry
    int scratch = 0;
    int *const p = n ? js : &scratch;
    const int last = n ? n-1 : 0;
    int a = p[0], b = p[last];
    compare_exchange(a,b);
    const int touching = unmark(a) + (unmark(b) & -static_cast<int>(n == 2));
    p[last] = b;
    p[0] = a;
    return touching;
  }
  if (n <= 4) {
    int v0 = js[0], v1 = js[1], v2 = js[2];
    const int pad = -static_cast<int>(n == 3);  // a fourth entry of INT_MAX sorts last
    int v3 = (js[n-1] & ~pad) | (INT_MAX & pad);
    compare_exchange(v0,v1);
    compare_exchange(v2,v3);
    compare_exchange(v0,v2);
    compare_exchange(v1,v3);
    compare_exchange(v1,v2);
    const int touching = unmark(v0) + unmark(v1) + unmark(v2) + unmark(v3);
    js[n-1] = v3;  // first: with n == 3 the padding is overwritten by v2
    js[2] = v2;
    js[1] = v1;
    js[0] = v0;
    return touching;
  }
  if (n > 32) {
    std::sort(js,js+n);
  } else {
    for (int a = 1; a < n; a++) {
      const int v = js[a];
      int b = a;
      for (; b > 0 && js[b-1] > v; b--) js[b] = js[b-1];
      js[b] = v;
    }
  }
  int touching = 0;
  for (int k = 0; k < n; k++) touching += unmark(js[k]);
  return touching;
}

// Entries of the chunks taken from a page at once (unless one atom alone has more): a page is
// left for the next at most that far before its end.
const int kBlock = 1024;

// 4. LIGGGHTS' pages, filled as granular_bin_no_newton fills them: per owned atom its
//    neighbours and, with contact history, the touching partners' history (zeros for new ones).
//    The chunks of consecutive atoms (list, contact flags, history; sized by the judge's
//    counts) are taken in blocks, one MyPage::get per block and page kind, and the flags and
//    history are zeroed stretch by stretch of a page; the listed pairs go straight into the
//    chunks; then each list is put in order and only atoms with partners look them up.
void fill_pages(NeighList *list, const NeighSpacetree &st, const Partners &partners, const int *tag,
                int nlocal, Error *error)
{
  int *ilist = list->ilist;
  int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  MyPage<int> *ipage = list->ipage;
  const int *count = numneigh;  // the judge's counts

  FixContactHistory *fix_history = list->fix_history;
  NeighList *listgranhistory = fix_history ? list->listgranhistory : NULL;
  const int *npartner = partners.count;
  int **partner = partners.tag;
  double **contacthistory = partners.history;
  int **first_contact_flag = NULL;
  double **first_contact_hist = NULL;
  MyPage<int> *ipage_contact_flag = NULL;
  MyPage<double> *dpage_contact_hist = NULL;
  int dnum = 0;
  int one = list->oneatom;  // the largest chunk MyPage::get hands out
  if (fix_history) {
    first_contact_flag = listgranhistory->firstneigh;
    first_contact_hist = listgranhistory->firstdouble;
    ipage_contact_flag = listgranhistory->ipage;
    dpage_contact_hist = listgranhistory->dpage;
    dnum = listgranhistory->dnum;
    one = std::min(one,listgranhistory->oneatom);
  }

  ipage->reset();
  if (fix_history) {
    ipage_contact_flag->reset();
    dpage_contact_hist->reset();
  }
  // Blocks of consecutive atoms' chunks. A count above `one` (size_pages prevents it) is the
  // overflow error before anything is written.
  const int block = std::min(one,kBlock);
  StretchToZero<int> flags_to_zero;
  StretchToZero<double> history_to_zero;
  for (int first = 0; first < nlocal;) {
    if (count[first] > one) error->one(FLERR,"Neighbor list overflow, boost neigh_modify one");
    int end = first + 1, size = count[first];
    for (; end < nlocal && size + count[end] <= block; end++) size += count[end];
    int *neigh = ipage->get(size);
    if (!neigh) error->one(FLERR,"Neighbor list overflow, boost neigh_modify one");
    int *flag = NULL;
    double *hist = NULL;
    if (fix_history) {
      flag = ipage_contact_flag->get(size);
      hist = dpage_contact_hist->get(dnum*size);
      if (!flag || !hist) error->one(FLERR,"Neighbor list overflow, boost neigh_modify one");
      flags_to_zero.add(flag,flag+size);
      history_to_zero.add(hist,hist+dnum*size);
    }
    for (int i = first, offset = 0; i < end; i++) {
      ilist[i] = i;
      if (fix_history) {
        first_contact_flag[i] = flag + offset;
        first_contact_hist[i] = hist + dnum*offset;
      }
      offset += count[i];
      firstneigh[i] = neigh + offset;  // the fill cursor below: moves back to the chunk's start
    }
    first = end;
  }
  flags_to_zero.finish();
  history_to_zero.finish();
#ifdef __SSE2__
  _mm_sfence();  // streamed zeros ordered before the history copies below
#endif
  list->inum = nlocal;

  const spacetree::NeighbourSearch::ListedPairs &pairs = st.pairs;
  const int *pi = pairs.first.data(), *pj = pairs.second.data();
  const size_t npairs = pairs.size();  // (stores through int* would reload it)
  for (size_t p = 0; p < npairs; p++) *--firstneigh[pi[p]] = pj[p];

  for (int i = 0; i < nlocal; i++) {
    int *js = firstneigh[i];
    const int touching = order_neighbours(js,numneigh[i]);
    if (!fix_history || !npartner[i]) continue;
    // the touching ones come first: a continued contact keeps its history
    int *contact_flag_ptr = first_contact_flag[i];
    double *contact_hist_ptr = first_contact_hist[i];
    for (int k = 0; k < touching; k++) {
      const int j = js[k];
      int m = 0;
      while (m < npartner[i] && partner[i][m] != tag[j]) m++;
      if (m == npartner[i]) continue;
      contact_flag_ptr[k] = 1;
      for (int d = 0; d < dnum; d++) contact_hist_ptr[k*dnum+d] = contacthistory[i][m*dnum+d];
    }
  }
}

}

/* ----------------------------------------------------------------------
   granular half list, newton off, with contact history
------------------------------------------------------------------------- */

void Neighbor::granular_spacetree_no_newton(NeighList *list)
{
  NeighSpacetree &st = *spacetree;
  if (st.bins_for_meshes) bin_atoms();

  double **x = atom->x;
  double *radius = atom->radius;
  int *type = atom->type;
  int *mask = atom->mask;
  int *molecule = atom->molecule;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;

  // 1. The pairs, from the core search (grid update, tree, sweep, refinement). With
  //    contact_distance_factor 1 its cut-off is bit for bit the one of granular_bin_no_newton;
  //    otherwise it is a superset (1e-12 relative) that is cut again here with LIGGGHTS'
  //    expression. The tree works on contact radii: the atoms' radii unless
  //    contact_distance_factor scales them.
  const double *contact_radius = radius;
  if (contactDistanceFactor != 1.0) {
    st.contact_radius.resize(nall);
    for (int i = 0; i < nall; i++) st.contact_radius[i] = radius[i]*contactDistanceFactor;
    contact_radius = st.contact_radius.data();
  }
  const double cdf = contactDistanceFactor, skin_ = skin;
  const bool exact_cut = (cdf == 1.0 && 2.0*st.search.epsilon() == skin);
  const int exclude_ = exclude;
  using Verdict = spacetree::NeighbourSearch::Verdict;
  // the count of each owned atom's pairs goes straight into the list's numneigh
  int *count = list->numneigh;
  std::fill(count,count+nlocal,0);
  auto judge = [&](int i, int j, double rsq, double contact_radsum) {
    // own/own pairs once under the lower index, own/ghost pairs under the owned atom; with
    // contact_distance_factor 1 the tree's radius sum is radius[i] + radius[j]
    const double radsum = exact_cut ? contact_radsum : (radius[i] + radius[j]) * cdf;
    if (!exact_cut) {
      const double delx = x[i][0] - x[j][0];
      const double dely = x[i][1] - x[j][1];
      const double delz = x[i][2] - x[j][2];
      rsq = delx*delx + dely*dely + delz*delz;
      const double cutsq = (radsum+skin_) * (radsum+skin_);
      if (rsq > cutsq) return Verdict::Skip;
    }
    if (exclude_ && exclusion(i,j,type[i],type[j],mask,molecule)) return Verdict::Skip;
    // touching pairs carry contact history: marked; i (the lower index) owns the pair
    count[i]++;
    return rsq < radsum*radsum ? Verdict::KeepMarked : Verdict::Keep;
  };
  // Ghost velocities exist only with `communicate ... vel yes`; without them the reluctant
  // grid treats every close pair as approaching (more refinement, same lists).
  const double (*xs)[3] = reinterpret_cast<const double (*)[3]>(nall ? x[0] : NULL);
  const double (*vs)[3] = (nall && comm->ghost_velocity)
    ? reinterpret_cast<const double (*)[3]>(atom->v[0]) : NULL;
  try {
    st.search.findPairs(xs,vs,contact_radius,nall,nlocal,exact_cut ? 0.0 : 1e-12,judge,st.pairs);
  } catch (const std::exception &e) {
    error->one(FLERR,e.what());
  }

  // 2.-4.
  const int maxcount = largest_count(list->numneigh,nlocal);
  const int one = size_pages(list,maxcount,comm->nthreads);
  if (one) {
    oneatom = std::max(oneatom,one);  // contact history follows at its next exchange
    pgsize = std::max(pgsize,10*oneatom);
  }
  Partners partners = {NULL,NULL,NULL};
  if (FixContactHistory *f = list->fix_history)
    partners = Partners{f->npartner_,f->partner_,f->contacthistory_};
  fill_pages(list,st,partners,atom->tag,nlocal,error);
}
