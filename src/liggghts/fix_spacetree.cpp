/* spacetree-dem: see fix_spacetree.h */

#include "fix_spacetree.h"

#include <cstdio>
#include <climits>
#include <cstring>
#include <exception>
#include <fstream>
#include <utility>

#include "comm.h"
#include "error.h"
#include "fix_lookup.h"
#include "force.h"
#include "modify.h"
#include "neigh_spacetree.h"
#include "neighbor.h"
#include "tree/AdaptiveGrid.h"
#include "tree/LeafCellVtk.h"
#include "tree/NeighbourSearch.h"
#include "tree/WordPacking.h"
#include "update.h"

using namespace LAMMPS_NS;
using namespace FixConst;

FixSpacetree::FixSpacetree(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), grid_given(false), vtk_every(0), restart_read(false),
  restored_grid_pending(false)
{
  char msg[512];
  restart_global = 1;
  for (int k = 0; k < kKeywords; k++) given[k] = false;
  // `grid` may be left out when a restart file holds this fix (restart() fills it in).
  const bool keyword_first = narg > 3 && (strcmp(arg[3],"shock") == 0 || strcmp(arg[3],"threshold") == 0 ||
                                          strcmp(arg[3],"maxlevel") == 0 || strcmp(arg[3],"padding") == 0 ||
                                          strcmp(arg[3],"vtk") == 0);
  const bool has_grid = narg > 3 && strcmp(arg[3],"grid") == 0;
  if ((has_grid && narg < 5) || (!has_grid && narg > 3 && !keyword_first))
    error->all(FLERR,"Illegal fix spacetree command: expected 'grid regular|adaptive|reluctant' "
               "after the style");
  int iarg = 3;
  if (has_grid) {
    given[kGrid] = true;
    if (strcmp(arg[4],"regular") == 0) options.type = spacetree::GridType::Regular;
    else if (strcmp(arg[4],"adaptive") == 0) options.type = spacetree::GridType::Adaptive;
    else if (strcmp(arg[4],"reluctant") == 0) options.type = spacetree::GridType::Reluctant;
    else {
      snprintf(msg,sizeof(msg),"Illegal fix spacetree command: unknown grid type '%s' "
               "(regular, adaptive or reluctant)",arg[4]);
      error->all(FLERR,msg);
    }
    iarg = 5;
  }

  while (iarg < narg) {
    const char *key = arg[iarg];
    const int nvalues = strcmp(key,"vtk") == 0 ? 2 : 1;
    if (iarg + nvalues >= narg) {
      snprintf(msg,sizeof(msg),"Illegal fix spacetree command: keyword '%s' needs %d value%s",
               key,nvalues,nvalues > 1 ? "s" : "");
      error->all(FLERR,msg);
    }
    if (strcmp(key,"shock") == 0) {
      given[kShock] = true;
      options.shock = force->inumeric(FLERR,arg[iarg+1]);
      if (options.shock <= 0) error->all(FLERR,"Illegal fix spacetree command: shock must be > 0");
    } else if (strcmp(key,"threshold") == 0) {
      given[kThreshold] = true;
      options.coarseningThreshold = force->inumeric(FLERR,arg[iarg+1]);
      if (options.coarseningThreshold < 0)
        error->all(FLERR,"Illegal fix spacetree command: threshold must be >= 0");
    } else if (strcmp(key,"maxlevel") == 0) {
      given[kMaxlevel] = true;
      options.maxLevel = force->inumeric(FLERR,arg[iarg+1]);
      if (options.maxLevel < 0 || options.maxLevel > spacetree::kMaxSpacetreeLevel) {
        snprintf(msg,sizeof(msg),"Illegal fix spacetree command: maxlevel %d is outside [0,%d]",
                 options.maxLevel,spacetree::kMaxSpacetreeLevel);
        error->all(FLERR,msg);
      }
    } else if (strcmp(key,"padding") == 0) {
      given[kPadding] = true;
      options.padding = force->numeric(FLERR,arg[iarg+1]);
      if (!(options.padding >= 0.0 && options.padding <= 10.0))
        error->all(FLERR,"Illegal fix spacetree command: padding must be in [0,10]");
    } else if (strcmp(key,"vtk") == 0) {
      given[kVtk] = true;
      vtk_every = force->inumeric(FLERR,arg[iarg+1]);
      vtk_file = arg[iarg+2];
      if (vtk_every <= 0) error->all(FLERR,"Illegal fix spacetree command: vtk interval must be > 0");
    } else {
      snprintf(msg,sizeof(msg),"Illegal fix spacetree command: unknown keyword '%s' "
               "(known: shock threshold maxlevel padding vtk)",key);
      error->all(FLERR,msg);
    }
    iarg += 1 + nvalues;
  }
  // With one of shock/threshold left out the other may still come from a restart file: the
  // pair is then checked in restart() / init().
  if (given[kShock] == given[kThreshold]) check_options();
  if (given[kVtk]) check_options();
  if (find_other_fix_of_style(modify,"spacetree",this))
    error->all(FLERR,"Fix spacetree: only one fix spacetree may exist");
  if (vtk_every > 0) nevery = vtk_every;
}

