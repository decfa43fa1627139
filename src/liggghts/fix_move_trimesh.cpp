/* spacetree-dem: prescribed motion of obstacles (thin layer over core PrescribedMotion). */

#include "fix_move_trimesh.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include <mpi.h>

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_trimesh_state.h"
#include "fix_trimesh_template.h"
#include "force.h"
#include "modify.h"
#include "update.h"

using namespace LAMMPS_NS;
namespace dy = spacetree::dynamics;

FixMoveTrimesh::FixMoveTrimesh(LAMMPS *lmp, int narg, char **arg) :
  Fix(lmp, narg, arg), templ_(NULL), started_(false), time_origin_(0.0), restored_elapsed_(-1.0)
{
  time_depend = 1;
  restart_global = 1;
  vector_flag = 1;
  size_vector = 2;
  global_freq = 1;
  extvector = 0;

  int iarg = 3;
  if (iarg >= narg || strcmp(arg[iarg],"type") != 0)
    error->all(FLERR,"Illegal fix move/trimesh command: expected 'type T [T ...]'");
  iarg++;
  while (iarg < narg && strcmp(arg[iarg],"rotate") != 0 && strcmp(arg[iarg],"linear") != 0) {
    const int t = force->inumeric(FLERR,arg[iarg]);
    if (t < 1 || t > atom->ntypes) {
      std::string msg = std::string("Illegal fix move/trimesh command: atom type ") + arg[iarg] + " out of range";
      error->all(FLERR,msg.c_str());
    }
    types_.push_back(t);
    iarg++;
  }
  if (types_.empty()) error->all(FLERR,"Illegal fix move/trimesh command: expected 'type T [T ...]'");

  Eigen::Vector3d velocity = Eigen::Vector3d::Zero(), origin = Eigen::Vector3d::Zero();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  double omega = 0.0;
  bool rotate = false, linear = false;
  while (iarg < narg) {
    if (strcmp(arg[iarg],"rotate") == 0) {
      if (rotate) error->all(FLERR,"Illegal fix move/trimesh command: rotate given twice");
      if (iarg+11 > narg || strcmp(arg[iarg+1],"origin") != 0 || strcmp(arg[iarg+5],"axis") != 0 ||
          (strcmp(arg[iarg+9],"period") != 0 && strcmp(arg[iarg+9],"omega") != 0))
        error->all(FLERR,"Illegal fix move/trimesh command: rotate origin Px Py Pz axis Ax Ay Az "
                   "(period P | omega W)");
      for (int k = 0; k < 3; k++) {
        origin[k] = force->numeric(FLERR,arg[iarg+2+k]);
        axis[k] = force->numeric(FLERR,arg[iarg+6+k]);
      }
      const double value = force->numeric(FLERR,arg[iarg+10]);
      if (strcmp(arg[iarg+9],"period") == 0) {
        if (value == 0.0) error->all(FLERR,"Illegal fix move/trimesh command: period must not be 0");
        omega = 2.0*M_PI/value;
      } else omega = value;
      rotate = true;
      iarg += 11;
    } else if (strcmp(arg[iarg],"linear") == 0) {
      if (linear) error->all(FLERR,"Illegal fix move/trimesh command: linear given twice");
      if (iarg+4 > narg) error->all(FLERR,"Illegal fix move/trimesh command: linear Vx Vy Vz");
      for (int k = 0; k < 3; k++) velocity[k] = force->numeric(FLERR,arg[iarg+1+k]);
      linear = true;
      iarg += 4;
    } else {
      std::string msg = std::string("Illegal fix move/trimesh command: unknown keyword '") + arg[iarg] +
                        "' (rotate, linear)";
      error->all(FLERR,msg.c_str());
    }
  }
  if (!rotate && !linear) error->all(FLERR,"Illegal fix move/trimesh command: expected rotate and/or linear");
  try { motion_ = dy::PrescribedMotion::make(velocity,origin,axis,omega); }
  catch (const std::exception &e) {
    error->all(FLERR,(std::string("Illegal fix move/trimesh command: ") + e.what()).c_str());
  }
}

FixMoveTrimesh::~FixMoveTrimesh()
{
  // the obstacles stop: their velocities are held at zero again by the template fix
  if (FixTrimeshTemplate *templ = FixTrimeshTemplate::find(lmp,"Fix move/trimesh"))
    for (int t : types_) templ->set_moving(t,false);
}

int FixMoveTrimesh::setmask()
{
  return FixConst::PRE_EXCHANGE | FixConst::INITIAL_INTEGRATE;
}

void FixMoveTrimesh::init()
{
  templ_ = FixTrimeshTemplate::find(lmp,"Fix move/trimesh");
  if (!templ_) error->all(FLERR,"Fix move/trimesh requires fix trimesh/template");
  char msg[256];
  for (int t : types_) {
    const TrimeshTypeTemplate *tt = templ_->type_template(t);
    if (!tt || !tt->fixed) {
      snprintf(msg,sizeof(msg),"Fix move/trimesh: atom type %d is not an obstacle (a 'fixed' type of "
               "fix trimesh/template)",t);
      error->all(FLERR,msg);
    }
    for (int i = 0; i < modify->nfix; i++) {
      if (modify->fix[i] == this || strcmp(modify->fix[i]->style,"move/trimesh") != 0) continue;
      const std::vector<int> &other = static_cast<FixMoveTrimesh*>(modify->fix[i])->types_;
      for (int u : other)
        if (u == t) {
          snprintf(msg,sizeof(msg),"Fix move/trimesh: atom type %d is moved by two fixes (%s, %s)",t,
                   id,modify->fix[i]->id);
          error->all(FLERR,msg);
        }
    }
    templ_->set_moving(t,true);
  }
}

