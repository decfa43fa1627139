#include "contact/MeshContact.h"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/PointTriangleDistance.h"

namespace spacetree::contact {

using Eigen::Matrix3d;
using Eigen::Vector3d;
using geometry::Triangle;

TriangleDistanceMethod parseTriangleDistanceMethod(const std::string& name) {
  if (name == "exact") return TriangleDistanceMethod::Exact;
  if (name == "penalty") return TriangleDistanceMethod::Penalty;
  if (name == "hybrid") return TriangleDistanceMethod::Hybrid;
  throw std::invalid_argument("unknown triangle distance method '" + name +
                              "' (expected exact, penalty or hybrid)");
}

const char* triangleDistanceMethodName(TriangleDistanceMethod method) {
  switch (method) {
    case TriangleDistanceMethod::Exact: return "exact";
    case TriangleDistanceMethod::Penalty: return "penalty";
    case TriangleDistanceMethod::Hybrid: return "hybrid";
  }
  return "?";
}

MeshContactStatistics& MeshContactStatistics::operator+=(const MeshContactStatistics& o) {
  bodyPairs += o.bodyPairs;
  boundingSphereRejections += o.boundingSphereRejections;
  boundingBoxRejections += o.boundingBoxRejections;
  approachRejections += o.approachRejections;
  trianglePairsPruned += o.trianglePairsPruned;
  trianglePairsChecked += o.trianglePairsChecked;
  fallbacks += o.fallbacks;
  continued += o.continued;
  rawContacts += o.rawContacts;
  nonMinimumContacts += o.nonMinimumContacts;
  contacts += o.contacts;
  return *this;
}

bool boundingSpheresWithinContactDistance(const geometry::RigidShape& first, const Pose& firstPose,
                                          const geometry::RigidShape& second,
                                          const Pose& secondPose, double epsilon) {
  const double reach = first.boundingRadius + second.boundingRadius + 2.0 * epsilon;
  return (secondPose.position - firstPose.position).squaredNorm() < reach * reach;
}

int newtonIterationsOf(const MeshContactOptions& options) {
  if (options.newtonIterations > 0) return options.newtonIterations;
  switch (options.method) {
    case TriangleDistanceMethod::Exact: return 0;
    case TriangleDistanceMethod::Penalty: return geometry::PenaltyOptions{}.newtonIterations;
    case TriangleDistanceMethod::Hybrid: return geometry::HybridOptions{}.newtonIterations;
  }
  return 0;
}

int continuationIterationsOf(const MeshContactOptions& options) {
  return options.method == TriangleDistanceMethod::Hybrid ? options.continuationIterations : 0;
}

void validateMeshContactOptions(const MeshContactOptions& options) {
  if (options.newtonIterations < 0)
    throw std::invalid_argument("MeshContactOptions: newtonIterations must be >= 0 (0 = default)");
  if (options.continuationIterations < 0)
    throw std::invalid_argument("MeshContactOptions: continuationIterations must be >= 0");
  if (newtonIterationsOf(options) + continuationIterationsOf(options) >
      geometry::kMaxNewtonIterations)
    throw std::invalid_argument(
        "MeshContactOptions: newtonIterations + continuationIterations (hybrid) must be <= " +
        std::to_string(geometry::kMaxNewtonIterations));
}

MeshContactFinder::MeshContactFinder(MeshContactOptions options) : options_(std::move(options)) {
  validateMeshContactOptions(options_);
}

namespace {

Vector3d outwardUnitNormal(const Triangle& t) {
  const Vector3d n = (t[1] - t[0]).cross(t[2] - t[0]);
  const double norm = n.norm();
  return norm > 0.0 ? Vector3d(n / norm) : Vector3d::Zero();
}

bool isNearVertex(const Vector3d& p, const Triangle& t, double tolerance) {
  for (int k = 0; k < 3; ++k)
    if ((p - t[k]).squaredNorm() <= tolerance * tolerance) return true;
  return false;
}

bool isInsideFace(const Vector3d& p, const Triangle& t, double tolerance) {
  for (int k = 0; k < 3; ++k) {
    const Vector3d edge = t[(k + 1) % 3] - t[k];
    const double length = edge.norm();
    if (!(edge.cross(p - t[k]).norm() > tolerance * length)) return false;  // on edge k's line
  }
  return true;
}

// Normal (first -> second, not normalised) of two touching triangles from their contact
// features: a vertex of one touching the other (on its face or an edge) takes the other's face
// normal; a point inside a face (an edge piercing it) takes that face's normal; otherwise
// (edge on edge, vertex on vertex) the difference of the outward normals.
Vector3d touchingNormal(const geometry::TriangleDistanceResult& r, const Triangle& first,
                        const Triangle& second, double tolerance) {
  const Vector3d firstNormal = outwardUnitNormal(first), secondNormal = outwardUnitNormal(second);
  const bool firstVertex = isNearVertex(r.pointOnFirst, first, tolerance);
  const bool secondVertex = isNearVertex(r.pointOnSecond, second, tolerance);
  if (firstVertex && !secondVertex) return -secondNormal;
  if (secondVertex && !firstVertex) return firstNormal;
  if (!firstVertex && !secondVertex) {
    if (isInsideFace(r.pointOnSecond, second, tolerance)) return -secondNormal;
    if (isInsideFace(r.pointOnFirst, first, tolerance)) return firstNormal;
  }
  return firstNormal - secondNormal;
}

// Height of vertex v above `face` (unit outward normal n) if v lies over the closed face within
// [0, contactDistance) of its plane, else -1. The tolerance admits a projection on an edge.
double heightOverFace(const Vector3d& v, const Triangle& face, const Vector3d& n,
                      double contactDistance, double tolerance) {
  const double h = n.dot(v - face[0]);
  if (!(h >= 0.0 && h < contactDistance)) return -1.0;
  const Vector3d q = v - h * n;
  for (int k = 0; k < 3; ++k) {
    const Vector3d edge = face[(k + 1) % 3] - face[k];
    if (edge.cross(q - face[k]).dot(n) < -tolerance * edge.norm()) return -1.0;
  }
  return h;
}

// Relative slack of the culls of step 3 beyond the bounding spheres: a cull drops a triangle
// or pair only when it is farther than its reach by this fraction of the scales involved, far
// above the rounding of the frame change and of the distances (~1e-16 of them).
constexpr double kCullSlack = 1e-9;

// Whether a sphere (centre p in `shape`'s body frame, radius reach) stays clear of the shape's
// bounding box: then no point of the sphere is within reach of the shape's surface.
bool clearOfBox(const Vector3d& p, const geometry::RigidShape& shape, double reach) {
  const Vector3d below = (shape.boundingBoxLow - p).cwiseMax(0.0);
  const Vector3d above = (p - shape.boundingBoxHigh).cwiseMax(0.0);
  const double extent = (shape.boundingBoxHigh - shape.boundingBoxLow).norm();
  const double limit = reach + kCullSlack * (reach + p.norm() + extent);
  return (below + above).squaredNorm() > limit * limit;
}

// Whether triangle t (radius r about its centroid) stays farther than reach from point p: its
// true distance, for triangles too large for their bounding sphere to say so.
bool clearOfPoint(const Vector3d& p, const Triangle& t, double r, double reach) {
  const double limit = reach + kCullSlack * (reach + r);
  return geometry::pointTriangleSquaredDistance(p, t) > limit * limit;
}

// Calls body(i) for the given candidate triangles of `shape`, or for all of them (nullptr).
template <class Body>
void forEachTriangle(const geometry::RigidShape& shape, const std::vector<int>* candidates,
                     Body&& body) {
  if (candidates)
    for (int i : *candidates) body(std::size_t(i));
  else
    for (std::size_t i = 0; i < shape.triangleCount(); ++i) body(i);
}

}  // namespace

// Second body in the first body's frame: x_1 = rotation * x_2 + shift.
struct MeshContactFinder::PairFrame {
  PairFrame(const geometry::RigidShape& first, const Pose& firstPose,
            const geometry::RigidShape& second, const Pose& secondPose, double contactDistance)
      : contactDistance(contactDistance),
        firstRotation(firstPose.orientation.toRotationMatrix()),
        rotation(firstRotation.transpose() * secondPose.orientation.toRotationMatrix()),
        inverseRotation(rotation.transpose()),
        shift(firstRotation.transpose() * (secondPose.position - firstPose.position)),
        firstCentreInSecond(-(inverseRotation * shift)),
        sphereGap(shift.norm() - first.boundingRadius - second.boundingRadius) {}