void FixSpacetree::check_options()
{
  char msg[512];
  if (options.coarseningThreshold >= options.shock) {
    snprintf(msg,sizeof(msg),"Illegal fix spacetree command: threshold %d must be below shock %d "
             "(else fresh refinements are coarsened at once)",options.coarseningThreshold,options.shock);
    error->all(FLERR,msg);
  }
  if (vtk_every > 0 && comm->nprocs > 1 && vtk_file.find('%') == std::string::npos)
    error->all(FLERR,"Illegal fix spacetree command: on more than one MPI rank the vtk file "
               "name needs a '%' (replaced by the rank; each rank writes its own grid)");
}

FixSpacetree::~FixSpacetree()
{
  // The grid lives in the neighbour search, which drops it at the next Neighbor::init() when
  // no fix spacetree is left; nothing here reads Neighbor (deleted first at exit).
}

spacetree::NeighbourSearch &FixSpacetree::search()
{
  return neighbor->spacetree->search;
}

const spacetree::AdaptiveGrid *FixSpacetree::grid()
{
  return grid_given && neighbor->spacetree ? search().grid() : NULL;
}

int FixSpacetree::setmask()
{
  // Always: Modify takes the mask before restart() may bring `vtk` from a restart file.
  return END_OF_STEP;
}

void FixSpacetree::init()
{
  if (!neighbor->uses_spacetree() || !neighbor->spacetree)
    error->all(FLERR,"Fix spacetree requires 'neighbor <skin> spacetree' (the grid drives that "
               "neighbor list builder; with bin, nsq or multi it would have no effect)");
  if (!given[kGrid] && !restart_read)
    error->all(FLERR,"Illegal fix spacetree command: expected 'grid regular|adaptive|reluctant' "
               "after the style (it may be left out only when a restart file holds this fix ID)");
  check_options();
  // The search gives the grid its halo and caps its depth. A new fix starts from the start-off
  // grid (or its restart file's grids); later runs keep refining the same grid.
  if (restored_grid_pending) apply_restored_grid();
  try {
    if (grid_given) search().useGrid(options);
    else search().useNewGrid(options);
  } catch (const std::exception &e) {
    error->all(FLERR,e.what());
  }
  grid_given = true;
}

void FixSpacetree::end_of_step()
{
  if (vtk_every > 0 && update->ntimestep % vtk_every == 0) write_vtk();
}

void FixSpacetree::write_vtk()
{
  std::string name;
  char number[32];
  for (char c : vtk_file) {
    if (c == '*') {
      snprintf(number,sizeof(number),BIGINT_FORMAT,update->ntimestep);
      name += number;
    } else if (c == '%') {
      snprintf(number,sizeof(number),"%d",comm->me);
      name += number;
    } else name += c;
  }
  if (comm->me != 0 && vtk_file.find('%') == std::string::npos) return;  // one rank only
  std::ofstream out(name.c_str(),std::ios::binary);
  if (!out) {
    char msg[512];
    snprintf(msg,sizeof(msg),"Fix spacetree: cannot open vtk file '%s'",name.c_str());
    error->one(FLERR,msg);
  }
  char title[128];
  snprintf(title,sizeof(title),"spacetree %s leaf cells, step " BIGINT_FORMAT ", rank %d",
           spacetree::gridTypeName(options.type),update->ntimestep,comm->me);
  try {
    spacetree::writeLeafCellsVtk(*grid(),out,title);
  } catch (const std::exception &e) {
    error->one(FLERR,e.what());
  }
}

