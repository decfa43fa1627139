/* spacetree-dem: per-type shape templates of triangulated rigid particles. */

#include "fix_trimesh_template.h"

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstring>
#include <random>
#include <exception>
#include <string>

#include <mpi.h>

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_template_sphere.h"
#include "fix_template_trimesh.h"
#include "fix_trimesh_state.h"
#include "force.h"
#include "geometry/SphereMesh.h"
#include "modify.h"

using namespace LAMMPS_NS;

namespace {

[[noreturn]] void bad(Error *error, const char *fmt, const char *what)
{
  char msg[1024];
  snprintf(msg,sizeof(msg),fmt,what);
  error->all(FLERR,msg);
  throw std::logic_error(msg);   // not reached: error->all does not return
}

}

FixTrimeshTemplate::FixTrimeshTemplate(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), state_(NULL), halo_(0.0), orientation_(OrientFile),
  orientation_seed_(0)
{
  if (!atom->sphere_flag)
    error->all(FLERR,"Fix trimesh/template requires atom_style sphere or granular "
                     "(radius, rmass, omega, torque per atom)");
  templates_.resize(atom->ntypes+1);

  int iarg = 3;
  if (iarg >= narg) error->all(FLERR,"Illegal fix trimesh/template command: expected 'type T ...'");
  while (iarg < narg) {
    if (strcmp(arg[iarg],"orientation") == 0) {
      if (iarg+2 > narg) error->all(FLERR,"Illegal fix trimesh/template command: orientation needs file, identity or random SEED");
      if (strcmp(arg[iarg+1],"file") == 0) { orientation_ = OrientFile; iarg += 2; }
      else if (strcmp(arg[iarg+1],"identity") == 0) { orientation_ = OrientIdentity; iarg += 2; }
      else if (strcmp(arg[iarg+1],"random") == 0) {
        if (iarg+3 > narg) error->all(FLERR,"Illegal fix trimesh/template command: orientation random needs a seed");
        orientation_ = OrientRandom;
        orientation_seed_ = force->inumeric(FLERR,arg[iarg+2]);
        if (orientation_seed_ <= 0) error->all(FLERR,"Illegal fix trimesh/template command: orientation seed must be > 0");
        iarg += 3;
      } else bad(error,"Illegal fix trimesh/template command: orientation '%s' (file, identity or random)",arg[iarg+1]);
      continue;
    }
    if (strcmp(arg[iarg],"type") != 0)
      bad(error,"Illegal fix trimesh/template command: unknown keyword '%s' (expected type, orientation)",arg[iarg]);
    if (iarg+3 > narg) error->all(FLERR,"Illegal fix trimesh/template command: 'type T' needs a source (file or dented)");
    const int t = force->inumeric(FLERR,arg[iarg+1]);
    if (t < 1 || t > atom->ntypes) bad(error,"Illegal fix trimesh/template command: atom type %s out of range",arg[iarg+1]);
    if (templates_[t]) bad(error,"Illegal fix trimesh/template command: type %s given twice",arg[iarg+1]);
    iarg += 2;

    TrimeshTypeSource src;
    if (strcmp(arg[iarg],"file") == 0) {
      if (iarg+2 > narg) error->all(FLERR,"Illegal fix trimesh/template command: file needs a path");
      src.kind = TrimeshTypeSource::File;
      src.path = arg[iarg+1];
      iarg += 2;
    } else if (strcmp(arg[iarg],"dented") == 0) {
      src.kind = TrimeshTypeSource::Dented;
      iarg++;
    } else bad(error,"Illegal fix trimesh/template command: unknown shape source '%s' (file or dented)",arg[iarg]);

    // per-type keywords until the next 'type' / 'orientation'
    while (iarg < narg && strcmp(arg[iarg],"type") != 0 && strcmp(arg[iarg],"orientation") != 0) {
      const char *kw = arg[iarg];
      if (strcmp(kw,"fixed") == 0) { src.fixed = true; iarg++; continue; }
      if (iarg+2 > narg) bad(error,"Illegal fix trimesh/template command: keyword '%s' needs a value",kw);
      const char *val = arg[iarg+1];
      if (strcmp(kw,"density") == 0) src.density = force->numeric(FLERR,val);
      else if (strcmp(kw,"scale") == 0 && src.kind == TrimeshTypeSource::File) src.scale = force->numeric(FLERR,val);
      else if (strcmp(kw,"ntri") == 0 && src.kind == TrimeshTypeSource::Dented) src.ntri = force->inumeric(FLERR,val);
      else if (strcmp(kw,"radius") == 0 && src.kind == TrimeshTypeSource::Dented) src.radius = force->numeric(FLERR,val);
      else if (strcmp(kw,"amplitude") == 0 && src.kind == TrimeshTypeSource::Dented) src.amplitude = force->numeric(FLERR,val);
      else if (strcmp(kw,"seed") == 0 && src.kind == TrimeshTypeSource::Dented) src.seed = force->inumeric(FLERR,val);
      else bad(error,"Illegal fix trimesh/template command: unknown keyword '%s' for this shape source",kw);
      iarg += 2;
    }
    if (!(src.density > 0.0)) error->all(FLERR,"Illegal fix trimesh/template command: density must be > 0");
    if (!(src.scale > 0.0)) error->all(FLERR,"Illegal fix trimesh/template command: scale must be > 0");
    if (src.kind == TrimeshTypeSource::Dented) {
      if (src.ntri < 12 || src.ntri > spacetree::geometry::kMaxSphereMeshTriangles)
        bad(error,"Illegal fix trimesh/template command: dented needs ntri >= 12 and <= %s",
            std::to_string(spacetree::geometry::kMaxSphereMeshTriangles).c_str());
      if (!(src.radius > 0.0)) error->all(FLERR,"Illegal fix trimesh/template command: dented needs radius > 0");
      if (!(src.amplitude >= 0.0 && src.amplitude < 1.0))
        error->all(FLERR,"Illegal fix trimesh/template command: dented amplitude must be in [0,1)");
      if (src.seed <= 0) error->all(FLERR,"Illegal fix trimesh/template command: dented needs seed > 0");
    }

    std::string why;
    templates_[t] = TrimeshTypeTemplate::build(src,why);
    if (!templates_[t]) {
      std::string msg = "Fix trimesh/template: type " + std::to_string(t) + ": " + why;
      error->all(FLERR,msg.c_str());
    }
  }

  bool any = false;
  obstacle_types_.assign(atom->ntypes+1,0);
  moving_types_.assign(atom->ntypes+1,0);
  for (int t = 1; t <= atom->ntypes; t++) {
    any = any || templates_[t];
    obstacle_types_[t] = templates_[t] && templates_[t]->fixed;
  }
  if (!any) error->all(FLERR,"Illegal fix trimesh/template command: no type given");
}

