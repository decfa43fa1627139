// Contacts between two posed rigid triangulated particles (paper §3 and §6.2).
//
// Convention (paper §3, "epsilon formalism"): each particle carries a soft halo of depth eps
// around its rigid surface. Two triangles whose distance d is below 2 eps yield a contact:
//   - point:  the midpoint of their shortest segment (halfway between the two surfaces);
//   - normal: unit vector along that segment, from the first body's surface towards the second's
//             (n_ij of eq. (1) is normal * |n|, pointing from the contact point onto the surface
//             of body j = second);
//   - |n| = d / 2, the distance from the contact point to either surface (|n| <= eps);
//   - penetration = eps - |n| = eps - d / 2 in (0, eps]: the halo overlap that the spring of
//     eq. (1) acts on. A penetration of eps means the rigid surfaces touch (d = 0); more than
//     eps cannot be represented (the bodies have interpenetrated, which a small enough time
//     step prevents).
// For d = 0 (touching or intersecting triangles) the segment has no direction; the normal is
// then taken from the contact features: a vertex of one triangle touching the other triangle
// takes that triangle's outward normal (negated when it belongs to the second body); a point
// inside a face (an edge piercing the face) takes that face's normal; otherwise (edge on edge,
// vertex on vertex) nA - nB, the difference of the outward normals (A's points towards B, B's
// towards A); if that vanishes, the direction from the first centre to the second. The same
// rule applies below kDirectionTolerance * h (h: longest edge of the pair), where the segment's
// direction is dominated by rounding.
//
// Pipeline per body pair: (1) bounding spheres (radius about the centre of mass) farther apart
// than 2 eps, or one body's bounding sphere farther than 2 eps from the other's bounding box
// (body frame): no contact; (2) optional approach precheck hook (e.g. bodies separating fast
// enough to stay apart) may skip the pair; (3) triangle pruning: a triangle of one body is
// kept only if its bounding sphere reaches within 2 eps of the other body's bounding sphere
// and of its bounding box (body frame), and, when the triangle is larger than the other body,
// if the triangle itself comes within that body's bounding radius + 2 eps of its centre; a
// pair of kept triangles only if their spheres are within 2 eps and each triangle's sphere
// comes within 2 eps of the other triangle itself. Every test is conservative (a surface point
// within 2 eps of the other surface passes all of them), so no contact is lost: a coarse
// obstacle's big triangles meet only the grain triangles that face them, and about half of the
// triangle pairs of two grains in contact are dropped before the distance kernel. For an
// indexed shape
// (kTriangleIndexMinimum triangles, or kTriangleIndexRadiusRatio times the other body) the
// candidates come from its TriangleBvh, queried with the other body's bounding sphere in this
// shape's frame, and pass the same tests as in the loop over all triangles, in ascending
// order: the same set, the same contacts, bit for bit; (4) the
// surviving triangle pairs go to the chosen distance method in one batch (Exact:
// triangleDistance; Penalty: the batched penalty-Newton kernel, uncertified; Hybrid: penalty
// with certified fallback, contact decisions identical to Exact's; by default two-stage:
// uncertified pairs continue continuationIterations more Newton steps before the fallback); the
// hybrid's pairs in contact get the exact method's closest points (it certifies distances, not
// where among equally close points its iterate stops: over two parallel faces that point
// wandered and moved the lever arm of the force); (4b) vertex contacts: every vertex of either
// triangle of a pair in contact that lies over the other triangle's face within 2 eps is a
// contact of its own (a face lying on a face is held at its corners, not at the one closest
// point the kernel gives per triangle pair, which under the slightest tilt is the lowest corner
// only); (5) contacts (d < 2 eps);
// (5b) local-minimum filter: a triangle-pair contact whose closest point lies on an edge or a
// vertex of its triangle is dropped when a neighbouring triangle across that edge (around that
// vertex) descends towards the other body (u . (w - p) > kFeatureTolerance |w - p|, u the unit
// direction to the other body, w the neighbour's vertex): such a pair is not a local minimum
// of the surface distance, a neighbouring pair is strictly closer and yields the true contact
// (so nothing is lost). It removes, e.g., the slanted edge-edge contacts of a flat face's
// interior diagonal, which would push a particle resting on a floor sideways;
// (6) de-duplication (paper §3, step 2): a contact is averaged into an earlier one when its
// point is closer than half the smaller of the two particles' minimum edge lengths to that
// contact's mean point and the normals' cosine is at least mergeNormalCosine. Typical
// duplicates: a vertex touching a face is found once per triangle around the vertex. (The
// paper's full edge length merged the corners of a face - an edge apart, within rounding -
// into one point at a corner: a cube on a floor was held at a corner and rocked.) The
// average (point, unit normal, penetration) is weighted by the penetrations, not plain as in
// the paper: a triangle pair that just enters the 2 eps band has weight 0, so the merged force
// changes continuously (with plain averaging, a slanted contact entering the band - e.g. one
// that the filter (5b) is switched off for - tilted the merged normal of a resting particle by
// 1e-3 rad at once).
// Work is done in the first body's frame (only the second body's triangles near the first
// are transformed); contacts are returned in the world frame.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "contact/ContactMerging.h"
#include "geometry/HybridTriangleDistance.h"
#include "geometry/RigidShape.h"
#include "geometry/TriangleDistance.h"

