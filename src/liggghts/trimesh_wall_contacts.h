/* spacetree-dem: triangulated grains against the walls of fix wall/gran, by their surfaces
   (pair_style trimesh calls it each step; the contacts go through its contact law).

   - Primitive walls (xplane/yplane/zplane, x/y/zcylinder), for each grain whose bounding sphere
     comes within 2 eps of the wall: a plane as a triangulated square placed under the grain
     (core geometry/WallPatches); a grain inside a cylinder by its vertices (core
     CylinderWallContact: exact), outside by a piece of the cylinder whose chords stay within
     1e-3 eps of it (slower: many narrow facets); `shear dim v` moves the wall's surface (a plane
     along dim, a cylinder about its axis when dim is not the axis), as fix wall/gran does for
     spheres.
   - Mesh walls (fix mesh/surface ... + fix wall/gran mesh): the triangles this rank holds of
     each mesh (owned and ghost) as one core surface shape, rebuilt when the set changes; a mesh
     that fix move/mesh moves is followed by the rigid motion of its nodes since the build (core
     RigidMotionFit, O(nodes) per step), rebuilt where the nodes moved otherwise; the wall's
     velocity at a contact is the mesh's node velocity interpolated at the contact point.
     Forces on a mesh that tracks them (fix mesh/surface/stress) are added to it, as for
     spheres.
   The grain is the first body of each contact (normal from the grain towards the wall); the
   wall's halo is eps like any body's, so a grain rests on a wall where it rests on an obstacle
   of the same surface. fix wall/gran itself skips the template types (hook: FixWallGran::
   exclude_types, liggghts_patch/0004). */

#ifndef LMP_TRIMESH_WALL_CONTACTS_H
#define LMP_TRIMESH_WALL_CONTACTS_H

#include <memory>
#include <vector>

#include <Eigen/Core>

#include "contact/CylinderWallContact.h"
#include "contact/MeshContact.h"
#include "geometry/RigidShape.h"
#include "pointers.h"

namespace LAMMPS_NS {

class FixTrimeshTemplate;

// One grain-wall contact: the grain (owned atom), the contact (grain first), the wall's
// velocity at the contact point, and where to report the force on a mesh (NULL: nowhere).
struct TrimeshWallContact {
  int atom;
  spacetree::contact::ContactPoint contact;
  Eigen::Vector3d wall_velocity;
  class FixMeshSurface *mesh;
  int mesh_triangle;
  int wall_type;
  int wall_key;   // < 0, one per wall (primitive) or mesh of a wall: the grain's history partner
};

class TrimeshWallContacts : protected Pointers {
 public:
  explicit TrimeshWallContacts(class LAMMPS *);
  ~TrimeshWallContacts();

  // At the pair style's init: the fix wall/gran instances, told to skip the template types;
  // patches of primitive walls sized for the largest grain. options: those of the pair style.
  void init(FixTrimeshTemplate *templ, const spacetree::contact::MeshContactOptions &options);
  bool empty() const { return walls_.empty(); }

  // The contacts of every owned grain with every wall (in wall order, then atom order);
  // statistics accumulated.
  void find(std::vector<TrimeshWallContact> &out, spacetree::contact::MeshContactStatistics &stats);

  // The force on the grain of contact c (world frame), to the mesh (if it tracks forces).
  void report_to_mesh(const TrimeshWallContact &c, const Eigen::Vector3d &force_on_grain);

 private:
  struct Wall;
  struct MeshWall;
  void find_primitive(Wall &w, std::vector<TrimeshWallContact> &out,
                      spacetree::contact::MeshContactStatistics &stats);
  void find_mesh(Wall &w, MeshWall &m, std::vector<TrimeshWallContact> &out,
                 spacetree::contact::MeshContactStatistics &stats);
  void refresh_mesh_shape(MeshWall &m);
  // f(i, template, pose) for every owned grain (template type, not an obstacle) of w's group
  template <class F> void for_each_grain(const Wall &w, F &&f);

  FixTrimeshTemplate *templ_;
  std::vector<int> excluded_;   // per type: 1 for template types (the hook's flags)
  std::vector<std::unique_ptr<Wall>> walls_;
  std::unique_ptr<spacetree::contact::MeshContactFinder> finder_;
  std::unique_ptr<spacetree::contact::CylinderWallContactFinder> cylinder_;
  double eps_;
  std::vector<spacetree::contact::ContactPoint> scratch_;
};

}

#endif
