/* spacetree-dem: triangulated grains against fix wall/gran walls (thin layer over the core's
   MeshContactFinder and WallPatches). */

#include "trimesh_wall_contacts.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <exception>
#include <map>
#include <string>

#include "atom.h"
#include "error.h"
#include "fix_mesh_surface.h"
#include "fix_trimesh_state.h"
#include "fix_trimesh_template.h"
#include "fix_wall_gran.h"
#include "contact/CylinderWallContact.h"
#include "geometry/RigidMotionFit.h"
#include "geometry/WallPatches.h"
#include "modify.h"
#include "neighbor.h"
#include "primitive_wall.h"
#include "tri_mesh.h"

using namespace LAMMPS_NS;
namespace ct = spacetree::contact;
namespace geo = spacetree::geometry;
namespace PWD = PRIMITIVE_WALL_DEFINITIONS;

struct TrimeshWallContacts::MeshWall {
  FixMeshSurface *fix = NULL;
  int key = 0;                // history partner key of its contacts (< 0)
  geo::RigidShape shape;
  ct::Pose pose;              // body frame of the shape -> world (a translation)
  std::vector<int> ids;       // mesh->id() of the triangles the shape was built from, in order
  std::vector<Eigen::Vector3d> reference, nodes;  // nodes (3 per triangle) at the build, now
  geo::RigidMotionFit fit;    // of a moving mesh: reference -> nodes
  bool built = false;
  bool stress = false;        // the mesh tracks forces (fix mesh/surface/stress)
};

struct TrimeshWallContacts::Wall {
  FixWallGran *fix = NULL;
  int key = 0;             // history partner key of a primitive wall's contacts (< 0)
  // primitive: its patch, plane (point, normal) or cylinder (point, axis, radius)
  bool primitive = false, cylinder = false;
  geo::RigidShape patch;   // plane; cylinder: its outer side (inside: exact, by the vertices)
  Eigen::Vector3d point = Eigen::Vector3d::Zero(), direction = Eigen::Vector3d::UnitZ();
  double radius = 0.0;
  Eigen::Vector3d shear_velocity = Eigen::Vector3d::Zero();  // plane: translation
  Eigen::Vector3d shear_omega = Eigen::Vector3d::Zero();     // cylinder: rotation about its axis
  std::vector<MeshWall> meshes;
};

TrimeshWallContacts::TrimeshWallContacts(LAMMPS *lmp) : Pointers(lmp), templ_(NULL), eps_(0.0) {}

TrimeshWallContacts::~TrimeshWallContacts()
{
  // the walls compute every atom again if they outlive the pair style
  for (auto &w : walls_)
    if (modify->find_fix(w->fix->id) >= 0) w->fix->exclude_types(NULL);
}