namespace spacetree::contact {

enum class TriangleDistanceMethod { Exact, Penalty, Hybrid };

// "exact", "penalty", "hybrid" <-> enum; parse throws std::invalid_argument naming the word.
TriangleDistanceMethod parseTriangleDistanceMethod(const std::string& name);
const char* triangleDistanceMethodName(TriangleDistanceMethod method);

// Where a shape is: x_world = orientation * x_body + position (position = centre of mass).
struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
};

// Below this times the longest edge, a triangle distance counts as touching for the normal.
constexpr double kDirectionTolerance = 1e-9;
// Slope (sine) above which a neighbour triangle is taken to descend towards the other body.
constexpr double kFeatureTolerance = 1e-7;

// Shapes with at least this many triangles, or whose bounding radius exceeds this many times
// the query radius (the other body's bounding radius + 2 eps: an obstacle of few large
// triangles against a grain), are pruned through their TriangleBvh, the others by the loop
// over all triangles (a choice, not tuned; the result is the same either way).
constexpr std::size_t kTriangleIndexMinimum = 64;
constexpr double kTriangleIndexRadiusRatio = 4.0;

struct MeshContactOptions {
  double epsilon = 0.0;  // halo depth; contact when the triangle distance < 2 epsilon
  TriangleDistanceMethod method = TriangleDistanceMethod::Hybrid;
  // Penalty Newton steps: of the penalty method and of the hybrid's stage 1 (4 or 8 in the
  // paper). 0: the method's own default (PenaltyOptions: 8; HybridOptions: 5).
  int newtonIterations = 0;
  // Hybrid only: further Newton steps for the pairs stage 1 leaves uncertified (the two-stage
  // hybrid, HybridOptions::continuationIterations; same decisions as exact either way). 0: single
  // stage. Default: the core's (4). Stage 1 + stage 2 <= kMaxNewtonIterations (32).
  int continuationIterations = geometry::HybridOptions{}.continuationIterations;
  // Hybrid only: its scale-aware path for triangles of very different sizes
  // (HybridOptions::clipLargeTriangles; same decisions either way, fewer fallbacks with it).
  bool clipLargeTriangles = true;
  bool deduplicate = true;
  bool localMinimaOnly = true;     // drop contacts that are not local distance minima (5b)
  double mergeNormalCosine = 0.9;  // "reasonably close normals": within about 25 degrees
  // Prune through the shapes' TriangleBvh (step 3); false: loop over all triangles (the
  // reference the index is tested against; same contacts either way).
  bool triangleIndex = true;
  // Step 3's culls beyond the bounding spheres (the other body's box, true distances of large
  // triangles); false: bounding spheres only (the reference the culls are tested against;
  // same contacts either way).
  bool triangleCulling = true;
  // Optional hook after the bounding-sphere check: gets both poses and the gap between the
  // bounding spheres (centre distance - radii, may be negative); return false to skip the pair.
  // Only pairs that cannot have a contact now may be skipped: a pair in halo contact that is
  // separating still feels the spring S (eps - |n|) of eq. (1), so "not approaching" alone is
  // no reason to skip it here (the paper uses its approach check for grid refinement, §5).
  // Example: a caller that knows the surfaces were farther apart than 2 eps + v_max dt one
  // step ago can skip the triangle checks.
  std::function<bool(const Pose& first, const Pose& second, double sphereGap)> approachPrecheck;
};

struct ContactPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   // world frame
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX(); // unit, from first body towards second
  double distance = 0.0;     // surface distance d (|n| = d / 2)
  double penetration = 0.0;  // epsilon - d / 2
  int firstTriangle = -1;    // triangles of the first contact merged into this one
  int secondTriangle = -1;
  int mergedCount = 1;       // raw contacts averaged into this one
  // Contact points this one stands for (ContactMerger): the force laws act on the penetration
  // weight * penetration. 1 for a raw contact and for copies of one contact found on several
  // triangle pairs; up to the number of merged raw contacts when they lie apart.
  double weight = 1.0;
};

struct MeshContactStatistics {
  std::size_t bodyPairs = 0;
  std::size_t boundingSphereRejections = 0;
  std::size_t boundingBoxRejections = 0;  // a bounding sphere clear of the other's box
  std::size_t approachRejections = 0;
  std::size_t trianglePairsPruned = 0;   // rejected by triangle bounding spheres
  std::size_t trianglePairsChecked = 0;  // given to the distance method
  std::size_t fallbacks = 0;             // hybrid: pairs that fell back to the exact method
  std::size_t continued = 0;             // two-stage hybrid: pairs that ran stage 2
  std::size_t nonMinimumContacts = 0;    // dropped by the local-minimum filter (5b)
  std::size_t rawContacts = 0;           // contacts before de-duplication
  std::size_t contacts = 0;              // after de-duplication

