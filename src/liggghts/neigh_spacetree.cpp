/* spacetree-dem: the `neighbor <skin> spacetree` granular list builder.
   Produces exactly the list granular_bin_no_newton produces (pairs with
   |xi-xj| <= (ri+rj)*contact_distance_factor + skin, own/own pairs once under
   the lower index, own/ghost pairs always, contact history copied from
   fix contacthistory), but finds the candidates with the multilevel
   spacetree instead of bins sized by the biggest particle. */

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>

#include "atom.h"
#include "comm.h"
#include "domain.h"
#include "error.h"
#include "fix.h"
#include "fix_contact_history.h"
#include "fix_spacetree.h"
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
  spacetree->options = spacetree::SpacetreeOptions();
  if (!spacetree->halo) spacetree->halo.reset(new MultilevelHalo(lmp));
  spacetree->halo->reset_settings();

  char msg[512];
  for (int iarg = 0; iarg < narg; iarg += 2) {
    if (strcmp(arg[iarg],"maxlevel") == 0) {
      if (iarg+1 >= narg)
        error->all(FLERR,"Illegal neighbor spacetree command: keyword 'maxlevel' needs a value");
      int value = force->inumeric(FLERR,arg[iarg+1]);
      if (value < 0 || value > spacetree::kMaxSpacetreeLevel) {
        snprintf(msg,sizeof(msg),"Illegal neighbor spacetree command: maxlevel %d is outside [0,%d]",
                 value,spacetree::kMaxSpacetreeLevel);
        error->all(FLERR,msg);
      }
      spacetree->options.maxLevel = value;
    } else if (spacetree->halo->set_keyword(arg[iarg],iarg+1 < narg ? arg[iarg+1] : NULL)) {
      // halo levels|single, halo_ratio Q: multilevel_halo.cpp
    } else {
      snprintf(msg,sizeof(msg),"Illegal neighbor spacetree command: unknown keyword '%s' "
               "(known keywords: maxlevel, halo, halo_ratio)",arg[iarg]);
      error->all(FLERR,msg);
    }
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

  // A fix spacetree (its init() ran before this one) supplies the adaptive grid.
  spacetree->grid_fix = static_cast<FixSpacetree *>(modify->find_fix_style_strict("spacetree",0));

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
   granular half list, newton off, with contact history
------------------------------------------------------------------------- */

void Neighbor::granular_spacetree_no_newton(NeighList *list)
{
  NeighSpacetree &st = *spacetree;
  if (st.bins_for_meshes) bin_atoms();

  double **x = atom->x;
  double *radius = atom->radius;
  int *tag = atom->tag;
  int *type = atom->type;
  int *mask = atom->mask;
  int *molecule = atom->molecule;
  const int nlocal = atom->nlocal;
  const int nall = nlocal + atom->nghost;

  // 1. Pairs from the tree. With contact_distance_factor 1 its cut-off is bit for bit the one
  //    of granular_bin_no_newton; otherwise it is a superset (1e-12 relative) that is cut
  //    again here with LIGGGHTS' expression.
  // the tree works on contact radii: the atoms' radii unless contact_distance_factor scales them
  const double *contact_radius = radius;
  if (contactDistanceFactor != 1.0) {
    st.contact_radius.resize(nall);
    for (int i = 0; i < nall; i++) st.contact_radius[i] = radius[i]*contactDistanceFactor;
    contact_radius = st.contact_radius.data();
  }
  st.options.epsilon = 0.5*skin;
  try {
    st.tree.setOptions(st.options);
    const double (*xs)[3] = reinterpret_cast<const double (*)[3]>(nall ? x[0] : NULL);
    if (st.grid_fix) {
      // Ghost velocities exist only with `communicate ... vel yes`; without them the
      // reluctant grid treats every close pair as approaching (more refinement, same lists).
      const double (*vs)[3] = (nall && comm->ghost_velocity)
        ? reinterpret_cast<const double (*)[3]>(atom->v[0]) : NULL;
      st.grid_fix->build_tree(st.tree,xs,vs,contact_radius,nall,nlocal);
    } else {
      st.tree.build(xs,contact_radius,nall,nlocal);
    }
  } catch (const std::exception &e) {
    error->one(FLERR,e.what());
  }

  st.pair_i.clear();
  st.pair_j.clear();
  st.first.assign(nlocal+1,0);
  const double cdf = contactDistanceFactor, skin_ = skin;
  const bool exact_cut = (cdf == 1.0 && 2.0*st.options.epsilon == skin);
  const int exclude_ = exclude;
  st.tree.forEachPairWithin([&](int a, int b, double rsq) {
    // own/own pairs once under the lower index, own/ghost pairs under the owned atom
    const int i = a < b ? a : b;
    const int j = a < b ? b : a;
    const double radsum = (radius[i] + radius[j]) * cdf;
    if (!exact_cut) {
      const double delx = x[i][0] - x[j][0];
      const double dely = x[i][1] - x[j][1];
      const double delz = x[i][2] - x[j][2];
      rsq = delx*delx + dely*dely + delz*delz;
      const double cutsq = (radsum+skin_) * (radsum+skin_);
      if (rsq > cutsq) return;
    }
    if (exclude_ && exclusion(i,j,type[i],type[j],mask,molecule)) return;
    // touching pairs carry contact history: remember which, as a sign bit on j
    st.pair_i.push_back(i);
    st.pair_j.push_back(rsq < radsum*radsum ? ~j : j);
    st.first[i+1]++;
  }, exact_cut ? 0.0 : 1e-12);

  // The reluctant grid refines for the pairs this sweep found (used from the next build on).
  if (st.grid_fix) {
    try {
      st.grid_fix->after_sweep(reinterpret_cast<const double (*)[3]>(nall ? x[0] : NULL),
                               (nall && comm->ghost_velocity)
                                 ? reinterpret_cast<const double (*)[3]>(atom->v[0]) : NULL,
                               contact_radius,nall,st.pair_i,st.pair_j);
    } catch (const std::exception &e) {
      error->one(FLERR,e.what());
    }
  }

  // 2. Per-atom neighbour arrays (CSR), each sorted by index for a canonical order
  //    (touching pairs, stored as ~j, sort first; the order is still deterministic).
  int maxcount = 0;
  for (int i = 0; i < nlocal; i++) {
    maxcount = std::max(maxcount,st.first[i+1]);
    st.first[i+1] += st.first[i];
  }
  st.neighbours.resize(st.pair_i.size());
  st.fill.assign(st.first.begin(),st.first.end()-1);
  for (size_t p = 0; p < st.pair_i.size(); p++)
    st.neighbours[st.fill[st.pair_i[p]]++] = st.pair_j[p];
  for (int i = 0; i < nlocal; i++)
    std::sort(st.neighbours.begin()+st.first[i],st.neighbours.begin()+st.first[i+1]);

  // 3. A big particle among thousands of small ones may exceed neigh_modify one:
  //    size the pages from the tree instead of failing.
  FixContactHistory *fix_history = list->fix_history;
  NeighList *listgranhistory = fix_history ? list->listgranhistory : NULL;
  if (maxcount > list->oneatom) {
    const int one = maxcount + maxcount/4 + 16;
    const int page = std::max(list->pgsize,10*one);
    oneatom = std::max(oneatom,one);           // contact history follows at its next exchange
    pgsize = std::max(pgsize,10*oneatom);
    list->oneatom = one;
    list->pgsize = page;
    for (int t = 0; t < comm->nthreads; t++) list->ipage[t].init(one,page,1);
    if (listgranhistory) {
      const int dnum = listgranhistory->dnum;
      listgranhistory->oneatom = one;
      listgranhistory->pgsize = page;
      for (int t = 0; t < comm->nthreads; t++) {
        listgranhistory->ipage[t].init(one,page,1);
        if (dnum) listgranhistory->dpage[t].init(dnum*one,dnum*page,1);
      }
    }
  }

  // 4. Fill LIGGGHTS' pages exactly as granular_bin_no_newton does.
  int *ilist = list->ilist;
  int *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  MyPage<int> *ipage = list->ipage;

  int *npartner = NULL, **partner = NULL;
  double **contacthistory = NULL;
  int **first_contact_flag = NULL;
  double **first_contact_hist = NULL;
  MyPage<int> *ipage_contact_flag = NULL;
  MyPage<double> *dpage_contact_hist = NULL;
  int dnum = 0;
  if (fix_history) {
    npartner = fix_history->npartner_;
    partner = fix_history->partner_;
    contacthistory = fix_history->contacthistory_;
    first_contact_flag = listgranhistory->firstneigh;
    first_contact_hist = listgranhistory->firstdouble;
    ipage_contact_flag = listgranhistory->ipage;
    dpage_contact_hist = listgranhistory->dpage;
    dnum = listgranhistory->dnum;
  }

  int inum = 0;
  ipage->reset();
  if (fix_history) {
    ipage_contact_flag->reset();
    dpage_contact_hist->reset();
  }

  for (int i = 0; i < nlocal; i++) {
    const int n = st.first[i+1] - st.first[i];
    const int *js = st.neighbours.data() + st.first[i];
    int *neighptr = ipage->vget();
    if (!neighptr) error->one(FLERR,"Neighbor list overflow, boost neigh_modify one");
    int *contact_flag_ptr = NULL;
    double *contact_hist_ptr = NULL;
    if (fix_history) {
      contact_flag_ptr = ipage_contact_flag->vget();
      contact_hist_ptr = dpage_contact_hist->vget();
      if (!contact_flag_ptr || !contact_hist_ptr)
        error->one(FLERR,"Neighbor list overflow, boost neigh_modify one");
    }

    int nn = 0;
    for (int k = 0; k < n; k++) {
      const bool touching = js[k] < 0;
      const int j = touching ? ~js[k] : js[k];
      neighptr[k] = j;
      if (!fix_history) continue;
      int m = npartner[i];
      if (touching)
        for (m = 0; m < npartner[i]; m++)
          if (partner[i][m] == tag[j]) break;
      if (m < npartner[i]) {
        contact_flag_ptr[k] = 1;
        for (int d = 0; d < dnum; d++) contact_hist_ptr[nn++] = contacthistory[i][m*dnum+d];
      } else {
        contact_flag_ptr[k] = 0;
        for (int d = 0; d < dnum; d++) contact_hist_ptr[nn++] = 0.0;
      }
    }

    ilist[inum++] = i;
    firstneigh[i] = neighptr;
    numneigh[i] = n;
    ipage->vgot(n);
    if (ipage->status())
      error->one(FLERR,"Neighbor list overflow, boost neigh_modify one");
    if (fix_history) {
      first_contact_flag[i] = contact_flag_ptr;
      first_contact_hist[i] = contact_hist_ptr;
      ipage_contact_flag->vgot(n);
      dpage_contact_hist->vgot(nn);
    }
  }

  list->inum = inum;
}