double FixMoveTrimesh::elapsed() const
{
  return update->get_cur_time() - time_origin_;
}

void FixMoveTrimesh::capture_start_poses()
{
  // (ID, x, q) of every owned atom of the moved types, gathered on every rank
  double **x = atom->x, **quat = templ_->state()->quat;
  std::vector<double> mine;
  for (int i = 0; i < atom->nlocal; i++)
    for (int t : types_)
      if (atom->type[i] == t) {
        mine.push_back((double) atom->tag[i]);
        for (int k = 0; k < 3; k++) mine.push_back(x[i][k]);
        for (int k = 0; k < 4; k++) mine.push_back(quat[i][k]);
      }
  const int n = (int) mine.size();
  std::vector<int> counts(comm->nprocs), displs(comm->nprocs);
  MPI_Allgather(&n,1,MPI_INT,counts.data(),1,MPI_INT,world);
  int total = 0;
  for (int p = 0; p < comm->nprocs; p++) { displs[p] = total; total += counts[p]; }
  std::vector<double> all(total);
  MPI_Allgatherv(mine.data(),n,MPI_DOUBLE,all.data(),counts.data(),displs.data(),MPI_DOUBLE,world);
  start_.clear();
  for (int k = 0; k + 8 <= total; k += 8) {
    StartPose s;
    s.position = Eigen::Vector3d(all[k+1],all[k+2],all[k+3]);
    s.orientation = Eigen::Quaterniond(all[k+4],all[k+5],all[k+6],all[k+7]);
    start_[(long long) all[k]] = s;
  }
  if (start_.empty()) {
    std::string msg = std::string("Fix move/trimesh ") + id + ": no atom of its obstacle types";
    error->all(FLERR,msg.c_str());
  }
}

void FixMoveTrimesh::setup_pre_exchange()
{
  // obstacles placed where their file puts them (idempotent), then the start poses once
  templ_->apply_to_atoms(true);
  if (!started_) {
    time_origin_ = update->get_cur_time();
    capture_start_poses();
    started_ = true;
  } else if (restored_elapsed_ >= 0.0) {
    // LIGGGHTS restarts the clock at read_restart: continue from the elapsed time written
    time_origin_ = update->get_cur_time() - restored_elapsed_;
    restored_elapsed_ = -1.0;
  }
  place(elapsed());
}

void FixMoveTrimesh::initial_integrate(int)
{
  // ntimestep is already the step being computed: the pose at its time
  place(elapsed());
}

void FixMoveTrimesh::place(double t)
{
  double **x = atom->x, **v = atom->v, **omega = atom->omega;
  double **quat = templ_->state()->quat;
  const Eigen::Vector3d w = motion_.angularVelocity();
  char msg[256];
  for (int i = 0; i < atom->nlocal; i++) {
    bool moved = false;
    for (int tp : types_) moved = moved || atom->type[i] == tp;
    if (!moved) continue;
    const auto it = start_.find((long long) atom->tag[i]);
    if (it == start_.end()) {
      snprintf(msg,sizeof(msg),"Fix move/trimesh %s: obstacle atom %d appeared after the motion "
               "started",id,atom->tag[i]);
      error->one(FLERR,msg);
    }
    Eigen::Vector3d p;
    Eigen::Quaterniond q;
    motion_.poseAt(it->second.position,it->second.orientation,t,p,q);
    const Eigen::Vector3d vc = motion_.velocityAt(p,t);
    for (int k = 0; k < 3; k++) { x[i][k] = p[k]; v[i][k] = vc[k]; omega[i][k] = w[k]; }
    quat[i][0] = q.w(); quat[i][1] = q.x(); quat[i][2] = q.y(); quat[i][3] = q.z();
  }
}

double FixMoveTrimesh::compute_vector(int n)
{
  const double t = started_ ? elapsed() : 0.0;
  return n == 0 ? t : motion_.angularSpeed * t;
}

void FixMoveTrimesh::write_restart(FILE *fp)
{
  if (comm->me != 0) return;
  std::vector<double> record;
  record.push_back(started_ ? 1.0 : 0.0);
  record.push_back(started_ ? elapsed() : 0.0);
  record.push_back((double) start_.size());
  for (const auto &s : start_) {
    record.push_back((double) s.first);
    for (int k = 0; k < 3; k++) record.push_back(s.second.position[k]);
    record.push_back(s.second.orientation.w()); record.push_back(s.second.orientation.x());
    record.push_back(s.second.orientation.y()); record.push_back(s.second.orientation.z());
  }
  const int n = (int) (record.size()*sizeof(double));
  fwrite(&n,sizeof(int),1,fp);
  fwrite(record.data(),sizeof(double),record.size(),fp);
}

void FixMoveTrimesh::restart(char *buf)
{
  const double *r = reinterpret_cast<const double *>(buf);
  started_ = r[0] != 0.0;
  restored_elapsed_ = started_ ? r[1] : -1.0;
  const int n = (int) r[2];
  start_.clear();
  for (int k = 0; k < n; k++) {
    const double *s = r + 3 + 8*k;
    StartPose p;
    p.position = Eigen::Vector3d(s[1],s[2],s[3]);
    p.orientation = Eigen::Quaterniond(s[4],s[5],s[6],s[7]);
    start_[(long long) s[0]] = p;
  }
}