/* ----------------------------------------------------------------------
   Restart. The record (int64 words, written by proc 0 after an int byte count):
     magic, version, words in all, grid type, shock, threshold, maxlevel, padding (bits),
     vtk interval, vtk file name bytes, nprocs, procgrid[3], ranks with a grid (0 or nprocs),
     the vtk file name (padded to whole words), then per rank: word count, AdaptiveGrid words.
   Each rank's grid covers its own owned + ghost particles, so the grids are gathered on
   proc 0 and reused only by a run with the same rank count and processor grid.
------------------------------------------------------------------------- */

namespace {
const std::int64_t kRestartMagic = 0x53544658;  // "STFX"
const std::int64_t kRestartVersion = 1;
enum RestartHeader {
  kRMagic, kRVersion, kRWords, kRType, kRShock, kRThreshold, kRMaxlevel, kRPadding, kRVtkEvery,
  kRVtkBytes, kRNprocs, kRGrid0, kRGrid1, kRGrid2, kRRanks, kRHeaderWords
};
}

void FixSpacetree::write_restart(FILE *fp)
{
  // Collective: Modify calls it on every rank (fp is open on proc 0 only).
  const spacetree::AdaptiveGrid *current = grid();
  const std::vector<std::int64_t> mine = current ? current->serialise() : restored_grid;
  long long count = (long long) mine.size();
  const int nprocs = comm->nprocs, me = comm->me;
  std::vector<long long> counts(me == 0 ? nprocs : 0);
  MPI_Gather(&count,1,MPI_LONG_LONG,counts.data(),1,MPI_LONG_LONG,0,world);

  const std::int64_t name_words = ((std::int64_t) vtk_file.size() + 7)/8;
  std::int64_t grid_words = 0;
  bool with_grids = true;
  if (me == 0) {
    for (long long c : counts) {
      grid_words += 1 + c;
      if (c == 0) with_grids = false;  // no grid yet (no run since the fix was defined)
    }
    // Modify stores the record with an int byte count, MPI_Gatherv takes int counts.
    if ((kRHeaderWords + name_words + grid_words)*8 > (std::int64_t) INT_MAX) {
      error->warning(FLERR,"Fix spacetree: the grids are too big for the restart file; only "
                     "the options are written (a restarted run starts from the start-off grid)");
      with_grids = false;
    }
  }
  int flag = with_grids ? 1 : 0;
  MPI_Bcast(&flag,1,MPI_INT,0,world);
  with_grids = flag != 0;

  std::vector<std::int64_t> record;
  if (me == 0) {
    record.assign(kRHeaderWords + name_words,0);
    record[kRMagic] = kRestartMagic;
    record[kRVersion] = kRestartVersion;
    record[kRType] = (std::int64_t) options.type;
    record[kRShock] = options.shock;
    record[kRThreshold] = options.coarseningThreshold;
    record[kRMaxlevel] = options.maxLevel;
    record[kRPadding] = spacetree::wordOfDouble(options.padding);
    record[kRVtkEvery] = vtk_every;
    record[kRVtkBytes] = (std::int64_t) vtk_file.size();
    record[kRNprocs] = nprocs;
    for (int d = 0; d < 3; d++) record[kRGrid0+d] = comm->procgrid[d];
    record[kRRanks] = with_grids ? nprocs : 0;
    if (!vtk_file.empty()) memcpy(&record[kRHeaderWords],vtk_file.data(),vtk_file.size());
  }
  if (with_grids) {
    std::vector<int> recvcounts, displs;
    std::vector<std::int64_t> all;
    if (me == 0) {
      recvcounts.resize(nprocs);
      displs.resize(nprocs);
      int at = 0;
      for (int p = 0; p < nprocs; p++) {
        recvcounts[p] = (int) counts[p];
        displs[p] = at;
        at += recvcounts[p];
      }
      all.resize(at);
    }
    MPI_Gatherv(const_cast<std::int64_t *>(mine.data()),(int) count,MPI_LONG_LONG,all.data(),
                recvcounts.data(),displs.data(),MPI_LONG_LONG,0,world);
    if (me == 0)
      for (int p = 0; p < nprocs; p++) {
        record.push_back(counts[p]);
        record.insert(record.end(),all.begin() + displs[p],all.begin() + displs[p] + recvcounts[p]);
      }
  }
  if (me == 0) {
    record[kRWords] = (std::int64_t) record.size();
    const int n = (int) (record.size()*sizeof(std::int64_t));
    fwrite(&n,sizeof(int),1,fp);
    fwrite(record.data(),sizeof(std::int64_t),record.size(),fp);
  }
}

