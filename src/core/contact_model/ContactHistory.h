// The identity of a body pair's contact points from step to step, for sub-models that keep
// per-contact history (e.g. the tangential spring). The contact search de-duplicates its raw
// triangle-pair contacts into merged points whose triangle indices depend on the order of the
// merge, so a contact point is recognised by where it is instead: its point and normal in the
// frame of the pair's first body (rigid motion of the pair does not move them there).
//
// A record per contact point: anchor point (3), anchor normal (3), both in the first body's
// frame, then the model's historySize() doubles. match() pairs this step's contact points with
// the previous step's records in three passes:
//   1. nearest: pairs closer than `distance` whose normals have a cosine of at least
//      `normalCosine`, the closest first (ties by index), each record and point at most once;
//      the point inherits the record's history;
//   2. moved within its patch: a point left over takes a record left over whose normal is as
//      close (any distance), the closest first. A flat face resting on another is reported as a
//      point at a place the triangle distance picks among equally close ones, which may jump
//      from step to step; its contact goes on;
//   3. merged: a record still left over whose normal is as close to a matched point's adds its
//      history to the nearest such point (the de-duplication merged two contact points into one;
//      history values are extensive: a tangential spring's displacement, so the merged point
//      carries the force of both). A record with no such point is dropped (the contact opened;
//      its history had shrunk with its normal force anyway, e.g. the Coulomb cap of a spring).
// A point matched by none starts with zeros. The result depends only on positions, not on the
// order of the triangles or of the points (up to exact ties).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cstddef>
#include <vector>

#include "contact/MeshContact.h"

namespace spacetree::contact_model {

constexpr int kContactAnchorDoubles = 6;

struct ContactHistoryMatchOptions {
  // Largest distance [m] between a point and the record it continues. For mesh contacts half the
  // de-duplication length (smaller of the two shapes' minimum edge lengths): distinct merged
  // points are at least about that far apart, a point moves by |v| dt per step.
  double distance = 0.0;
  double normalCosine = 0.9;  // the merge's "reasonably close normals"
};

struct ContactHistoryMatchStatistics {
  std::size_t kept = 0;     // points that continued a record (passes 1 and 2)
  std::size_t moved = 0;    // of these, by pass 2
  std::size_t merged = 0;   // records added to a continuing point (pass 3)
  std::size_t started = 0;  // points that started with zeros
  std::size_t dropped = 0;  // records whose history ended
};

class ContactHistoryMatcher {
 public:
  ContactHistoryMatcher(int historySize, ContactHistoryMatchOptions options);
  int historySize() const { return historySize_; }
  // The match distance of the next match() calls (e.g. per body pair); >= 0.
  void setDistance(double distance);
  int recordSize() const { return kContactAnchorDoubles + historySize_; }

  // previous: previousCount records (recordSize() doubles each); current: this step's contact
  // points (elements with .point and .normal, world frame), firstBody: the pose of the pair's
  // first body. `next` is replaced by current.size() records in the order of `current`; it must
  // not hold `previous`.
  template <class Contacts>
  void match(const double* previous, std::size_t previousCount, const Contacts& current,
             const contact::Pose& firstBody, std::vector<double>& next,
             ContactHistoryMatchStatistics* statistics = nullptr) {
    const Eigen::Quaterniond toBody = firstBody.orientation.conjugate();
    points_.clear();
    normals_.clear();
    for (const auto& c : current) {
      points_.push_back(toBody * (c.point - firstBody.position));
      normals_.push_back(toBody * c.normal);
    }
    matchAnchors(previous, previousCount, next, statistics);
  }

 private:
  void matchAnchors(const double* previous, std::size_t previousCount, std::vector<double>& next,
                    ContactHistoryMatchStatistics* statistics);

  int historySize_;
  ContactHistoryMatchOptions options_;
  std::vector<Eigen::Vector3d> points_, normals_;
  struct Candidate {
    double distance;
    int current, previous;
  };
  std::vector<Candidate> candidates_;
  std::vector<int> matchOfCurrent_;
  std::vector<char> previousTaken_;
};

}  // namespace spacetree::contact_model
