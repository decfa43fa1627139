/* spacetree-dem: contacts of triangulated rigid particles (paper §3, §6.2; core:
   src/core/contact/MeshContact, src/core/contact_model/ContactModel). Syntax and units:
   docs/pair_trimesh.md.

     pair_style trimesh eps E [model halo] [damping_model approach|none]
                        [tangential none|viscous|history] [rolling_friction none|epsd]
                        [cohesion none|sjkr] [stiffness S] [damping D] [friction MU [GAMMA]]
                        [tangential_stiffness KT] [method exact|penalty|hybrid] [iterations K]
                        [continuation C] [rotation yes|no] [threads N]
     pair_coeff * *

   Candidate pairs come from a granular half list (newton off; `neighbor ... bin` or
   `neighbor ... spacetree`) built on radius = bounding radius + E. Per pair: bounding-sphere
   precheck |xi - xj| < Ri + Rj + 2E, then the core's triangle checks (serially or as TBB tasks,
   trimesh_parallel_contacts.h); forces per contact point from the core's ContactModel of the
   type pair (sub-models named by the keywords, coefficients from the keywords or the LIGGGHTS
   materials: trimesh_contact_coefficients.h). Sub-models with per-contact history (tangential
   history) keep it in fix trimesh_contact_history, per particle pair on the owned atoms
   (fix_trimesh_contact_history.h), matched step to step by the core's ContactHistoryMatcher.
   Torques and angular velocities only with `rotation yes` (default). Obstacles (fixed template
   types) have infinite mass and move with their atom's velocity and angular velocity (fix
   move/trimesh). Types without template are spheres (core radius r - E plus the halo): against
   grains and obstacles here, exact sphere-triangle contacts (core SphereMeshContact); sphere
   pairs belong to pair gran (pair_style hybrid). Grains against fix wall/gran walls by their
   surfaces: trimesh_wall_contacts.h (history keyed by the wall). Every contact kind goes through
   the one law of its type pair and the same history (add_pair_forces). Statistics: compute
   trimesh/contacts. */

#ifdef PAIR_CLASS

PairStyle(trimesh,PairTrimesh)

#else

#ifndef LMP_PAIR_TRIMESH_H
#define LMP_PAIR_TRIMESH_H

#include <cstddef>
#include <memory>
#include <vector>

#include "contact/MeshContact.h"
#include "dynamics/RigidBody.h"
#include "pair.h"

namespace LAMMPS_NS {

struct PairTrimeshModel;
struct TrimeshCandidatePair;
struct TrimeshWallContact;

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
  // Largest stable time step of one contact point of type pair (itype, jtype), as init_style
  // prints it (+inf for pairs with a sphere or wall type, or before init).
  double stable_step(int itype, int jtype) const;
  class FixTrimeshTemplate *trimesh_template() const { return templ; }

 private:
  void allocate();
  void setup_history();
  // The contacts of body pair (a, b) (b < 0: a wall; wall: its contacts) by the law of their
  // type pair, with history; pair_trimesh.cpp.
  void add_pair_forces(int a, const spacetree::dynamics::RigidBody &ba, int b,
                       const spacetree::dynamics::RigidBody &bb, int wall_type,
                       const std::vector<spacetree::contact::ContactPoint> &contacts,
                       double match_distance, double dt, Eigen::Vector3d *force_on_a,
                       const TrimeshWallContact *wall = NULL);

  std::unique_ptr<PairTrimeshModel> model;
  class FixTrimeshTemplate *templ;
  class NeighList *list;
  double stat_max_penetration;
};

}

#endif
#endif