void TrimeshWallContacts::init(FixTrimeshTemplate *templ, const ct::MeshContactOptions &options)
{
  templ_ = templ;
  eps_ = options.epsilon;
  finder_.reset(new ct::MeshContactFinder(options));
  cylinder_.reset(new ct::CylinderWallContactFinder(options));
  for (auto &w : walls_)
    if (modify->find_fix(w->fix->id) >= 0) w->fix->exclude_types(NULL);
  walls_.clear();

  const int ntypes = atom->ntypes;
  excluded_.assign(ntypes+1,0);
  double grain_reach = 0.0;   // largest bounding radius + 2 eps of a grain
  for (int t = 1; t <= ntypes; t++) {
    const TrimeshTypeTemplate *tt = templ->type_template(t);
    if (!tt) continue;
    excluded_[t] = 1;
    if (!tt->fixed) grain_reach = std::max(grain_reach,tt->boundingRadius + 2.0*eps_);
  }

  int next_key = -1;
  for (int i = 0; i < modify->nfix; i++) {
    if (strcmp(modify->fix[i]->style,"wall/gran") != 0) continue;
    FixWallGran *fwg = static_cast<FixWallGran *>(modify->fix[i]);
    std::unique_ptr<Wall> w(new Wall);
    w->fix = fwg;
    fwg->exclude_types(excluded_.data());
    int shear_dim = -1;
    double vshear = 0.0;
    const bool shear = fwg->primitive_shear(shear_dim,vshear);
    // history partner keys: negative (atom tags are positive), one per primitive wall or mesh
    w->key = next_key--;
    if (fwg->is_mesh_wall()) {
      for (int k = 0; k < fwg->n_meshes(); k++) {
        MeshWall m;
        m.key = next_key--;
        m.fix = fwg->mesh_list()[k];
        m.stress = m.fix->trackStress();
        w->meshes.push_back(m);
      }
    } else if (PrimitiveWall *pw = fwg->primitiveWall()) {
      w->primitive = true;
      const PWD::WallType type = pw->type();
      // plane normal / cylinder axis (PrimitiveWall::axis() is -1 for planes)
      const int axis = type == PWD::XPLANE || type == PWD::XCYLINDER ? 0 :
                       type == PWD::YPLANE || type == PWD::YCYLINDER ? 1 : 2;
      w->direction = Eigen::Vector3d::Unit(axis);
      if (type == PWD::XPLANE || type == PWD::YPLANE || type == PWD::ZPLANE) {
        w->point = pw->parameter(0) * w->direction;
        if (grain_reach > 0.0) w->patch = geo::RigidShape::fromSurface(geo::planeWallPatch(2.0*grain_reach));
        if (shear) w->shear_velocity = vshear * Eigen::Vector3d::Unit(shear_dim);
      } else if (type == PWD::XCYLINDER || type == PWD::YCYLINDER || type == PWD::ZCYLINDER) {
        w->cylinder = true;
        w->radius = pw->parameter(0);
        w->point = Eigen::Vector3d::Zero();
        w->point[(axis+1)%3] = pw->parameter(1);
        w->point[(axis+2)%3] = pw->parameter(2);
        if (grain_reach > 0.0) {
          // azimuths within reach of a grain on either side, chords within 1e-3 eps
          const double r = w->radius, reach = 2.0*grain_reach;
          const double half_angle = reach >= r ? M_PI : std::asin(reach / r) * 1.5;
          const double sagitta = std::min(1e-3 * eps_,0.5 * r);
          try {
            w->patch = geo::RigidShape::fromSurface(
                geo::cylinderWallPatch(r,std::max(half_angle,1e-9),reach,sagitta));
          } catch (const std::exception &e) {
            error->all(FLERR,(std::string("Pair style trimesh: fix wall/gran ") + fwg->id + ": " + e.what()).c_str());
          }
        }
        if (shear) {
          if (shear_dim == axis) w->shear_velocity = vshear * w->direction;
          else w->shear_omega = vshear * w->direction;
        }
      } else {
        std::string msg = std::string("Pair style trimesh: fix wall/gran ") + fwg->id +
                          ": this primitive wall is not supported with triangulated grains";
        error->all(FLERR,msg.c_str());
      }
    } else continue;
    walls_.push_back(std::move(w));
  }
}

void TrimeshWallContacts::find(std::vector<TrimeshWallContact> &out, ct::MeshContactStatistics &stats)
{
  out.clear();
  for (auto &w : walls_) {
    if (w->primitive) find_primitive(*w,out,stats);
    else for (MeshWall &m : w->meshes) find_mesh(*w,m,out,stats);
  }
}

namespace {

ct::Pose grain_pose(double *x, double *q)
{
  ct::Pose p;
  p.position = Eigen::Vector3d(x[0],x[1],x[2]);
  p.orientation = Eigen::Quaterniond(q[0],q[1],q[2],q[3]);
  return p;
}

}

template <class F>
void TrimeshWallContacts::for_each_grain(const Wall &w, F &&f)
{
  double **x = atom->x, **quat = templ_->state()->quat;
  int *mask = atom->mask, *type = atom->type;
  for (int i = 0; i < atom->nlocal; i++) {
    if (!(mask[i] & w.fix->groupbit)) continue;
    const TrimeshTypeTemplate *tt = templ_->type_template(type[i]);
    if (!tt || tt->fixed) continue;
    f(i,*tt,grain_pose(x[i],quat[i]));
  }
}