void FixSpacetree::restart(char *buf)
{
  // Called on every rank with the whole record when the restated fix has this ID.
  char msg[1024];
  std::int64_t head[kRHeaderWords];
  memcpy(head,buf,3*sizeof(std::int64_t));
  if (head[kRMagic] != kRestartMagic || head[kRVersion] != kRestartVersion ||
      head[kRWords] < kRHeaderWords)
    error->all(FLERR,"Fix spacetree: the restart file's fix spacetree record is not one this "
               "version wrote");
  std::vector<std::int64_t> record((size_t) head[kRWords]);
  memcpy(record.data(),buf,record.size()*sizeof(std::int64_t));
  restart_read = true;
  const bool me0 = comm->me == 0;

  // Options: the file's value where the command named none; the command's (with a warning
  // when it differs) where it did.
  std::string from_file;
  auto merge_int = [&](Keyword k, const char *name, int &value, std::int64_t stored) {
    if (!given[k]) {
      value = (int) stored;
      from_file += std::string(" ") + name;
    } else if (value != stored && me0) {
      snprintf(msg,sizeof(msg),"Fix spacetree: keyword '%s' is %d in this command but %lld in "
               "the restart file: using %d",name,value,(long long) stored,value);
      error->warning(FLERR,msg);
    }
  };
  const spacetree::GridType stored_type = (spacetree::GridType) record[kRType];
  bool same_type = true;
  if (!given[kGrid]) {
    options.type = stored_type;
    from_file += " grid";
  } else if (options.type != stored_type) {
    same_type = false;
    if (me0) {
      snprintf(msg,sizeof(msg),"Fix spacetree: keyword 'grid' is %s in this command but %s in the "
               "restart file: using %s; the stored grids are dropped (start-off grid)",
               spacetree::gridTypeName(options.type),spacetree::gridTypeName(stored_type),
               spacetree::gridTypeName(options.type));
      error->warning(FLERR,msg);
    }
  }
  merge_int(kShock,"shock",options.shock,record[kRShock]);
  merge_int(kThreshold,"threshold",options.coarseningThreshold,record[kRThreshold]);
  merge_int(kMaxlevel,"maxlevel",options.maxLevel,record[kRMaxlevel]);
  const double stored_padding = spacetree::doubleOfWord(record[kRPadding]);
  if (!given[kPadding]) {
    options.padding = stored_padding;
    from_file += " padding";
  } else if (options.padding != stored_padding && me0) {
    snprintf(msg,sizeof(msg),"Fix spacetree: keyword 'padding' is %g in this command but %g in "
             "the restart file: using %g",options.padding,stored_padding,options.padding);
    error->warning(FLERR,msg);
  }
  const std::string stored_file((const char *) &record[kRHeaderWords],(size_t) record[kRVtkBytes]);
  const int stored_every = (int) record[kRVtkEvery];
  if (!given[kVtk]) {
    vtk_every = stored_every;
    vtk_file = stored_file;
    if (vtk_every > 0) from_file += " vtk";
  } else if ((vtk_every != stored_every || vtk_file != stored_file) && me0) {
    snprintf(msg,sizeof(msg),"Fix spacetree: keyword 'vtk' is '%d %s' in this command but "
             "'%d %s' in the restart file: using '%d %s'",vtk_every,vtk_file.c_str(),stored_every,
             stored_every > 0 ? stored_file.c_str() : "(none)",vtk_every,vtk_file.c_str());
    error->warning(FLERR,msg);
  }
  nevery = vtk_every > 0 ? vtk_every : 1;
  check_options();

  if (me0) {
    char line[512];
    snprintf(line,sizeof(line),"Fix spacetree %s: grid %s shock %d threshold %d maxlevel %d "
             "padding %g (from the restart file:%s)\n",id,spacetree::gridTypeName(options.type),
             options.shock,options.coarseningThreshold,options.maxLevel,options.padding,
             from_file.empty() ? " none" : from_file.c_str());
    if (screen) fputs(line,screen);
    if (logfile) fputs(line,logfile);
  }

  // The grids: reused only by the same ranks over the same processor grid.
  restored_grid.clear();
  restored_grid_pending = false;
  const int stored_nprocs = (int) record[kRNprocs];
  const bool same_ranks = stored_nprocs == comm->nprocs && record[kRGrid0] == comm->procgrid[0] &&
                          record[kRGrid1] == comm->procgrid[1] && record[kRGrid2] == comm->procgrid[2];
  if (record[kRRanks] == 0) return;  // written before any run: nothing to reuse
  if (!same_type) return;
  if (!same_ranks) {
    if (me0) {
      snprintf(msg,sizeof(msg),"Fix spacetree: the restart file holds the grids of %d ranks "
               "(%lld x %lld x %lld), this run has %d (%d x %d x %d): each rank's grid covers its "
               "own subdomain, so the grids start from the start-off grid",stored_nprocs,
               (long long) record[kRGrid0],(long long) record[kRGrid1],(long long) record[kRGrid2],
               comm->nprocs,comm->procgrid[0],comm->procgrid[1],comm->procgrid[2]);
      error->warning(FLERR,msg);
    }
    return;
  }
  size_t at = (size_t) kRHeaderWords + ((size_t) record[kRVtkBytes] + 7)/8;
  for (int p = 0; p < stored_nprocs; p++) {
    if (at >= record.size() || record[at] < 0 || (size_t) record[at] > record.size() - at - 1)
      error->all(FLERR,"Fix spacetree: the restart file's grid record is truncated");
    const size_t n = (size_t) record[at];
    if (p == comm->me) restored_grid.assign(record.begin() + at + 1,record.begin() + at + 1 + n);
    at += 1 + n;
  }
  restored_grid_pending = true;
}

