/* spacetree-dem: see timestep_wall_history.h */

#include "timestep_wall_history.h"

#include <cstring>
#include <string>

#include "comm.h"
#include "error.h"
#include "fix_property_atom.h"
#include "fix_wall_gran.h"
#include "lammps.h"
#include "modify.h"

using namespace LAMMPS_NS;

std::vector<std::unique_ptr<TimestepWallHistory>> TimestepWallHistory::collect(LAMMPS *lmp)
{
  std::vector<std::unique_ptr<TimestepWallHistory>> found;
  Modify *modify = lmp->modify;
  for (int f = 0; f < modify->nfix; f++) {
    if (strcmp(modify->fix[f]->style,"wall/gran") != 0) continue;
    FixWallGran *wall = static_cast<FixWallGran*>(modify->fix[f]);
    if (wall->dnum() <= 0) continue;
    if (wall->is_mesh_wall()) {
      if (lmp->comm->me == 0)
        lmp->error->warning(FLERR,"Fix adapt/timestep rollback: the tangential history of mesh wall "
                            "(fix wall/gran mesh) is not restored by a rollback; use a model without "
                            "tangential history on that wall or accept one extra increment per rollback");
      continue;
    }
    const std::string name = std::string("history_") + wall->id;
    const int ifix = modify->find_fix(name.c_str());
    if (ifix < 0) continue;   // created in the wall's post_create; absent before the first run
    FixPropertyAtom *hist = static_cast<FixPropertyAtom*>(modify->fix[ifix]);
    if (!hist->array_atom) continue;   // the wall's history is rows of get_nvalues() (style vector)
    found.emplace_back(new TimestepWallHistory(hist));
  }
  return found;
}

TimestepWallHistory::TimestepWallHistory(FixPropertyAtom *history) :
  history_(history), nvalues_(history->get_nvalues())
{
}

void TimestepWallHistory::pack(int i, double *values) const
{
  for (int k = 0; k < nvalues_; k++) values[k] = history_->array_atom[i][k];
}

void TimestepWallHistory::unpack(int i, const double *values)
{
  for (int k = 0; k < nvalues_; k++) history_->array_atom[i][k] = values[k];
}