void TrimeshWallContacts::find_primitive(Wall &w, std::vector<TrimeshWallContact> &out,
                                         ct::MeshContactStatistics &stats)
{
  double *radius = atom->radius;
  for_each_grain(w,[&](int i, const TrimeshTypeTemplate &grain, const ct::Pose &pose) {
    const TrimeshTypeTemplate *tt = &grain;
    const Eigen::Vector3d &c = pose.position;
    // the bounding sphere (radius = R + eps) within eps of the wall
    geo::WallPatchPlacement place;
    scratch_.clear();
    if (w.cylinder) {
      place = geo::WallPatchPlacement::onCylinder(w.point,w.direction,c);
      const double rho = (c - place.position).norm();
      if (!(std::abs(rho - w.radius) < radius[i] + eps_)) return;
      if (rho < w.radius) {   // inside: exact, by the grain's vertices
        cylinder_->find(tt->shape,pose,w.point,w.direction,w.radius,scratch_,&stats);
      } else {                // outside: the patch of the cylinder's outer side
        const ct::Pose wall_pose{place.position + place.orientation * w.patch.centreOfMassInMesh,
                                 place.orientation};
        finder_->find(tt->shape,pose,w.patch,wall_pose,scratch_,&stats);
      }
    } else {
      if (!(std::abs((c - w.point).dot(w.direction)) < radius[i] + eps_)) return;
      place = geo::WallPatchPlacement::onPlane(w.point,w.direction,c);
      // the patch's body frame sits at its mesh's box centre
      const ct::Pose wall_pose{place.position + place.orientation * w.patch.centreOfMassInMesh,
                               place.orientation};
      finder_->find(tt->shape,pose,w.patch,wall_pose,scratch_,&stats);
    }
    for (const ct::ContactPoint &cp : scratch_) {
      TrimeshWallContact wc;
      wc.atom = i;
      wc.contact = cp;
      wc.wall_velocity = w.shear_velocity;
      if (w.cylinder) {
        const Eigen::Vector3d foot = w.point + (cp.point - w.point).dot(w.direction) * w.direction;
        wc.wall_velocity += w.shear_omega.cross(cp.point - foot);
      }
      wc.mesh = NULL;
      wc.mesh_triangle = -1;
      wc.wall_type = w.fix->atom_type_wall();
      wc.wall_key = w.key;
      out.push_back(wc);
    }
  });
}

void TrimeshWallContacts::refresh_mesh_shape(MeshWall &m)
{
  TriMesh *mesh = m.fix->triMesh();
  const int n = mesh->sizeLocal() + mesh->sizeGhost();
  const bool moving = mesh->isMoving() || mesh->isDeforming();
  if (m.built && !moving && neighbor->ago != 0 && (int) m.ids.size() == n) return;
  std::vector<int> ids(n);
  for (int k = 0; k < n; k++) ids[k] = mesh->id(k);
  const bool same = m.built && ids == m.ids;
  if (same && !moving) return;
  // the nodes now, three per triangle
  m.nodes.resize(3*size_t(n));
  for (int k = 0; k < n; k++)
    for (int j = 0; j < 3; j++) {
      double node[3];
      mesh->node(k,j,node);
      m.nodes[3*size_t(k)+j] = Eigen::Vector3d(node[0],node[1],node[2]);
    }
  if (same) {
    // a moving mesh: its rigid motion since the build moves the shape (fix move/mesh's motions
    // are rigid); anything else (deformation) rebuilds it
    Eigen::Matrix3d r;
    Eigen::Vector3d t;
    const double tolerance = 1e-12 * (m.shape.boundingRadius + m.shape.centreOfMassInMesh.norm());
    if (m.fit.fit(m.reference,m.nodes,tolerance,r,t)) {
      m.pose.orientation = Eigen::Quaterniond(r);
      m.pose.position = r * m.shape.centreOfMassInMesh + t;
      return;
    }
  }
  m.ids.swap(ids);
  m.built = true;
  m.reference = m.nodes;
  m.fit = geo::RigidMotionFit(m.reference);
  if (n == 0) { m.shape = geo::RigidShape(); return; }
  // shared vertices by their coordinates (a mesh's nodes are copies per triangle)
  geo::TriangleMesh surface;
  std::map<std::array<double,3>,int> index;
  for (int k = 0; k < n; k++) {
    std::array<int,3> f;
    for (int j = 0; j < 3; j++) {
      const Eigen::Vector3d &node = m.reference[3*size_t(k)+j];
      const std::array<double,3> key = {node[0],node[1],node[2]};
      auto it = index.find(key);
      if (it == index.end()) {
        it = index.emplace(key,(int) surface.vertices.size()).first;
        surface.vertices.push_back(node);
      }
      f[j] = it->second;
    }
    surface.triangles.push_back(f);
  }
  m.shape = geo::RigidShape::fromSurface(surface);
  m.pose.position = m.shape.centreOfMassInMesh;
  m.pose.orientation = Eigen::Quaterniond::Identity();
}