  MeshContactStatistics& operator+=(const MeshContactStatistics& o);
};

// The Newton steps the options ask for, defaults resolved: of the penalty method or the hybrid's
// stage 1 (0 for exact), and of the hybrid's stage 2 (0 unless hybrid).
int newtonIterationsOf(const MeshContactOptions& options);
int continuationIterationsOf(const MeshContactOptions& options);

// Throws std::invalid_argument naming the field for newtonIterations or continuationIterations
// < 0, or more than kMaxNewtonIterations penalty steps (stage 1 + stage 2 for the hybrid).
// epsilon is checked by find() (a default-constructed finder may get it later).
void validateMeshContactOptions(const MeshContactOptions& options);

// Reusable contact search (owns scratch buffers: one per thread).
class MeshContactFinder {
 public:
  // Throws as validateMeshContactOptions.
  explicit MeshContactFinder(MeshContactOptions options);
  const MeshContactOptions& options() const { return options_; }

  // Appends the contacts of `first` at `firstPose` with `second` at `secondPose` to `contacts`
  // and returns how many were appended; statistics, if given, are accumulated. Throws
  // std::invalid_argument for epsilon <= 0.
  std::size_t find(const geometry::RigidShape& first, const Pose& firstPose,
                   const geometry::RigidShape& second, const Pose& secondPose,
                   std::vector<ContactPoint>& contacts, MeshContactStatistics* statistics = nullptr);

 private:
  // The two poses as the phases below use them (defined in MeshContact.cpp).
  struct PairFrame;

  // One function per phase of the pipeline above; each works on the scratch buffers below.
  // (1)-(2): whether the body pair is rejected whole (bounding spheres, bounding boxes, the
  // approach precheck hook); counts the rejection.
  bool rejectBodyPair(const geometry::RigidShape& first, const Pose& firstPose,
                      const geometry::RigidShape& second, const Pose& secondPose,
                      const PairFrame& frame, MeshContactStatistics& counts) const;
  // (3a): the triangles of each body that reach the other body -> nearFirst_, nearSecond_ (with
  // secondCentres_ and secondTriangles_, the second's in the first frame).
  void selectNearTriangles(const geometry::RigidShape& first, const geometry::RigidShape& second,
                           const PairFrame& frame);
  // The TriangleBvh candidates of `shape` within radius of q (ascending), or nullptr when the
  // shape is pruned by the loop over all its triangles.
  const std::vector<int>* indexCandidates(const geometry::RigidShape& shape,
                                          const Eigen::Vector3d& q, double radius);
  // (3b): the pairs of near triangles that may come within 2 eps -> pairFirst_, pairSecond_,
  // pairIndex_; counts the pairs checked and pruned.
  void pairNearTriangles(const geometry::RigidShape& first, const geometry::RigidShape& second,
                         const PairFrame& frame, MeshContactStatistics& counts);
  // (4): the chosen distance method on all pairs at once -> results_.
  void computeDistances(double contactDistance, MeshContactStatistics& counts);
  // (4b), (5), (5b): the pairs closer than 2 eps that are local distance minima, and the
  // vertices over the other triangle's face within 2 eps, as contacts in the first body's
  // frame -> raw_.
  void collectRawContacts(const geometry::RigidShape& first, const geometry::RigidShape& second,
                          const PairFrame& frame, MeshContactStatistics& counts);
  // (4b) for pair p: its vertex contacts -> raw_.
  void addVertexContacts(std::size_t pair);
  // (4b') for pair p: the ends of a convex edge's part over the other's face -> raw_.
  void addEdgeCrossingContacts(const geometry::RigidShape& first,
                               const geometry::RigidShape& second, std::size_t pair);
  // (6): raw_ merged into the contacts it appends to `contacts` (ContactMerger).
  void mergeDuplicates(const geometry::RigidShape& first, const geometry::RigidShape& second,
                       std::vector<ContactPoint>& contacts);

  MeshContactOptions options_;
  std::vector<int> nearFirst_, nearSecond_, candidates_;
  std::vector<Eigen::Vector3d> secondCentres_;
  std::vector<geometry::Triangle> secondTriangles_;
  std::vector<geometry::Triangle> pairFirst_, pairSecond_;
  std::vector<std::array<int, 2>> pairIndex_;
  std::vector<geometry::TriangleDistanceResult> results_;
  std::vector<ContactPoint> raw_;
  ContactMerger merger_;
};

// Whether the bounding spheres come within 2 epsilon (the first precheck).
bool boundingSpheresWithinContactDistance(const geometry::RigidShape& first, const Pose& firstPose,
                                          const geometry::RigidShape& second,
                                          const Pose& secondPose, double epsilon);

}  // namespace spacetree::contact
