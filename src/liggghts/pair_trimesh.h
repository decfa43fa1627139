/* spacetree-dem: contacts of triangulated rigid particles (paper §3, §6.2; core:
   src/core/contact/MeshContact, src/core/contact_model/ContactModel).

     pair_style trimesh eps E stiffness S damping D [method exact|penalty|hybrid]
                        [iterations K] [continuation C] [friction MU GAMMA] [rotation yes|no]
                        [threads N]
     pair_coeff * *

   Candidate pairs come from a granular half list (newton off; `neighbor ... bin` or
   `neighbor ... spacetree`) built on radius = bounding radius + E. Per pair: bounding-sphere
   precheck |xi - xj| < Ri + Rj + 2E, then the core's triangle checks; a contact where two
   surfaces are closer than 2E, force per eq. (1) (core ContactModel): spring on the halo
   overlap plus damping while approaching; Coulomb friction only with `friction MU`, torques
   and angular velocities only with `rotation yes` (default). Obstacles (fixed template
   types) have infinite mass. Statistics: compute trimesh/contacts. `threads N`: the triangle
   checks of a step as TBB tasks on N threads (0 = TBB default, 1 = serial; same trajectory bit
   for bit, trimesh_parallel_contacts.h). Newton steps of the penalty kernel: `iterations K`
   (penalty: default 8; hybrid stage 1: default 5), `continuation C` (hybrid only: C more steps
   for the pairs stage 1 leaves uncertified, default 4, 0 = single stage; K + C <= 32). */

#ifdef PAIR_CLASS

PairStyle(trimesh,PairTrimesh)

#else

#ifndef LMP_PAIR_TRIMESH_H
#define LMP_PAIR_TRIMESH_H

#include <cstddef>
#include <memory>
#include <vector>

#include "contact/MeshContact.h"
#include "pair.h"

namespace LAMMPS_NS {

struct PairTrimeshModel;
struct TrimeshCandidatePair;

class PairTrimesh : public Pair {
 public:
  PairTrimesh(class LAMMPS *);
  ~PairTrimesh();
  void compute(int, int);
  void settings(int, char **);
  void coeff(int, char **);
  void init_style();
  void init_list(int, class NeighList *);
  double init_one(int, int);
  double single(int, int, int, int, double, double, double, double &) { return 0.0; }
  void write_restart(FILE *) {}
  void read_restart(FILE *) {}
  void *extract(const char *, int &);
  // Of the last compute, summed over ranks: contacts, body pairs tested, triangle pairs
  // checked, hybrid fallbacks; and the largest penetration (halo overlap eps - d/2, <= eps).
  void contact_statistics(double out[5]);

  // The last compute's body pairs that passed the bounding-sphere precheck (local atom indices
  // in the canonical body order, shapes, poses) with their contact points (world frame), and the
  // contact search's options (halo, distance method): what fix adapt/timestep reads for its veto,
  // contact ceiling and rollback (timestep_trimesh_scan.h).
  std::size_t candidate_pairs() const;
  const TrimeshCandidatePair &candidate_pair(std::size_t k) const;
  const std::vector<spacetree::contact::ContactPoint> &contacts_of(std::size_t k) const;
  const spacetree::contact::MeshContactOptions &contact_options() const;
  class FixTrimeshTemplate *trimesh_template() const { return templ; }

 private:
  void allocate();

  std::unique_ptr<PairTrimeshModel> model;
  class FixTrimeshTemplate *templ;
  class NeighList *list;
  double stat_max_penetration;
};

}

#endif
#endif