  double contactDistance;        // 2 eps
  Matrix3d firstRotation;        // first body frame -> world
  Matrix3d rotation;             // second body frame -> first body frame
  Matrix3d inverseRotation;      // first body frame -> second body frame
  Vector3d shift;                // the second centre in the first frame
  Vector3d firstCentreInSecond;  // the first centre in the second frame
  double sphereGap;              // centre distance - both bounding radii
};

std::size_t MeshContactFinder::find(const geometry::RigidShape& first, const Pose& firstPose,
                                    const geometry::RigidShape& second, const Pose& secondPose,
                                    std::vector<ContactPoint>& contacts,
                                    MeshContactStatistics* statistics) {
  const double eps = options_.epsilon;
  if (!(eps > 0.0)) throw std::invalid_argument("MeshContactFinder: epsilon must be > 0");
  MeshContactStatistics counts;
  counts.bodyPairs = 1;
  const PairFrame frame(first, firstPose, second, secondPose, 2.0 * eps);
  const std::size_t begin = contacts.size();
  if (!rejectBodyPair(first, firstPose, second, secondPose, frame, counts)) {
    selectNearTriangles(first, second, frame);
    pairNearTriangles(first, second, frame, counts);
    computeDistances(frame.contactDistance, counts);
    collectRawContacts(first, second, frame, counts);
    mergeDuplicates(first, second, contacts);
    // To the world frame.
    for (std::size_t k = begin; k < contacts.size(); ++k) {
      contacts[k].point = frame.firstRotation * contacts[k].point + firstPose.position;
      contacts[k].normal = frame.firstRotation * contacts[k].normal;
    }
  }
  counts.contacts = contacts.size() - begin;
  if (statistics) *statistics += counts;
  return counts.contacts;
}

bool MeshContactFinder::rejectBodyPair(const geometry::RigidShape& first, const Pose& firstPose,
                                       const geometry::RigidShape& second,
                                       const Pose& secondPose, const PairFrame& frame,
                                       MeshContactStatistics& counts) const {
  if (!(frame.sphereGap < frame.contactDistance)) {
    ++counts.boundingSphereRejections;
    return true;
  }
  // Each body's bounding sphere against the other's bounding box (a grain far from a slab
  // obstacle whose bounding sphere holds it).
  if (options_.triangleCulling &&
      (clearOfBox(frame.shift, first, second.boundingRadius + frame.contactDistance) ||
       clearOfBox(frame.firstCentreInSecond, second,
                  first.boundingRadius + frame.contactDistance))) {
    ++counts.boundingBoxRejections;
    return true;
  }
  if (options_.approachPrecheck &&
      !options_.approachPrecheck(firstPose, secondPose, frame.sphereGap)) {
    ++counts.approachRejections;
    return true;
  }
  return false;
}

// With an index: its candidates (a superset), ascending, through the same test as the loop
// over all triangles.
const std::vector<int>* MeshContactFinder::indexCandidates(const geometry::RigidShape& shape,
                                                           const Vector3d& q, double radius) {
  const bool indexed = shape.triangleCount() >= kTriangleIndexMinimum ||
                       shape.boundingRadius > kTriangleIndexRadiusRatio * radius;
  if (!options_.triangleIndex || !indexed || shape.triangleIndex.size() != shape.triangleCount())
    return nullptr;
  candidates_.clear();
  shape.triangleIndex.forEachCandidate(q, radius, [&](int i) { candidates_.push_back(i); });
  std::sort(candidates_.begin(), candidates_.end());
  return &candidates_;
}

// Triangles of each body whose bounding sphere reaches the other body's bounding sphere. The
// second body's index query point is the first's centre in the second's frame,
// -rotation^T shift (rotation orthogonal to rounding; else the plain loop). Culls beyond the
// bounding spheres (options_.triangleCulling): a triangle must also reach the other body's box,
// and a triangle larger than the other body must reach its bounding sphere by its true
// distance (a coarse obstacle's big faces).
void MeshContactFinder::selectNearTriangles(const geometry::RigidShape& first,
                                            const geometry::RigidShape& second,
                                            const PairFrame& frame) {
  const double contactDistance = frame.contactDistance;
  const Matrix3d& rotation = frame.rotation;
  const Vector3d& shift = frame.shift;
  const bool cull = options_.triangleCulling;
  nearFirst_.clear();
  nearSecond_.clear();
  forEachTriangle(first, indexCandidates(first, shift, second.boundingRadius + contactDistance),
                  [&](std::size_t i) {
    const double r = first.triangleRadii[i];
    const double reach = r + second.boundingRadius + contactDistance;
    const Vector3d& c = first.triangleCentres[i];
    if (!((c - shift).squaredNorm() < reach * reach)) return;
    if (cull) {
      if (clearOfBox(frame.inverseRotation * (c - shift), second, r + contactDistance)) return;
      if (r > second.boundingRadius &&
          clearOfPoint(shift, first.bodyTriangles[i], r, second.boundingRadius + contactDistance))
        return;
    }
    nearFirst_.push_back(int(i));
  });
  secondCentres_.clear();
  const bool orthogonal =
      (rotation.transpose() * rotation - Matrix3d::Identity()).cwiseAbs().maxCoeff() < 1e-12;
  const std::vector<int>* secondCandidates =
      orthogonal ? indexCandidates(second, frame.firstCentreInSecond,
                                   first.boundingRadius + contactDistance)
                 : nullptr;
  forEachTriangle(second, secondCandidates, [&](std::size_t j) {
    const double r = second.triangleRadii[j];
    const Vector3d centre = rotation * second.triangleCentres[j] + shift;
    const double reach = r + first.boundingRadius + contactDistance;
    if (!(centre.squaredNorm() < reach * reach)) return;
    if (cull) {
      if (clearOfBox(centre, first, r + contactDistance)) return;
      if (r > first.boundingRadius &&
          clearOfPoint(frame.firstCentreInSecond, second.bodyTriangles[j], r,
                       first.boundingRadius + contactDistance))
        return;
    }
    nearSecond_.push_back(int(j));
    secondCentres_.push_back(centre);
  });
  secondTriangles_.clear();
  for (int j : nearSecond_) {
    const Triangle& t = second.bodyTriangles[std::size_t(j)];
    secondTriangles_.emplace_back(rotation * t[0] + shift, rotation * t[1] + shift,
                                  rotation * t[2] + shift);
  }
}

// Every near triangle of the first body with every near triangle of the second whose spheres
// come within 2 eps, and (culling) each triangle's sphere within 2 eps of the other triangle.
void MeshContactFinder::pairNearTriangles(const geometry::RigidShape& first,
                                          const geometry::RigidShape& second,
                                          const PairFrame& frame, MeshContactStatistics& counts) {
  const double contactDistance = frame.contactDistance;
  const bool cull = options_.triangleCulling;
  pairFirst_.clear();
  pairSecond_.clear();
  pairIndex_.clear();
  for (int i : nearFirst_) {
    const Vector3d& centre = first.triangleCentres[std::size_t(i)];
    const double ri = first.triangleRadii[std::size_t(i)];
    const Triangle& ti = first.bodyTriangles[std::size_t(i)];
    for (std::size_t k = 0; k < nearSecond_.size(); ++k) {
      const double rk = second.triangleRadii[std::size_t(nearSecond_[k])];
      const double reach = ri + rk + contactDistance;
      if (!((centre - secondCentres_[k]).squaredNorm() < reach * reach)) continue;
      // Each triangle's sphere against the other triangle itself (the larger one first).
      if (cull) {
        const bool firstLarger = ri >= rk;
        if (firstLarger ? clearOfPoint(secondCentres_[k], ti, ri, rk + contactDistance)
                        : clearOfPoint(centre, secondTriangles_[k], rk, ri + contactDistance))
          continue;
        if (firstLarger ? clearOfPoint(centre, secondTriangles_[k], rk, ri + contactDistance)
                        : clearOfPoint(secondCentres_[k], ti, ri, rk + contactDistance))
          continue;
      }
      pairFirst_.push_back(ti);
      pairSecond_.push_back(secondTriangles_[k]);
      pairIndex_.push_back({i, int(k)});
    }
  }
  counts.trianglePairsChecked = pairFirst_.size();
  counts.trianglePairsPruned = first.triangleCount() * second.triangleCount() - pairFirst_.size();
}

void MeshContactFinder::computeDistances(double contactDistance, MeshContactStatistics& counts) {
  const std::size_t pairs = pairFirst_.size();
  results_.resize(pairs);
  switch (options_.method) {
    case TriangleDistanceMethod::Exact:
      geometry::triangleDistances(pairFirst_.data(), pairSecond_.data(), pairs, results_.data());
      break;
    case TriangleDistanceMethod::Penalty: {
      geometry::PenaltyOptions penalty;
      penalty.newtonIterations = newtonIterationsOf(options_);
      geometry::penaltyTriangleDistances(pairFirst_.data(), pairSecond_.data(), pairs, penalty,
                                         results_.data());
      break;
    }
    case TriangleDistanceMethod::Hybrid: {
      geometry::HybridOptions hybrid;
      hybrid.contactDistance = contactDistance;
      hybrid.newtonIterations = newtonIterationsOf(options_);
      hybrid.continuationIterations = continuationIterationsOf(options_);
      hybrid.clipLargeTriangles = options_.clipLargeTriangles;
      geometry::HybridStatistics hybridCounts;
      geometry::hybridTriangleDistances(pairFirst_.data(), pairSecond_.data(), pairs, hybrid,
                                        results_.data(), &hybridCounts);
      counts.fallbacks = hybridCounts.fallbacks();
      counts.continued = hybridCounts.continued;
      // Its contact points: the exact method's closest points for the pairs in contact. The
      // hybrid certifies distances and contact decisions, not where its Newton iterate stops
      // among equally close points: for two (nearly) parallel faces that set is a whole region,
      // and a point wandering over it moves the lever arm of the force (a cube resting on a
      // face rocked without end). The exact method picks the closest features consistently.
      for (std::size_t p = 0; p < pairs; ++p)
        if (results_[p].distance < contactDistance)
          results_[p] = geometry::triangleDistance(pairFirst_[p], pairSecond_[p]);
      break;
    }
  }
}

void MeshContactFinder::collectRawContacts(const geometry::RigidShape& first,
                                           const geometry::RigidShape& second,
                                           const PairFrame& frame, MeshContactStatistics& counts) {
  const double eps = options_.epsilon;
  const std::size_t pairs = pairFirst_.size();
  raw_.clear();
  for (std::size_t p = 0; p < pairs; ++p) {
    const geometry::TriangleDistanceResult& r = results_[p];
    if (!(r.distance < frame.contactDistance)) continue;
    addVertexContacts(p);
    addEdgeCrossingContacts(first, second, p);
    ContactPoint c;
    c.point = 0.5 * (r.pointOnFirst + r.pointOnSecond);
    c.distance = r.distance;
    c.penetration = eps - 0.5 * r.distance;
    c.firstTriangle = pairIndex_[p][0];
    c.secondTriangle = nearSecond_[std::size_t(pairIndex_[p][1])];
    const double h = std::max(pairFirst_[p].longestEdge(), pairSecond_[p].longestEdge());
    Vector3d direction = r.pointOnSecond - r.pointOnFirst;
    if (r.distance > kDirectionTolerance * h && options_.localMinimaOnly) {
      const Vector3d u = direction / r.distance;
      const double tolerance = kDirectionTolerance * h;
      if (!isLocalMinimum(first, c.firstTriangle, r.pointOnFirst, u, Matrix3d::Identity(),
                          Vector3d::Zero(), tolerance) ||
          !isLocalMinimum(second, c.secondTriangle, r.pointOnSecond, -u, frame.rotation,
                          frame.shift, tolerance)) {
        ++counts.nonMinimumContacts;
        continue;
      }
    }
    if (!(r.distance > kDirectionTolerance * h)) {
      direction = touchingNormal(r, pairFirst_[p], pairSecond_[p], kDirectionTolerance * h);
      if (!(direction.squaredNorm() > 1e-12)) direction = frame.shift;
      if (!(direction.squaredNorm() > 0.0)) direction = Vector3d::UnitX();
    }
    c.normal = direction.normalized();
    raw_.push_back(c);
  }
  counts.rawContacts = raw_.size();
}

// Penetration-weighted running means of close contacts with close normals (ContactMerging.h).
void MeshContactFinder::mergeDuplicates(const geometry::RigidShape& first,
                                        const geometry::RigidShape& second,
                                        std::vector<ContactPoint>& contacts) {
  // half the shortest edge: the vertex contacts of a face resting on a face (4b) stay apart
  merger_.merge(raw_, 0.5 * std::min(first.minimumEdgeLength, second.minimumEdgeLength), options_,
                contacts);
}

namespace {

// Sine of the angle up to which an edge counts as lying on a face (4b'): resting contacts tilt
// an edge by up to ~eps / edge length; the creases of a 40-triangle grain turn by ~30 degrees.
constexpr double kLyingSlope = 0.0872;  // sin 5 degrees

enum class Crease { Flat, Convex, Concave };

// How the surface bends across edge k of triangle t (body frame, frame-independent): convex
// when the neighbour's apex lies below the triangle's plane (inside the body) by more than
// kFeatureTolerance of its distance, concave when above, flat otherwise (e.g. a box face's
// diagonal). An edge without a neighbour (an open surface's border) ends the surface: convex.
Crease creaseOf(const geometry::RigidShape& shape, int t, int k) {
  const int apex = shape.edgeApex[std::size_t(t)][std::size_t(k)];
  if (apex < 0) return Crease::Convex;
  const Triangle& tri = shape.bodyTriangles[std::size_t(t)];
  const Vector3d n = outwardUnitNormal(tri);
  const Vector3d step = shape.bodyMesh.vertices[std::size_t(apex)] - tri[k];
  const double rise = n.dot(step);
  if (rise < -kFeatureTolerance * step.norm()) return Crease::Convex;
  if (rise > kFeatureTolerance * step.norm()) return Crease::Concave;
  return Crease::Flat;
}

}  // namespace

// Step (4b'): the ends of an edge's part over the other triangle's face. A convex edge of one
// body (a ridge) lying on the other's face touches along a segment; where the segment leaves
// the face over a crease of the face's border, the contact region has a corner that is neither
// body's vertex, so (4b) misses it, and the kernel gives one point per triangle pair: the
// lower end, which under a tilt of 1e-7 jumps to the other end and back. A grain resting on
// such a ridge was held at one end at a time and rocked without end (a pile of dented grains
// kept ~1e-8 of its peak kinetic energy, bench/resting_energy.cpp). With both ends it rests.
// Each end within the contact distance of the face's plane is a contact along the face normal,
// like a vertex contact; the kernel's own point at an end is merged with it (6). Flat edges (a
// face's diagonal) bound no region: they give none. Nor does an end where the edge, leaving the
// face, comes down towards the face's plane by more than kLyingSlope: the edge is then tilted
// onto that end and comes closest to the border crease beyond it (the kernel's contact), or the
// face is a slope next to the face the edge lies on (its end would push sideways).
void MeshContactFinder::addEdgeCrossingContacts(const geometry::RigidShape& first,
                                                const geometry::RigidShape& second, std::size_t p) {
  const double eps = options_.epsilon, contactDistance = 2.0 * eps;
  const int triangle[2] = {pairIndex_[p][0], nearSecond_[std::size_t(pairIndex_[p][1])]};
  const geometry::RigidShape* shape[2] = {&first, &second};
  const Triangle* tri[2] = {&pairFirst_[p], &pairSecond_[p]};
  for (int side = 0; side < 2; ++side) {
    const Triangle& edges = *tri[side];
    const Triangle& face = *tri[1 - side];
    const Vector3d faceNormal = outwardUnitNormal(face);
    if (!(faceNormal.squaredNorm() > 0.0)) continue;
    for (int k = 0; k < 3; ++k) {
      if (creaseOf(*shape[side], triangle[side], k) != Crease::Convex) continue;
      // the edge a + t (b - a), t in [0, 1], clipped to the prism over the face: inside(t) >= 0
      // for each border line of the face
      const Vector3d& a = edges[k];
      const Vector3d d = edges[(k + 1) % 3] - a;
      double low = 0.0, high = 1.0;
      int lowBorder = -1, highBorder = -1;
      for (int m = 0; m < 3 && low <= high; ++m) {
        const Vector3d border = face[(m + 1) % 3] - face[m];
        const Vector3d inward = faceNormal.cross(border);
        const double at = inward.dot(a - face[m]), slope = inward.dot(d);
        if (slope == 0.0) {
          if (at < 0.0) low = 2.0;  // parallel and outside
          continue;
        }
        const double t = -at / slope;
        if (slope > 0.0 && t > low) low = t, lowBorder = m;
        if (slope < 0.0 && t < high) high = t, highBorder = m;
      }
      if (!(low <= high)) continue;
      const double ends[2] = {low, high};
      const int borders[2] = {lowBorder, highBorder};
      for (int e = 0; e < 2; ++e) {
        if (borders[e] < 0) continue;  // an end of the edge itself: a vertex contact (4b)
        if (creaseOf(*shape[1 - side], triangle[1 - side], borders[e]) == Crease::Flat) continue;
        // leaving the prism (t decreasing at the low end) the edge must not come down towards
        // the face's plane: else it comes closer to the border crease beyond, and that closest
        // approach, not this point, is the contact (the kernel's)
        const double leaving = (e == 0 ? -1.0 : 1.0) * faceNormal.dot(d) / d.norm();
        if (leaving < -kLyingSlope) continue;
        const Vector3d x = a + ends[e] * d;
        const double h = faceNormal.dot(x - face[0]);
        if (!(h >= 0.0 && h < contactDistance)) continue;
        ContactPoint c;
        c.point = x - 0.5 * h * faceNormal;
        c.normal = side == 0 ? Vector3d(-faceNormal) : faceNormal;
        c.distance = h;
        c.penetration = eps - 0.5 * h;
        c.firstTriangle = triangle[0];
        c.secondTriangle = triangle[1];
        raw_.push_back(c);
      }
    }
  }
}

// Step (4b): the vertices of either triangle of a pair in contact that lie over the other's face
// within the contact distance, each a contact (vertex on face) of its own. The kernel gives one
// closest pair per triangle pair; for two faces lying on each other (a grain resting on a face,
// a box on a floor) that is one corner of the region where they are equally close, and under
// the slightest tilt only the lowest one, so a face on a face was held at one or two points and
// rocked. With its corners the face is held where it rests. For a vertex touching a face the
// added contact is the kernel's own (merged by the de-duplication).
void MeshContactFinder::addVertexContacts(std::size_t p) {
  const double eps = options_.epsilon, contactDistance = 2.0 * eps;
  const Triangle& a = pairFirst_[p];
  const Triangle& b = pairSecond_[p];
  const int firstTriangle = pairIndex_[p][0];
  const int secondTriangle = nearSecond_[std::size_t(pairIndex_[p][1])];
  const double tolerance = kDirectionTolerance * std::max(a.longestEdge(), b.longestEdge());
  const Vector3d na = outwardUnitNormal(a), nb = outwardUnitNormal(b);
  for (int side = 0; side < 2; ++side) {
    const Triangle& vertices = side == 0 ? a : b;
    const Triangle& face = side == 0 ? b : a;
    const Vector3d& faceNormal = side == 0 ? nb : na;
    if (!(faceNormal.squaredNorm() > 0.0)) continue;
    for (int k = 0; k < 3; ++k) {
      const Vector3d& v = vertices[k];
      const double h = heightOverFace(v, face, faceNormal, contactDistance, tolerance);
      if (h < 0.0) continue;
      // first -> second: down onto the second's face, or up from the first's face. No
      // local-minimum filter (5b): under a tilt of 1e-7 the corners of a face lying on another
      // are not local minima of the distance, yet lie in the halo like the lowest one; and the
      // force along the face normal pushes nothing sideways.
      const Vector3d normal = side == 0 ? Vector3d(-faceNormal) : faceNormal;
      ContactPoint c;
      c.point = v - 0.5 * h * faceNormal;  // halfway between the vertex and the face
      c.normal = normal;
      c.distance = h;
      c.penetration = eps - 0.5 * h;
      c.firstTriangle = firstTriangle;
      c.secondTriangle = secondTriangle;
      raw_.push_back(c);
    }
  }
}

}  // namespace spacetree::contact