void *FixTrimeshTemplate::extract(const char *name, int &dim)
{
  dim = 1;
  if (strcmp(name,"obstacle_types") == 0) return obstacle_types_.data();
  return NULL;
}

FixTrimeshTemplate::~FixTrimeshTemplate()
{
  if (state_ && modify->find_fix(state_->id) >= 0) modify->delete_fix(state_->id);
}

void FixTrimeshTemplate::post_create()
{
  // per-atom orientation + angular momentum; re-created with the same ID after read_restart
  // so that the restart file's values are restored
  std::string sid = std::string(id) + "_state";
  int ifix = modify->find_fix(sid.c_str());
  if (ifix < 0) {
    char *fixarg[3];
    fixarg[0] = const_cast<char*>(sid.c_str());
    fixarg[1] = (char *) "all";
    fixarg[2] = (char *) "trimesh/state";
    modify->add_fix(3,fixarg);
    ifix = modify->find_fix(sid.c_str());
  }
  state_ = dynamic_cast<FixTrimeshState*>(modify->fix[ifix]);
  if (!state_) error->all(FLERR,"Fix trimesh/template: fix <ID>_state exists but is not trimesh/state");
}

int FixTrimeshTemplate::setmask()
{
  // PRE_EXCHANGE for setup_pre_exchange() (poses of new atoms before the ghosts are made;
  // pre_exchange() itself does nothing); PRE_NEIGHBOR for atoms inserted during a run
  return FixConst::PRE_EXCHANGE | FixConst::PRE_NEIGHBOR;
}

