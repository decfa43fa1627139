/* spacetree-dem: shape templates of triangulated rigid particles, one per atom type
   (paper §3; core: src/core/geometry MeshIO, RigidShape, DentedSphere).

     fix ID group trimesh/template type T SOURCE [density RHO] [fixed] [type T2 SOURCE ...]
                                   [orientation file|identity|random SEED]
       SOURCE = file PATH [scale S]                      (STL ascii/binary or OBJ)
              | dented ntri N radius R amplitude A seed S

   On setup every owned atom of a template type gets radius = bounding radius + eps (eps of
   pair_style trimesh), rmass = RHO * volume and, if not yet set, an orientation. Grains are
   kept in their principal body frame (atom position = centre of mass); a `fixed` type is an
   obstacle of infinite mass whose mesh stays in file coordinates (atom position = file origin).
   Atoms inserted during a run (fix insert/pack, insert/stream, ...; particle template
   particletemplate/trimesh) get their template before the next neighbour list build
   (pre_neighbor, ghosts refreshed too).
   Per-atom orientation and angular momentum live in the fix trimesh/state "<ID>_state". */

#ifdef FIX_CLASS

FixStyle(trimesh/template,FixTrimeshTemplate)

#else

#ifndef LMP_FIX_TRIMESH_TEMPLATE_H
#define LMP_FIX_TRIMESH_TEMPLATE_H

#include <memory>
#include <vector>

#include "fix.h"
#include "trimesh_type_template.h"

namespace LAMMPS_NS {

class FixTrimeshTemplate : public Fix {
 public:
  FixTrimeshTemplate(class LAMMPS *, int, char **);
  ~FixTrimeshTemplate();
  void post_create();
  int setmask();
  void init();
  void setup_pre_exchange();
  void pre_neighbor();

  // radius used for neighbour search and ghost cut-offs: bounding radius + halo
  double max_rad(int type);
  double min_rad(int type);
  // "obstacle_types": int per atom type (index 1..ntypes), 1 for fixed obstacles (neighbor
  // spacetree lets them be larger than the box)
  void *extract(const char *name, int &dim);

  // The deck's fix trimesh/template, NULL if there is none; more than one is an error that
  // names `who` (the command looking for it).
  static FixTrimeshTemplate *find(class LAMMPS *lmp, const char *who);

  // Template of atom type t (1..ntypes), NULL where none was given.
  const TrimeshTypeTemplate *type_template(int t) const;
  // The halo eps of pair_style trimesh, added to every bounding radius.
  void set_halo(double eps);
  double halo() const { return halo_; }
  class FixTrimeshState *state() const { return state_; }

  // Owned atoms of template types whose orientation is unset (new atoms), summed over ranks.
  bigint count_new_atoms() const;
  // Sets radius and rmass of owned atoms of template types and, with initialise_poses, the
  // orientation of those whose orientation is still unset (obstacles: file placement too).
  void apply_to_atoms(bool initialise_poses);

 private:
  // Insertion templates for template types (particletemplate/sphere, .../trimesh): the
  // inserted sphere must cover the grain; errors and warnings name the fix.
  void check_insertion_templates();

  std::vector<std::unique_ptr<TrimeshTypeTemplate>> templates_;   // index = type
  std::vector<int> obstacle_types_;                                // index = type
  class FixTrimeshState *state_;
  double halo_;
  enum Orientation { OrientFile, OrientIdentity, OrientRandom } orientation_;
  int orientation_seed_;
};

}

#endif
#endif