void FixSpacetree::apply_restored_grid()
{
  // First init() after read_restart: every rank takes its stored grid under this run's
  // options, or (if any rank cannot: other skin or maxlevel) all start from the start-off grid.
  restored_grid_pending = false;
  std::string why;
  spacetree::AdaptiveGrid restored;
  try {
    restored = spacetree::AdaptiveGrid::deserialise(restored_grid.data(),restored_grid.size(),
                                                    search().gridOptions(options));
  } catch (const std::exception &e) {
    why = e.what();
  }
  restored_grid.clear();
  int failed = why.empty() ? 0 : 1, any = 0;
  MPI_Allreduce(&failed,&any,1,MPI_INT,MPI_MAX,world);
  if (!any) {
    search().useGrid(std::move(restored));
    grid_given = true;  // init() keeps it
  } else {
    if (comm->me == 0) {
      char msg[512];
      snprintf(msg,sizeof(msg),"Fix spacetree: the grids of the restart file are not reused (%s): "
               "starting from the start-off grid",
               failed ? why.c_str() : "another rank's grid does not fit this run's skin or maxlevel");
      error->warning(FLERR,msg);
    }
    return;
  }
  if (comm->me == 0) {
    char line[256];
    snprintf(line,sizeof(line),"Fix spacetree %s: reusing the grids of %d rank%s from the restart "
             "file\n",id,comm->nprocs,comm->nprocs > 1 ? "s" : "");
    if (screen) fputs(line,screen);
    if (logfile) fputs(line,logfile);
  }
}
