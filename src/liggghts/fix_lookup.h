/* spacetree-dem: finding fixes by style from a fix constructor.

   While a `fix` command replaces a fix of the same ID, Modify::add_fix() deletes the old fix and
   leaves a NULL slot in modify->fix until the new one is constructed; Modify's own
   find_fix_style*() would dereference it. Constructors look fixes up through this instead. */

#ifndef LMP_SPACETREE_FIX_LOOKUP_H
#define LMP_SPACETREE_FIX_LOOKUP_H

#include <cstring>

#include "fix.h"
#include "modify.h"

namespace LAMMPS_NS {

// The first fix whose style is exactly `style`, other than `except`; NULL when there is none.
inline Fix *find_other_fix_of_style(Modify *modify, const char *style, const Fix *except)
{
  for (int i = 0; i < modify->nfix; i++) {
    Fix *f = modify->fix[i];
    if (f && f != except && strcmp(f->style,style) == 0) return f;
  }
  return NULL;
}

}  // namespace LAMMPS_NS

#endif
