/* spacetree-dem: the pairs of triangulated particles (pair_style trimesh) as fix adapt/timestep
   sees them: by the distance the pair style measures between their surfaces, not by their
   bounding spheres (which overlap long before concave or elongated grains touch, and between a
   grain and a large obstacle always).

   A pair in contact (the pair style's last compute found contact points: surfaces closer than
   2 eps, eps the halo) is judged at each contact point: its halo penetration eps - d/2 (the
   deepest one is the overlap of the rollback and f_ID[7,8]), the closing speed of the two
   material points there (rotation included) for the veto, which keeps the extrapolated
   penetration within the allowed one P, and the contact speed (vimpact).
   A pair without contact is at least 2 eps apart (the search certifies it) and within the tested
   step dt its surfaces close by at most w dt, w the closing-speed bound |v_j - v_i| + |w_i| R_i +
   |w_j| R_j (core SurfaceGapProbe.h). Only when that much closing could make the pair critical or
   about to touch (the contact ceiling) is its true gap measured, within the band
   2 eps + w dt / safety (SurfaceGapProbe), and then judged like a contact point. So no pair
   that can reach the allowed penetration within the step escapes the veto, and the probes are
   few: a grain pair at rest or a bed below dtcontact needs none. */

#ifndef LMP_TIMESTEP_TRIMESH_SCAN_H
#define LMP_TIMESTEP_TRIMESH_SCAN_H

#include <cstdint>
#include <limits>
#include <memory>
#include <unordered_set>

#include "contact/SurfaceGapProbe.h"
#include "dynamics/TimestepVeto.h"
#include "pointers.h"

namespace LAMMPS_NS {

class TimestepTrimeshScan : protected Pointers {
 public:
  struct Settings {
    int groupbit = 0;
    double dtTest = 0.0;              // the step tested (the largest creep can give)
    double allowedPenetration = 0.0;  // P: the veto keeps eps - d/2 within it
    double safety = 1.0;
    bool ceiling = false;             // dtcontact: pairs about to touch count as contacts
    bool stable = false;              // stability ceiling: the stable steps of those pairs' types
    bool speeds = false;              // vimpact: contact speeds
    double contactTime = 0.0;         // tcontact (speeds)
    const double *accel = nullptr;    // f/m of owned and ghost atoms, 3 per atom (speeds)
  };
  // This rank's part (own/ghost pairs count half, as in TimestepPairScan).
  struct Tally {
    double maxPenetration = 0.0;
    double contacts = 0.0;       // body pairs in contact
    double critical = 0.0;       // pairs the veto cut the step for
    bool soon = false;           // a pair without contact may touch within dtTest
    double speed = 0.0;          // largest contact speed (or approach speed of a pair about to touch)
    // (stable) smallest largest-stable-step of the type pairs in contact or about to touch
    double stable = std::numeric_limits<double>::infinity();
  };

  TimestepTrimeshScan(class LAMMPS *lmp, class PairTrimesh *pair);

  // list: the fix's copy of the granular list (rebuilt here). Collective (the contact count).
  Tally scan(class NeighList *list, const Settings &s, spacetree::TimestepVeto *veto);

  double halo() const { return halo_; }
  // gap probes so far (all ranks)
  double probes() const;

 private:
  void scan_contacts(const Settings &s, spacetree::TimestepVeto *veto, Tally &t);
  void scan_near_pairs(class NeighList *list, const Settings &s, bool any_contact,
                       spacetree::TimestepVeto *veto, Tally &t);
  // (v_b + w_b x (p - x_b)) - (v_a + w_a x (p - x_a)) along n: < 0 while the points approach
  double normal_velocity(int a, int b, const double *point, const double *normal) const;
  // atom i's velocity and angular velocity enter the closing speed (template types: grains and
  // obstacles, static or moved by fix move/trimesh, as the contact law sees them)
  bool moving(int i) const;

  class PairTrimesh *pair_;
  class FixTrimeshTemplate *templ_;
  double halo_;
  std::unique_ptr<spacetree::contact::SurfaceGapProbe> probe_;
  std::unordered_set<std::uint64_t> in_contact_;   // local index pairs with contact points
};

}

#endif
