// Does a small pile of dented grains come to rest? The heap deck's grains (40 triangles, radius
// 2.5 mm, dents 20 %, density 2500) and materials (E 1e5 Pa, nu 0.3, e 0.3, mu 0.5, halo 0.1 mm)
// dropped onto a fixed floor box, integrated as fix nve/trimesh does (velocity Verlet: half kick,
// drift, forces from the half-step velocities, half kick) with the contact model pair_style
// trimesh builds from those materials, every pair checked every step. Prints the kinetic energy
// (translation and rotation apart), the contact points and the history matcher's counts every
// `every` steps.
//
//   bench_resting_energy [grains N] [steps S] [every K] [dt s] [eps m] [rotation 0|1]
//                        [tangential none|viscous|history] [seed n] [drop m]
#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "contact/MeshContact.h"
#include "contact_model/ContactHistory.h"
#include "contact_model/ContactModel.h"
#include "contact_model/DampingApproach.h"
#include "contact_model/MaterialMapping.h"
#include "dynamics/ContactForce.h"
#include "dynamics/RigidBody.h"
#include "geometry/DentedSphere.h"
#include "geometry/PrimitiveMeshes.h"
#include "geometry/RigidShape.h"

using namespace spacetree;

namespace {

struct Settings {
  int grains = 1;
  long steps = 40000;
  long every = 500;
  double dt = 1e-4;
  double eps = 1e-4;
  bool rotation = true;
  std::string tangential = "history";
  unsigned seed = 7;
  double drop = 0.5e-3;  // gap below the lowest grain [m]
  double tangentialDampingFactor = 1.0;
  long traceFrom = -1, traceSteps = 0;
  int traceI = -1, traceJ = -1;  // this pair's raw contacts too (no de-duplication)  // print every pair's contact points over these steps  // times the normal damping ratio's D_t
  double youngs = 1e5, poisson = 0.3, restitution = 0.3, friction = 0.5, density = 2500;
};

contact_model::ContactParameters parameters(const Settings& s, double ri, double rj) {
  const double rstar = contact_model::effectiveRadius(ri, rj);
  const double S = contact_model::haloStiffness(
      contact_model::effectiveModulus(s.youngs, s.poisson, s.youngs, s.poisson), rstar);
  contact_model::ContactParameters p;
  p.set("haloDepth", s.eps);
  p.set("characteristicRadius", rstar);
  p.set("stiffness", S);
  const double D = contact_model::dampingForRestitution(S, s.restitution);
  p.set("damping", D);
  p.set("friction", s.friction);
  p.set("slidingDamping", 1.0);
  const double kt = S * contact_model::mindlinStiffnessRatio(s.youngs, s.poisson, s.youngs, s.poisson);
  p.set("tangentialStiffness", kt);
  p.set("tangentialDamping", s.tangentialDampingFactor * contact_model::tangentialDampingFor(S, D, kt));
  return p;
}

struct Body {
  const geometry::RigidShape* shape;
  dynamics::RigidBody body;
  const contact_model::ContactModel* againstGrain;
};

}  // namespace

