/* spacetree-dem: contact statistics of pair_style trimesh. */

#include "compute_trimesh_contacts.h"

#include "error.h"
#include "force.h"
#include "pair_trimesh.h"
#include "update.h"

using namespace LAMMPS_NS;

ComputeTrimeshContacts::ComputeTrimeshContacts(LAMMPS *lmp, int &iarg, int narg, char **arg) :
  Compute(lmp, iarg, narg, arg), pair(NULL)
{
  if (iarg != narg) error->all(FLERR,"Illegal compute trimesh/contacts command: it takes no arguments");
  vector_flag = 1;
  size_vector = 5;
  extvector = 0;
  vector = new double[5];
}

ComputeTrimeshContacts::~ComputeTrimeshContacts()
{
  delete [] vector;
}

void ComputeTrimeshContacts::init()
{
  pair = dynamic_cast<PairTrimesh*>(force->pair_match("trimesh",1));
  if (!pair) error->all(FLERR,"Compute trimesh/contacts requires pair_style trimesh");
}

void ComputeTrimeshContacts::compute_vector()
{
  invoked_vector = update->ntimestep;
  pair->contact_statistics(vector);
}