void FixTrimeshTemplate::init()
{
  int ifix = modify->find_fix((std::string(id) + "_state").c_str());
  state_ = ifix >= 0 ? dynamic_cast<FixTrimeshState*>(modify->fix[ifix]) : NULL;
  if (!state_) error->all(FLERR,"Fix trimesh/template: its fix trimesh/state was deleted");
  check_insertion_templates();
  // walls meet grains by their surfaces through pair_style trimesh; without it they would push
  // the grains' bounding spheres
  if (!force->pair_match("trimesh",1))
    for (int i = 0; i < modify->nfix; i++)
      if (strcmp(modify->fix[i]->style,"wall/gran") == 0) {
        std::string msg = std::string("Fix trimesh/template ") + id + ": fix wall/gran " +
                          modify->fix[i]->id + " would treat the grains as their bounding spheres: "
                          "use pair_style trimesh (alone or in pair_style hybrid)";
        error->all(FLERR,msg.c_str());
      }
  apply_to_atoms(false);
}

void FixTrimeshTemplate::check_insertion_templates()
{
  // Spheres inserted for a template type: the insertion's overlap check is conservative only
  // when the sphere covers the grain (bounding radius + eps); particletemplate/trimesh makes
  // exactly that sphere with the grain's mass, particletemplate/sphere is checked.
  char msg[1024];
  for (int i = 0; i < modify->nfix; i++) {
    Fix *f = modify->fix[i];
    const bool sphere = strcmp(f->style,"particletemplate/sphere") == 0;
    const bool grain = strcmp(f->style,"particletemplate/trimesh") == 0;
    if (!sphere && !grain) continue;
    FixTemplateSphere *pt = static_cast<FixTemplateSphere *>(f);
    for (int t = pt->mintype(); t <= pt->maxtype(); t++) {
      const TrimeshTypeTemplate *tt = type_template(t);
      if (!tt) continue;
      const double need = tt->boundingRadius + halo_;
      if (grain) {
        if (std::abs(static_cast<FixTemplateTrimesh *>(f)->insertion_radius() - need) > 1e-12 * need) {
          snprintf(msg,sizeof(msg),"Fix particletemplate/trimesh %s: pair_style trimesh eps changed "
                   "after it was defined (insertion radius %g m, grain bounding radius + eps %g m): "
                   "define it again after the pair style",f->id,
                   static_cast<FixTemplateTrimesh *>(f)->insertion_radius(),need);
          error->all(FLERR,msg);
        }
        continue;
      }
      if (pt->min_rad() < need * (1.0 - 1e-12)) {
        snprintf(msg,sizeof(msg),"Fix particletemplate/sphere %s inserts atom type %d (a grain of fix "
                 "trimesh/template %s) with radius %g m, below the grain's bounding radius + eps %g m: "
                 "the insertion would place grains overlapping each other. Use fix "
                 "particletemplate/trimesh (the grain's bounding sphere and mass) or radius >= %g",
                 f->id,t,id,pt->min_rad(),need,need);
        error->all(FLERR,msg);
      }
      if (comm->me == 0 && std::abs(pt->massexpect() - tt->mass) > 1e-9 * tt->mass) {
        snprintf(msg,sizeof(msg),"Fix particletemplate/sphere %s inserts grains of type %d as spheres "
                 "of mass %g kg: insertion by mass and its INFO lines count that, not the grain's "
                 "%g kg (fix particletemplate/trimesh counts the grain's)",f->id,t,pt->massexpect(),
                 tt->mass);
        error->warning(FLERR,msg);
      }
    }
  }
}

void FixTrimeshTemplate::setup_pre_exchange()
{
  apply_to_atoms(true);
}

bigint FixTrimeshTemplate::count_new_atoms() const
{
  bigint mine = 0, all = 0;
  double **quat = state_->quat;
  for (int i = 0; i < atom->nlocal; i++)
    if (type_template(atom->type[i]) &&
        quat[i][0] == 0.0 && quat[i][1] == 0.0 && quat[i][2] == 0.0 && quat[i][3] == 0.0) mine++;
  MPI_Allreduce(&mine,&all,1,MPI_LMP_BIGINT,MPI_SUM,world);
  return all;
}

void FixTrimeshTemplate::pre_neighbor()
{
  // insertion fixes create spheres (set_arrays leaves quat = 0) in pre_exchange: give them
  // their template, then refresh the ghosts' radius/mass/orientation before the list build
  if (count_new_atoms() == 0) return;
  apply_to_atoms(true);
  state_->forward_shapes();
}

void FixTrimeshTemplate::set_moving(int t, bool moving)
{
  if (t >= 1 && t < static_cast<int>(moving_types_.size())) moving_types_[t] = moving;
}

bool FixTrimeshTemplate::is_moving(int t) const
{
  return t >= 1 && t < static_cast<int>(moving_types_.size()) && moving_types_[t];
}