int main(int argc, char** argv) {
  Settings s;
  for (int a = 1; a + 1 < argc; a += 2) {
    const std::string k = argv[a], v = argv[a + 1];
    if (k == "grains") s.grains = std::atoi(v.c_str());
    else if (k == "steps") s.steps = std::atol(v.c_str());
    else if (k == "every") s.every = std::atol(v.c_str());
    else if (k == "dt") s.dt = std::atof(v.c_str());
    else if (k == "eps") s.eps = std::atof(v.c_str());
    else if (k == "rotation") s.rotation = std::atoi(v.c_str()) != 0;
    else if (k == "tangential") s.tangential = v;
    else if (k == "seed") s.seed = unsigned(std::atoi(v.c_str()));
    else if (k == "drop") s.drop = std::atof(v.c_str());
    else if (k == "trace") s.traceFrom = std::atol(v.c_str());
    else if (k == "tracei") s.traceI = std::atoi(v.c_str());
    else if (k == "tracej") s.traceJ = std::atoi(v.c_str());
    else if (k == "tracesteps") s.traceSteps = std::atol(v.c_str());
    else if (k == "tdamp") s.tangentialDampingFactor = std::atof(v.c_str());
    else { std::fprintf(stderr, "unknown option %s\n", k.c_str()); return 2; }
  }
  geometry::DentedSphereOptions d;
  d.triangles = 40;
  d.radius = 0.0025;
  d.amplitude = 0.2;
  d.seed = 7;
  const geometry::RigidShape grain = geometry::RigidShape::fromMesh(geometry::dentedSphere(d));
  const geometry::RigidShape floor =
      geometry::RigidShape::fromMesh(geometry::boxMesh(Eigen::Vector3d(0.2, 0.2, 0.004)));
  const double r = std::cbrt(3.0 * grain.volume / (4.0 * M_PI));
  const double mass = grain.mass(s.density);

  contact_model::ContactModelSpec spec;
  spec.tangential = s.tangential;
  const contact_model::ContactModel grainGrain(spec, parameters(s, r, r));
  const contact_model::ContactModel grainFloor(spec, parameters(s, r, INFINITY));

  std::vector<Body> bodies;
  bodies.push_back({&floor, dynamics::RigidBody::fixed(Eigen::Vector3d(0, 0, -0.002)), nullptr});
  std::mt19937_64 rng(s.seed);
  std::normal_distribution<double> n;
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  // grains in a loose column of 2 x 2 per layer, spacing 2.6 radii, randomly turned
  const double spacing = 2.2 * d.radius;
  for (int g = 0; g < s.grains; ++g) {
    const Eigen::Quaterniond q = Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
    double lowest = INFINITY;
    for (const Eigen::Vector3d& v : grain.bodyMesh.vertices) lowest = std::min(lowest, (q * v).z());
    const int layer = g / 4, k = g % 4;
    const Eigen::Vector3d at((k % 2 - 0.5) * spacing + 0.1 * spacing * u(rng),
                             (k / 2 - 0.5) * spacing + 0.1 * spacing * u(rng),
                             s.drop - lowest + layer * spacing);
    bodies.push_back({&grain, dynamics::RigidBody::free(mass, grain.principalInertiaForMass(mass), at, q),
                      &grainGrain});
  }

  contact::MeshContactOptions options;
  options.epsilon = s.eps;
  contact::MeshContactFinder finder(options);
  contact_model::ContactHistoryMatcher matcher(grainGrain.historySize(), {0.0, 0.9});
  std::map<std::pair<int, int>, std::vector<double>> histories, next;
  std::vector<contact::ContactPoint> contacts;
  const Eigen::Vector3d gravity(0, 0, -9.81);
  std::vector<dynamics::BodyLoad> loads(bodies.size());
  contact_model::ContactHistoryMatchStatistics stats;
  std::size_t contactCount = 0;

  long currentStep = 0;
  const auto forces = [&](double historyDt) {
    const bool trace = s.traceFrom >= 0 && currentStep >= s.traceFrom && currentStep < s.traceFrom + s.traceSteps;
    for (auto& l : loads) l = dynamics::BodyLoad();
    next.clear();
    contactCount = 0;
    for (std::size_t i = 0; i < bodies.size(); ++i)
      for (std::size_t j = i + 1; j < bodies.size(); ++j) {
        const dynamics::RigidBody& a = bodies[i].body;
        const dynamics::RigidBody& b = bodies[j].body;
        contacts.clear();
        const contact::Pose pa{a.position, a.orientation}, pb{b.position, b.orientation};
        finder.find(*bodies[i].shape, pa, *bodies[j].shape, pb, contacts);
        if (trace && int(i) == s.traceI && int(j) == s.traceJ)
        {
          if (currentStep == s.traceFrom)
            for (int side = 0; side < 2; ++side) {
              const geometry::RigidShape& sh = *bodies[side == 0 ? i : j].shape;
              const contact::Pose& ps = side == 0 ? pa : pb;
              for (std::size_t t = 0; t < sh.bodyMesh.triangles.size(); ++t) {
                std::printf("V %d %zu", side, t);
                for (int c = 0; c < 3; ++c) {
                  const Eigen::Vector3d w = ps.orientation * sh.bodyMesh.vertices[std::size_t(sh.bodyMesh.triangles[t][c])] + ps.position;
                  const Eigen::Vector3d l = pa.orientation.conjugate() * (w - pa.position);
                  std::printf(" %d %.4f %.4f %.4f", sh.bodyMesh.triangles[t][c], 1e6 * l.x(), 1e6 * l.y(), 1e6 * l.z());
                }
                std::printf("\n");
              }
            }
          for (int filter = 0; filter < 2; ++filter) {
            contact::MeshContactOptions o = options;
            o.deduplicate = false;
            o.localMinimaOnly = filter != 0;
            contact::MeshContactFinder f(o);
            std::vector<contact::ContactPoint> raw;
            f.find(*bodies[i].shape, pa, *bodies[j].shape, pb, raw);
            for (const contact::ContactPoint& c : raw) {
              const Eigen::Vector3d local = pa.orientation.conjugate() * (c.point - pa.position);
              const Eigen::Vector3d nl = pa.orientation.conjugate() * c.normal;
              std::printf("R %ld filter %d tri %d %d p_um %8.2f %8.2f %8.2f n %7.4f %7.4f %7.4f pen_um %.4f\n",
                          currentStep, filter, c.firstTriangle, c.secondTriangle, 1e6 * local.x(), 1e6 * local.y(),
                          1e6 * local.z(), nl.x(), nl.y(), nl.z(), 1e6 * c.penetration);
            }
          }
        }
        if (contacts.empty()) continue;
        contactCount += contacts.size();
        const contact_model::ContactModel& law = i == 0 ? grainFloor : grainGrain;
        double* slots = nullptr;
        int stride = 0;
        if (law.historySize() > 0) {
          matcher.setDistance(0.5 * std::min(bodies[i].shape->minimumEdgeLength, bodies[j].shape->minimumEdgeLength));
          const std::vector<double>& prev = histories[{int(i), int(j)}];
          std::vector<double>& rec = next[{int(i), int(j)}];
          matcher.match(prev.data(), prev.size() / std::size_t(matcher.recordSize()), contacts, pa, rec,
                        historyDt > 0 ? &stats : nullptr);
          slots = rec.data() + contact_model::kContactAnchorDoubles;
          stride = matcher.recordSize();
        }
        dynamics::RigidBody ca = a, cb = b;
        if (!s.rotation) {
          ca.angularMomentum.setZero();
          cb.angularMomentum.setZero();
          ca.inverseInertia.setZero();  // no rotation: infinite inertia
          cb.inverseInertia.setZero();
        }
        for (std::size_t k = 0; k < contacts.size(); ++k) {
          const contact::ContactPoint& c = contacts[k];
          const contact_model::Contact con = contact_model::makeContact(ca, cb, c.point, c.normal, c.penetration);
          const Eigen::Vector3d f = law.evaluate(con, slots ? slots + k * stride : nullptr, historyDt).forceOnFirst;
          dynamics::applyContactForce(ca, cb, c.point, f, loads[i], loads[j]);
          if (trace) {
            const Eigen::Vector3d local = pa.orientation.conjugate() * (c.point - pa.position);
            const Eigen::Vector3d nl = pa.orientation.conjugate() * c.normal;
            std::printf("T %ld pair %zu %zu k %zu tri %d %d merged %d p_um %8.2f %8.2f %8.2f n %7.4f %7.4f %7.4f pen_um %.4f f %.3e %.3e %.3e xi %.3e\n",
                        currentStep, i, j, k, c.firstTriangle, c.secondTriangle, c.mergedCount, 1e6 * local.x(),
                        1e6 * local.y(), 1e6 * local.z(), nl.x(), nl.y(), nl.z(), 1e6 * c.penetration, f.x(), f.y(),
                        f.z(), slots ? Eigen::Map<const Eigen::Vector3d>(slots + k * stride).norm() : 0.0);
          }
        }
      }
    histories.swap(next);
    for (std::size_t i = 1; i < bodies.size(); ++i) {
      loads[i].force += mass * gravity;
      if (!s.rotation) loads[i].torque.setZero();
    }
  };

  {
    const contact_model::ContactParameters p = parameters(s, r, INFINITY);
    const Eigen::Vector3d inertia = grain.principalInertiaForMass(mass);
    const double inverseTangential = 1.0 / mass + grain.boundingRadius * grain.boundingRadius / inertia.minCoeff();
    const contact_model::ContactTiming t = contact_model::contactTiming(
        p.values().at("stiffness"), p.values().at("damping"), mass, p.values().at("tangentialStiffness"),
        p.values().at("tangentialDamping"), 1.0 / inverseTangential);
    std::printf("# grain-floor: S %.4g N/m kt %.4g N/m D %.4g D_t %.4g; omega_n %.4g omega_t %.4g 1/s; "
                "stable step %.4g s; inertia %.4g %.4g %.4g (0.4 m r^2 = %.4g) bounding radius %.4g\n",
                p.values().at("stiffness"), p.values().at("tangentialStiffness"), p.values().at("damping"),
                p.values().at("tangentialDamping"), t.normalFrequency, t.tangentialFrequency, t.stableStep,
                inertia.x(), inertia.y(), inertia.z(), 0.4 * mass * r * r, grain.boundingRadius);
  }
  forces(0.0);
  double peak = 0.0;
  std::printf("# grains %d dt %g eps %g rotation %d tangential %s r %.4g m mass %.4g kg\n", s.grains, s.dt,
              s.eps, int(s.rotation), s.tangential.c_str(), r, mass);
  std::printf("%8s %10s %12s %12s %12s %7s %7s %7s %7s %7s %7s %10s\n", "step", "time", "ke_trans",
              "ke_rot", "ke/peak", "points", "kept", "moved", "merged", "started", "dropped", "zmin");
  for (long step = 1; step <= s.steps; ++step) {
    currentStep = step;
    for (std::size_t i = 1; i < bodies.size(); ++i) {
      bodies[i].body.kick(loads[i].force, loads[i].torque, 0.5 * s.dt);
      bodies[i].body.drift(s.dt);
    }
    forces(s.dt);
    double et = 0, er = 0, zmin = INFINITY;
    for (std::size_t i = 1; i < bodies.size(); ++i) {
      bodies[i].body.kick(loads[i].force, loads[i].torque, 0.5 * s.dt);
      et += bodies[i].body.translationalEnergy();
      er += bodies[i].body.rotationalEnergy();
      zmin = std::min(zmin, bodies[i].body.position.z());
    }
    peak = std::max(peak, et + er);
    if (step % s.every == 0) {
      std::printf("%8ld %10.4f %12.4e %12.4e %12.4e %7zu %7zu %7zu %7zu %7zu %7zu %10.6f\n", step, step * s.dt,
                  et, er, (et + er) / peak, contactCount, stats.kept, stats.moved, stats.merged, stats.started,
                  stats.dropped, zmin);
      stats = contact_model::ContactHistoryMatchStatistics();
    }
  }
  return 0;
}