void TrimeshWallContacts::find_mesh(Wall &w, MeshWall &m, std::vector<TrimeshWallContact> &out,
                                    ct::MeshContactStatistics &stats)
{
  refresh_mesh_shape(m);
  if (m.shape.triangleCount() == 0) return;
  TriMesh *mesh = m.fix->triMesh();
  MultiVectorContainer<double,3,3> *vnodes =
      mesh->prop().getElementProperty<MultiVectorContainer<double,3,3> >("v");
  double ***vmesh = vnodes ? vnodes->begin() : NULL;
  for_each_grain(w,[&](int i, const TrimeshTypeTemplate &grain, const ct::Pose &pose) {
    scratch_.clear();
    finder_->find(grain.shape,pose,m.shape,m.pose,scratch_,&stats);
    for (const ct::ContactPoint &cp : scratch_) {
      TrimeshWallContact wc;
      wc.atom = i;
      wc.contact = cp;
      wc.wall_velocity = Eigen::Vector3d::Zero();
      wc.mesh = m.stress ? m.fix : NULL;
      wc.mesh_triangle = cp.secondTriangle;
      wc.wall_type = m.fix->atomTypeWall();
      wc.wall_key = m.key;
      if (vmesh) {
        // node velocities at the contact point's barycentric coordinates in its wall triangle
        // (exact for the affine velocity field of a rigid motion, also outside the triangle)
        const int t = cp.secondTriangle;
        double a[3], b[3], c[3];
        mesh->node(t,0,a); mesh->node(t,1,b); mesh->node(t,2,c);
        const Eigen::Vector3d A(a[0],a[1],a[2]), B(b[0],b[1],b[2]), C(c[0],c[1],c[2]);
        const Eigen::Vector3d e1 = B - A, e2 = C - A, p = cp.point - A;
        const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
        const double det = d11*d22 - d12*d12;
        double l1 = 0.0, l2 = 0.0;
        if (det > 0.0) {
          l1 = (d22*p.dot(e1) - d12*p.dot(e2)) / det;
          l2 = (d11*p.dot(e2) - d12*p.dot(e1)) / det;
        }
        const double l0 = 1.0 - l1 - l2;
        for (int k = 0; k < 3; k++)
          wc.wall_velocity[k] = l0*vmesh[t][0][k] + l1*vmesh[t][1][k] + l2*vmesh[t][2][k];
      }
      out.push_back(wc);
    }
  });
}

void TrimeshWallContacts::report_to_mesh(const TrimeshWallContact &c, const Eigen::Vector3d &force_on_grain)
{
  if (!c.mesh || c.mesh_triangle < 0) return;
  double frc[3] = {force_on_grain[0],force_on_grain[1],force_on_grain[2]};
  double *x = atom->x[c.atom];
  double delta[3] = {c.contact.point[0]-x[0],c.contact.point[1]-x[1],c.contact.point[2]-x[2]};
  double vwall[3] = {c.wall_velocity[0],c.wall_velocity[1],c.wall_velocity[2]};
  c.mesh->add_particle_contribution(c.atom,frc,delta,c.mesh_triangle,vwall);
}