void FixTrimeshTemplate::set_halo(double eps)
{
  halo_ = eps;
}

FixTrimeshTemplate *FixTrimeshTemplate::find(LAMMPS *lmp, const char *who)
{
  FixTrimeshTemplate *found = NULL;
  // A NULL slot is a fix being replaced by ID while a constructor asks (fix_lookup.h).
  for (int i = 0; i < lmp->modify->nfix; i++)
    if (lmp->modify->fix[i] && strcmp(lmp->modify->fix[i]->style,"trimesh/template") == 0) {
      if (found) {
        char msg[256];
        snprintf(msg,sizeof(msg),"%s: more than one fix trimesh/template",who);
        lmp->error->all(FLERR,msg);
      }
      found = static_cast<FixTrimeshTemplate*>(lmp->modify->fix[i]);
    }
  return found;
}

const TrimeshTypeTemplate *FixTrimeshTemplate::type_template(int t) const
{
  if (t < 1 || t >= static_cast<int>(templates_.size())) return NULL;
  return templates_[t].get();
}

double FixTrimeshTemplate::max_rad(int t)
{
  const TrimeshTypeTemplate *tt = type_template(t);
  return tt ? tt->boundingRadius + halo_ : 0.0;
}

double FixTrimeshTemplate::min_rad(int t)
{
  return max_rad(t);
}

void FixTrimeshTemplate::apply_to_atoms(bool initialise_poses)
{
  const int nlocal = atom->nlocal;
  int *type = atom->type;
  int *tag = atom->tag;
  double *radius = atom->radius, *rmass = atom->rmass, *density = atom->density;
  double **omega = atom->omega;
  double **quat = state_->quat, **angmom = state_->angmom;

  for (int i = 0; i < nlocal; i++) {
    const TrimeshTypeTemplate *tt = type_template(type[i]);
    if (!tt) continue;
    radius[i] = tt->boundingRadius + halo_;
    rmass[i] = tt->mass;
    if (density) density[i] = tt->density;
    // a static obstacle's surface does not move, whatever a `velocity` command set
    if (tt->fixed && !moving_types_[type[i]])
      for (int k = 0; k < 3; k++) atom->v[i][k] = omega[i][k] = 0.0;
    const double n2 = quat[i][0]*quat[i][0] + quat[i][1]*quat[i][1] +
                      quat[i][2]*quat[i][2] + quat[i][3]*quat[i][3];
    // restart / earlier run: keep the pose; init() only refreshes radius and mass
    if (n2 > 0.0 || !initialise_poses) continue;
    quat[i][0] = 1.0; quat[i][1] = quat[i][2] = quat[i][3] = 0.0;
    if (tt->fixed) {
      // obstacle: the pose that puts the surface where the file has it
      double **x = atom->x;
      for (int k = 0; k < 3; k++) x[i][k] = tt->filePosition[k];
      quat[i][0] = tt->fileOrientation.w(); quat[i][1] = tt->fileOrientation.x();
      quat[i][2] = tt->fileOrientation.y(); quat[i][3] = tt->fileOrientation.z();
      for (int k = 0; k < 3; k++) atom->v[i][k] = omega[i][k] = angmom[i][k] = 0.0;
      continue;
    } else if (orientation_ == OrientFile) {
      // the surface starts as the file (or generator) has it, centred on the atom
      quat[i][0] = tt->fileOrientation.w(); quat[i][1] = tt->fileOrientation.x();
      quat[i][2] = tt->fileOrientation.y(); quat[i][3] = tt->fileOrientation.z();
    } else if (orientation_ == OrientRandom) {
      // uniform random rotation (Shoemake), reproducible per atom ID on any number of ranks
      std::mt19937_64 rng(static_cast<std::uint64_t>(orientation_seed_) * 1000003u +
                          static_cast<std::uint64_t>(tag[i]));
      auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
      const double u1 = uniform(), u2 = 2.0*M_PI*uniform(), u3 = 2.0*M_PI*uniform();
      const double a = std::sqrt(1.0-u1), b = std::sqrt(u1);
      quat[i][0] = b*std::cos(u3); quat[i][1] = a*std::sin(u2);
      quat[i][2] = a*std::cos(u2); quat[i][3] = b*std::sin(u3);
    }
    // angular momentum from a given omega (e.g. `velocity` / `set` on omega), world frame
    tt->angularMomentumFromOmega(quat[i],omega[i],angmom[i]);
  }
}
