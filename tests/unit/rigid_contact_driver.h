// A tiny rigid-body driver for the core physics tests (no LIGGGHTS): symplectic Euler (forces
// at x_n, then v_{n+1}, then x_{n+1}, the order of LIGGGHTS' nve integrators), all pairs
// checked every step, forces and rolling torques from one ContactModel. With a model that keeps
// history, each pair's contact points are matched to the previous step's
// (ContactHistoryMatcher, half the de-duplication length) and carry their history slots, as
// pair_style trimesh does.
#pragma once

#include <Eigen/Geometry>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include "contact/MeshContact.h"
#include "contact_model/ContactHistory.h"
#include "contact_model/ContactModel.h"
#include "dynamics/ContactForce.h"
#include "dynamics/RigidBody.h"
#include "geometry/RigidShape.h"

namespace spacetree::testing {

struct Particle {
  const geometry::RigidShape* shape;
  dynamics::RigidBody body;
};

struct StepReport {
  std::size_t contacts = 0;
  double largestPenetration = 0.0;  // eps - d/2 over all contacts (> eps: surfaces overlap)
  std::size_t historiesKept = 0;    // contact points that continued a previous one
};

class RigidContactDriver {
 public:
  RigidContactDriver(contact::MeshContactOptions options, const contact_model::ContactModel& model,
                     Eigen::Vector3d gravity)
      : finder_(std::move(options)), model_(model), gravity_(gravity),
        matcher_(model.historySize(), {0.0, 0.9}) {}

  void setGravity(const Eigen::Vector3d& g) { gravity_ = g; }
  // An external force and torque (about the centre) on one particle, added to the contact
  // loads in every step until changed.
  void setExternalLoad(std::size_t particle, const Eigen::Vector3d& force,
                       const Eigen::Vector3d& torque = Eigen::Vector3d::Zero()) {
    external_[particle] = {force, torque};
  }
  // The history records of the pair (i, j), i < j (recordSize() doubles per contact point).
  const std::vector<double>& history(std::size_t i, std::size_t j) { return histories_[{i, j}]; }

  StepReport step(std::vector<Particle>& particles, double dt) {
    using contact::ContactPoint;
    StepReport report;
    std::vector<dynamics::BodyLoad> loads(particles.size());
    std::map<std::pair<std::size_t, std::size_t>, std::vector<double>> nextHistories;
    const int h = model_.historySize();
    for (std::size_t i = 0; i < particles.size(); ++i)
      for (std::size_t j = i + 1; j < particles.size(); ++j) {
        const dynamics::RigidBody& a = particles[i].body;
        const dynamics::RigidBody& b = particles[j].body;
        if (a.isFixed() && b.isFixed()) continue;
        contacts_.clear();
        const contact::Pose pa{a.position, a.orientation}, pb{b.position, b.orientation};
        finder_.find(*particles[i].shape, pa, *particles[j].shape, pb, contacts_);
        double* slots = nullptr;
        int stride = 0;
        if (h > 0 && !contacts_.empty()) {
          const double length =
              0.5 * std::min(particles[i].shape->minimumEdgeLength, particles[j].shape->minimumEdgeLength);
          matcher_.setDistance(length);
          contact_model::ContactHistoryMatcher& matcher = matcher_;
          const std::vector<double>& previous = histories_[{i, j}];
          std::vector<double>& next = nextHistories[{i, j}];
          contact_model::ContactHistoryMatchStatistics stats;
          matcher.match(previous.data(), previous.size() / std::size_t(matcher.recordSize()),
                        contacts_, pa, next, &stats);
          report.historiesKept += stats.kept;
          slots = next.data() + contact_model::kContactAnchorDoubles;
          stride = matcher.recordSize();
        }
        for (std::size_t k = 0; k < contacts_.size(); ++k) {
          const ContactPoint& c = contacts_[k];
          const contact_model::Contact con =
              contact_model::makeContact(a, b, c.point, c.normal, c.weight * c.penetration,
                                         model_.rolling() != nullptr);
          const contact_model::ContactForces out =
              model_.evaluate(con, slots ? slots + k * std::size_t(stride) : nullptr, dt);
          dynamics::applyContactForce(a, b, c.point, out.forceOnFirst, loads[i], loads[j]);
          loads[i].torque += out.torqueOnFirst;  // rolling: a couple, the second gets -tau
          loads[j].torque -= out.torqueOnFirst;
          report.largestPenetration = std::max(report.largestPenetration, c.penetration);
        }
        report.contacts += contacts_.size();
      }
    histories_ = std::move(nextHistories);
    for (std::size_t i = 0; i < particles.size(); ++i) {
      dynamics::RigidBody& body = particles[i].body;
      if (body.isFixed()) continue;
      Eigen::Vector3d f = loads[i].force + body.mass() * gravity_, tau = loads[i].torque;
      const auto ext = external_.find(i);
      if (ext != external_.end()) f += ext->second.force, tau += ext->second.torque;
      body.kick(f, tau, dt);
      body.drift(dt);
    }
    return report;
  }

 private:
  contact::MeshContactFinder finder_;
  const contact_model::ContactModel& model_;
  Eigen::Vector3d gravity_;
  std::map<std::size_t, dynamics::BodyLoad> external_;
  std::map<std::pair<std::size_t, std::size_t>, std::vector<double>> histories_;
  std::vector<contact::ContactPoint> contacts_;
  contact_model::ContactHistoryMatcher matcher_;
};

}  // namespace spacetree::testing
