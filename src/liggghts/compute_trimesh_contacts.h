/* spacetree-dem: contact statistics of pair_style trimesh (last force evaluation), a global
   vector: [1] contacts (after de-duplication), [2] body pairs tested, [3] triangle pairs
   checked, [4] hybrid fallbacks to the exact method, [5] largest penetration (halo overlap
   eps - d/2; eps = the rigid surfaces touch).

     compute ID group trimesh/contacts */

#ifdef COMPUTE_CLASS

ComputeStyle(trimesh/contacts,ComputeTrimeshContacts)

#else

#ifndef LMP_COMPUTE_TRIMESH_CONTACTS_H
#define LMP_COMPUTE_TRIMESH_CONTACTS_H

#include "compute.h"

namespace LAMMPS_NS {

class ComputeTrimeshContacts : public Compute {
 public:
  ComputeTrimeshContacts(class LAMMPS *, int &iarg, int, char **);
  ~ComputeTrimeshContacts();
  void init();
  void compute_vector();

 private:
  class PairTrimesh *pair;
};

}

#endif
#endif
