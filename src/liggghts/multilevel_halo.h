/* spacetree-dem: the per-size ghost rule of `neighbor <skin> spacetree` (keyword `halo`).

   LIGGGHTS sends every atom to its neighbouring subdomains and periodic images out to
   r_i + r_max + skin (Comm::decide with use_gran_opt), so a wide size distribution gives every
   small atom a ghost shell as thick as the largest particle. With `halo levels` (default) the
   atoms are exchanged by size class, coarse first (Comm::halo_borders, patch 0006): a small
   atom reaches its own class's partners ((r + R_class) f + skin) plus the owner of every bigger
   ghost it can touch; fixed obstacles (fix trimesh/template ... fixed) are touched by their
   surface. The rule is the LIGGGHTS-free core parallel/HaloReach; this class feeds it the
   atoms, classes and obstacle surfaces of one borders() call and keeps the counts that
   compute halo reports.

   Applies with newton off (the spacetree lists need it); falls back to the stock shell, with a
   warning that says why, for a wedge domain and for fixes that extend the ghost cut-off
   (multisphere bodies). A `comm_modify cutoff` and the overlap checks of insertion fixes
   become a floor of every atom's reach. */

#ifndef LMP_MULTILEVEL_HALO_H
#define LMP_MULTILEVEL_HALO_H

#include <memory>
#include <vector>

#include "parallel/HaloReach.h"
#include "parallel/HaloSizeClasses.h"
#include "parallel/HaloSurface.h"
#include "pointers.h"

namespace LAMMPS_NS {

class MultilevelHalo : protected Pointers {
 public:
  explicit MultilevelHalo(class LAMMPS *);
  ~MultilevelHalo();

  // `neighbor ... spacetree halo levels|single halo_ratio Q`: true if `key` is one of these
  // (its value consumed), false for other keywords; errors name a bad value.
  bool set_keyword(const char *key, const char *value);
  void reset_settings();
  bool levels() const { return levels_; }
  double ratio() const { return ratio_; }

  // At each Neighbor::init of neighbor spacetree: this, or NULL (stock shell) with a warning
  // naming why the rule does not apply to this run.
  MultilevelHalo *install();

  // ---- one borders() call (Comm::halo_borders) -------------------------------------------
  // Collective: global size classes, subdomain grid, rule; forgets the previous partners.
  void begin();
  int passes() const { return int(pass_class_.size()); }
  int pass_class(int p) const { return pass_class_[p]; }
  // Owned atoms [0, nowned) of class c, ascending; their reaches (same order). keep false:
  // the class's counts only, nothing listed (a rank that sends nothing).
  const std::vector<int> &owned_of_class(int c, int nowned, bool keep = true);
  const std::vector<double> &owned_reach() const { return owned_reach_; }
  // Ghosts [first, last) arrived in the pass of class c: partners of the finer classes.
  void add_partners(int first, int last, int c);
  // Counts of the pass of class c (this rank): sent copies and received ghosts.
  void count_pass(int c, int nsent, int nrecv);
  // Scratch of Comm::halo_borders: the reach of each atom in the current pass (-1: not sent).
  std::vector<double> &pass_reach() { return pass_reach_; }

  // ---- what compute halo reports ------------------------------------------------------------
  const spacetree::parallel::HaloSizeClasses &classes() const { return classes_; }
  double class_largest(int c) const { return class_largest_[c]; }
  int class_of_radius(double r) const { return classes_.classOf(r); }
  double radius_of(int i) const;           // radius the rule uses for atom i (owned or ghost)
  struct ClassCounts {
    long served = 0;                       // owned atoms that reach farther to serve a bigger one
    double largest_reach = 0.0;            // largest reach of an owned atom of the class
    long sent = 0, received = 0;           // copies sent / ghosts received in the class's pass
  };
  const std::vector<ClassCounts> &counts() const { return counts_; }

 private:
  double effective_radius(int type, double radius) const;
  const spacetree::parallel::HaloSurface *surface_of(int i);
  double shell_floor() const;

  bool levels_ = true;
  double ratio_ = 4.0;
  double largest_guess_ = -1.0;            // global largest radius of the last borders()

  spacetree::parallel::HaloSizeClasses classes_;
  std::vector<double> class_largest_;      // global largest radius per class (-1: empty)
  std::vector<int> pass_class_;
  spacetree::parallel::HaloReach reach_;
  std::vector<int> owned_;
  std::vector<double> owned_reach_;
  std::vector<ClassCounts> counts_;
  std::vector<double> pass_reach_;

  // triangulated types (fix trimesh/template): their radius is the template's, also for atoms
  // inserted since the last list build; obstacles have a surface
  class FixTrimeshTemplate *templ_ = nullptr;
  std::vector<double> type_radius_;        // index = type; 0: the atom's own radius
  std::vector<std::unique_ptr<spacetree::parallel::PosedShapeSurface>> surfaces_;
};

}  // namespace LAMMPS_NS

#endif
