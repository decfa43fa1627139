// Triangle-to-triangle distance: the exact geometric method, the batched penalty-Newton method
// and the hybrid, checked against independent implementations that are linked into the tests
// only (never into spacetree_core):
//   - CGAL 5.5 squared_distance(Triangle_3, Triangle_3), evaluated rigorously: interval
//     arithmetic, and exact rationals wherever the intervals cannot decide;
//   - FCL 0.7 TriangleDistance::triDistance (double precision), the fast bulk reference for
//     random pairs; wherever it and the method under test differ, CGAL decides.
// Errors are measured as |d - d_ref| / max(d_ref, h), h the longest edge of the pair: relative
// to the distance for separated pairs, relative to the triangle size for touching ones (a
// double-precision result cannot be relative to a distance of 1e-14 h).
#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "geometry/HybridTriangleDistance.h"
#include "geometry/PenaltyTriangleDistance.h"
#include "geometry/PointTriangleDistance.h"
#include "geometry/SphereMesh.h"
#include "geometry/TriangleDistance.h"
#include "geometry/TrianglePairSources.h"

#if SPACETREE_HAVE_TRIANGLE_ORACLES
#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/squared_distance_3.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/triangle_distance.h>
#endif

using namespace spacetree::geometry;
using Eigen::Vector3d;

namespace {

constexpr double kTolerance = 1e-10;  // required agreement, relative to max(d_ref, h)

struct TrianglePair {
  Triangle first, second;
};

double pairScale(const TrianglePair& p) {
  return std::max(p.first.longestEdge(), p.second.longestEdge());
}

double scaledError(double d, double reference, double h) {
  // Two coincident points (h = 0, reference = 0) allow no error at all.
  return std::abs(d - reference) / std::max({reference, h, 1e-300});
}

// ---------------------------------------------------------------------------------------------
// Pair generators. Every set is randomly rotated, scaled and moved, so that no coordinate is
// special; the oracle decides what the true distance is.
// ---------------------------------------------------------------------------------------------
class PairFactory {
 public:
  explicit PairFactory(unsigned seed) : rng_(seed) {}

  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  double logUniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  Vector3d inCube() { return {uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)}; }
  Vector3d unit() {
    Vector3d v;
    do v = inCube(); while (v.squaredNorm() > 1.0 || v.squaredNorm() < 1e-4);
    return v.normalized();
  }
  Eigen::Matrix3d rotation() {
    std::normal_distribution<double> n;
    return Eigen::Quaterniond(n(rng_), n(rng_), n(rng_), n(rng_)).normalized().toRotationMatrix();
  }
  Triangle randomTriangle() { return {inCube(), inCube(), inCube()}; }

  // Rigid motion plus scale of the whole pair (scale 1e-3 .. 1e3, offsets up to 1e3 sizes).
  TrianglePair place(TrianglePair p) {
    const Eigen::Matrix3d r = rotation();
    const double scale = logUniform(1e-3, 1e3);
    const Vector3d offset = inCube() * scale * logUniform(1e-2, 1e3);
    for (Triangle* t : {&p.first, &p.second})
      for (int i = 0; i < 3; ++i) (*t)[i] = r * (*t)[i] * scale + offset;
    return p;
  }

  std::mt19937_64& rng() { return rng_; }

 private:
  std::mt19937_64 rng_;
};

using PairGenerator = std::function<TrianglePair(PairFactory&)>;

// Offsets along a normal from exactly 0 over tiny to large, log-uniform.
double adversarialOffset(PairFactory& f) {
  const double r = f.uniform(0, 1);
  if (r < 0.1) return 0.0;
  return (r < 0.55 ? 1.0 : -1.0) * f.logUniform(1e-15, 1.0);
}

TrianglePair randomPair(PairFactory& f) {
  Triangle a = f.randomTriangle();
  const Vector3d shift = f.inCube() * f.uniform(0.0, 3.0);
  Triangle b = f.randomTriangle();
  for (int i = 0; i < 3; ++i) b[i] += shift;
  return {a, b};
}

// Parallel planes: B is A turned within its plane, slid and lifted along the normal.
TrianglePair parallelPair(PairFactory& f) {
  Triangle a = f.randomTriangle();
  const Vector3d n = (a[1] - a[0]).cross(a[2] - a[0]).normalized();
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(f.uniform(0, 6.3), n).toRotationMatrix();
  const Vector3d centroid = (a[0] + a[1] + a[2]) / 3.0;
  Vector3d slide = f.inCube() * f.uniform(0, 1.5);
  slide -= n * n.dot(slide);
  const Vector3d lift = n * adversarialOffset(f);
  Triangle b;
  for (int i = 0; i < 3; ++i) b[i] = centroid + turn * (a[i] - centroid) + slide + lift;
  return {a, b};
}

// Coplanar: as parallel but without lift, overlapping or just apart.
TrianglePair coplanarPair(PairFactory& f) {
  Triangle a = f.randomTriangle();
  const Vector3d u = (a[1] - a[0]).normalized();
  const Vector3d n = u.cross(a[2] - a[0]).normalized();
  const Vector3d v = n.cross(u);
  Triangle b;
  const Vector3d base = a[0] + (u * f.uniform(-1, 2) + v * f.uniform(-1, 2)) * 0.7;
  for (int i = 0; i < 3; ++i) b[i] = base + u * f.uniform(-1, 1) + v * f.uniform(-1, 1);
  return {a, b};
}

// Edge on edge: an edge of B crosses an edge of A (in projection) at a normal offset that is 0,
// tiny or large; the third vertices point away so that the edges are the closest features.
TrianglePair edgeOnEdgePair(PairFactory& f) {
  Triangle a = f.randomTriangle();
  const Vector3d aEdge = a[1] - a[0];
  const Vector3d crossing = a[0] + f.uniform(0, 1) * aEdge;
  Vector3d bDir = f.unit();
  if (f.uniform(0, 1) < 0.2) bDir = (aEdge.normalized() + f.logUniform(1e-9, 1e-2) * f.unit()).normalized();
  Vector3d n = aEdge.cross(bDir);
  if (n.norm() < 1e-12) n = aEdge.unitOrthogonal();
  n.normalize();
  if (n.dot(a[2] - a[0]) > 0) n = -n;  // A's third vertex lies on the other side
  const Vector3d onB = crossing + n * std::abs(adversarialOffset(f));
  const double t = f.uniform(0.05, 0.95);
  Triangle b;
  b[0] = onB - t * bDir;
  b[1] = onB + (1 - t) * bDir;
  b[2] = onB + n * f.uniform(0.1, 1.0) + f.inCube() * 0.5;
  return {a, b};
}

// Vertex on face: a vertex of B sits on (or just above/below) the interior of A.
TrianglePair vertexOnFacePair(PairFactory& f) {
  Triangle a = f.randomTriangle();
  Vector3d n = (a[1] - a[0]).cross(a[2] - a[0]).normalized();
  double w1 = f.uniform(0, 1), w2 = f.uniform(0, 1);
  if (w1 + w2 > 1) { w1 = 1 - w1; w2 = 1 - w2; }
  const Vector3d onFace = a[0] + w1 * (a[1] - a[0]) + w2 * (a[2] - a[0]);
  const Vector3d apex = onFace + n * adversarialOffset(f);
  Triangle b;
  b[0] = apex;
  b[1] = apex + n * f.uniform(0.1, 1) + f.inCube() * 0.7;
  b[2] = apex + n * f.uniform(0.1, 1) + f.inCube() * 0.7;
  return {a, b};
}

// Slivers with aspect ratio 1e6: needles (one short edge) and caps (one vertex near the long
// edge), against random triangles or other slivers nearby.
Triangle sliver(PairFactory& f, const Vector3d& from, const Vector3d& to) {
  const Vector3d side = (to - from).cross(f.unit()).normalized() * (to - from).norm() * 1e-6;
  if (f.uniform(0, 1) < 0.5) return {from, to, to + side};                           // needle
  return {from, to, from + f.uniform(0.1, 0.9) * (to - from) + side};                // cap
}
TrianglePair sliverPair(PairFactory& f) {
  Triangle a = sliver(f, f.inCube(), f.inCube());
  Triangle b;
  const double r = f.uniform(0, 1);
  if (r < 0.4) {
    b = f.randomTriangle();
  } else if (r < 0.7) {
    b = sliver(f, f.inCube(), f.inCube());
  } else {  // nearly parallel sliver just above the first one
    const Vector3d lift = (a[1] - a[0]).unitOrthogonal() * adversarialOffset(f);
    b = sliver(f, a[0] + lift + f.inCube() * 0.1, a[1] + lift + f.inCube() * 1e-3);
  }
  return {a, b};
}

// Mesh neighbours: triangles sharing a vertex or an edge (distance exactly 0).
TrianglePair sharedVertexPair(PairFactory& f) {
  Triangle a = f.randomTriangle();
  Triangle b = f.randomTriangle();
  b[0] = a[int(f.uniform(0, 3)) % 3];
  if (f.uniform(0, 1) < 0.5) b[1] = a[(int(f.uniform(0, 3)) + 1) % 3];  // may share an edge
  if (b[1] == b[0]) b[1] = f.inCube();
  return {a, b};
}

// Intersecting: an edge of B pierces the interior of A.
TrianglePair intersectingPair(PairFactory& f) {
  Triangle a = f.randomTriangle();
  const Vector3d n = (a[1] - a[0]).cross(a[2] - a[0]).normalized();
  double w1 = f.uniform(0, 1), w2 = f.uniform(0, 1);
  if (w1 + w2 > 1) { w1 = 1 - w1; w2 = 1 - w2; }
  const Vector3d hit = a[0] + w1 * (a[1] - a[0]) + w2 * (a[2] - a[0]);
  const Vector3d dir = (n + f.inCube() * 0.8).normalized();
  Triangle b;
  b[0] = hit - dir * f.uniform(0.01, 1);
  b[1] = hit + dir * f.uniform(0.01, 1);
  b[2] = f.inCube();
  return {a, b};
}

// Degenerate: zero-area (collinear), repeated vertices, single points, against anything.
TrianglePair degeneratePair(PairFactory& f) {
  const auto degenerate = [&f]() {
    const Vector3d p = f.inCube(), q = f.inCube();
    switch (int(f.uniform(0, 3)) % 3) {
      case 0: return Triangle(p, q, p + f.uniform(-0.5, 1.5) * (q - p));  // collinear
      case 1: return Triangle(p, p, q);                                     // repeated vertex
      default: return Triangle(p, p, p);                                    // a point
    }
  };
  Triangle a = degenerate();
  Triangle b = f.uniform(0, 1) < 0.5 ? degenerate() : f.randomTriangle();
  return {a, b};
}

// Small triangles far from the origin (coordinates 1e3, size 1e-2): absolute rounding of the
// coordinates is large compared with the triangles.
TrianglePair farFromOriginPair(PairFactory& f) {
  TrianglePair p = randomPair(f);
  const Vector3d far = f.unit() * 1e3;
  for (Triangle* t : {&p.first, &p.second})
    for (int i = 0; i < 3; ++i) (*t)[i] = far + (*t)[i] * 1e-2;
  return p;
}

// Very different sizes (a grain's triangle against a coarse obstacle's, the hybrid's
// scale-aware path): a triangle `ratio` times larger than a random unit one, which sits over
// the large one's face (60 %), near one of its edges (20 %) or vertices (10 %) at an
// adversarial offset, or pierces it (10 %).
PairGenerator sizeRatioPair(double ratio) {
  return [ratio](PairFactory& f) {
    Triangle large = f.randomTriangle();
    while ((large[1] - large[0]).cross(large[2] - large[0]).norm() < 0.2) large = f.randomTriangle();
    for (int i = 0; i < 3; ++i) large[i] *= ratio;
    const Vector3d n = (large[1] - large[0]).cross(large[2] - large[0]).normalized();
    double w1 = f.uniform(0, 1), w2 = f.uniform(0, 1);
    if (w1 + w2 > 1) { w1 = 1 - w1; w2 = 1 - w2; }
    const double r = f.uniform(0, 1);
    Vector3d anchor = large[0] + w1 * (large[1] - large[0]) + w2 * (large[2] - large[0]);
    if (r >= 0.6 && r < 0.8) {
      const int e = int(f.uniform(0, 3)) % 3;
      anchor = large[e] + f.uniform(0, 1) * (large[(e + 1) % 3] - large[e]);
    } else if (r >= 0.8 && r < 0.9) {
      anchor = large[int(f.uniform(0, 3)) % 3];
    }
    const Vector3d apex = anchor + n * adversarialOffset(f) + f.inCube() * (r < 0.6 ? 0.0 : 0.3);
    Triangle small;
    if (r < 0.9) {
      small[0] = apex;
      small[1] = apex + n * f.uniform(-0.2, 1) + f.inCube() * 0.7;
      small[2] = apex + n * f.uniform(-0.2, 1) + f.inCube() * 0.7;
    } else {
      const Vector3d dir = (n + f.inCube() * 0.8).normalized();
      small[0] = anchor - dir * f.uniform(0.01, 1);
      small[1] = anchor + dir * f.uniform(0.01, 1);
      small[2] = anchor + f.inCube();
    }
    return TrianglePair{small, large};
  };
}

std::vector<TrianglePair> makePairs(const PairGenerator& generator, int count, unsigned seed,
                                    bool place = true) {
  PairFactory f(seed);
  std::vector<TrianglePair> pairs;
  pairs.reserve(count);
  for (int i = 0; i < count; ++i) {
    TrianglePair p = generator(f);
    if (f.uniform(0, 1) < 0.5) std::swap(p.first, p.second);
    pairs.push_back(place ? f.place(p) : p);
  }
  return pairs;
}

struct NamedGenerator {
  const char* name;
  PairGenerator generator;
  bool place;  // false: the generator fixes its own coordinates (far from origin)
};

const std::vector<NamedGenerator>& adversarialSets() {
  static const std::vector<NamedGenerator> sets = {
      {"parallel", parallelPair, true},          {"coplanar", coplanarPair, true},
      {"edge-on-edge", edgeOnEdgePair, true},    {"vertex-on-face", vertexOnFacePair, true},
      {"sliver-1e6", sliverPair, true},          {"shared-vertex", sharedVertexPair, true},
      {"intersecting", intersectingPair, true},  {"degenerate", degeneratePair, true},
      {"far-from-origin", farFromOriginPair, false},
      {"size-ratio-1e2", sizeRatioPair(1e2), true},
      {"size-ratio-1e4", sizeRatioPair(1e4), true},
      {"size-ratio-1e6", sizeRatioPair(1e6), true},
  };
  return sets;
}

// Pairs of triangles of two latitude-longitude spheres at contact distance: the benchmark case.
std::vector<TrianglePair> spherePairs(int trianglesPerSphere, double gap, unsigned seed) {
  PairFactory f(seed);
  const std::vector<Triangle> mesh = latitudeLongitudeSphereWithAbout(trianglesPerSphere, 1.0);
  const Eigen::Matrix3d r1 = f.rotation(), r2 = f.rotation();
  std::vector<TrianglePair> pairs;
  for (const Triangle& s : mesh)
    for (const Triangle& t : mesh) {
      TrianglePair p;
      for (int i = 0; i < 3; ++i) {
        p.first[i] = r1 * s[i];
        p.second[i] = r2 * t[i] + Vector3d(2.0 + gap, 0, 0);
      }
      pairs.push_back(p);
    }
  return pairs;
}

std::vector<TriangleDistanceResult> exactDistances(const std::vector<TrianglePair>& pairs) {
  std::vector<TriangleDistanceResult> r;
  r.reserve(pairs.size());
  for (const TrianglePair& p : pairs) r.push_back(triangleDistance(p.first, p.second));
  return r;
}

void splitPairs(const std::vector<TrianglePair>& pairs, std::vector<Triangle>& first,
                std::vector<Triangle>& second) {
  first.clear();
  second.clear();
  for (const TrianglePair& p : pairs) {
    first.push_back(p.first);
    second.push_back(p.second);
  }
}

std::vector<TriangleDistanceResult> hybridDistances(const std::vector<TrianglePair>& pairs,
                                                    const HybridOptions& options,
                                                    HybridStatistics* statistics = nullptr) {
  std::vector<Triangle> first, second;
  splitPairs(pairs, first, second);
  std::vector<TriangleDistanceResult> r(pairs.size());
  hybridTriangleDistances(first.data(), second.data(), pairs.size(), options, r.data(),
                          statistics);
  return r;
}

// The raw penalty kernel on all pairs (upper bound, lower bound, scale per pair).
struct PenaltyOutcome {
  double distance, lowerBound, lengthScale;
};
std::vector<PenaltyOutcome> penaltyOutcomes(const std::vector<TrianglePair>& pairs,
                                            int newtonIterations) {
  std::vector<PenaltyOutcome> out;
  PenaltyOptions options;
  options.newtonIterations = newtonIterations;
  std::vector<Triangle> first, second;
  splitPairs(pairs, first, second);
  const ElementwisePairs source{first.data(), second.data(), pairs.size()};
  TrianglePairBatch batch;
  PenaltyBatchResult result;
  for (std::size_t begin = 0; begin < pairs.size(); begin += kTrianglePairBatchSize) {
    const int lanes = source.loadBatch(batch, begin);
    penaltyTriangleDistanceBatch(batch, options, result);
    for (int l = 0; l < lanes; ++l)
      out.push_back({result.distance[l], result.lowerBound[l], result.lengthScale[l]});
  }
  return out;
}

double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

// Closest points must lie on their triangles and realise the distance. Checked here against
// our own exact method's notion of "on the triangle" only through the distance itself: the
// oracle-based variant is below.
void expectConsistentClosestPoints(const TrianglePair& p, const TriangleDistanceResult& r,
                                   const char* what) {
  const double h = pairScale(p);
  EXPECT_LE(std::abs((r.pointOnFirst - r.pointOnSecond).norm() - r.distance),
            kTolerance * std::max(r.distance, h))
      << what;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Known configurations (no oracle needed)
// ---------------------------------------------------------------------------------------------

TEST(ExactTriangleDistance, KnownConfigurations) {
  const Triangle base({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  // Parallel, overlapping in projection, lifted by 0.5.
  {
    const Triangle lifted({0.1, 0.1, 0.5}, {0.9, 0.1, 0.5}, {0.1, 0.7, 0.5});
    const TriangleDistanceResult r = triangleDistance(base, lifted);
    EXPECT_NEAR(r.distance, 0.5, 1e-15);
    EXPECT_NEAR(r.pointOnFirst.z(), 0.0, 1e-15);
    EXPECT_NEAR(r.pointOnSecond.z(), 0.5, 1e-15);
  }
  // Vertex above the face interior.
  {
    const Triangle apex({0.2, 0.3, 0.25}, {0.2, 0.3, 2}, {1, 1, 3});
    const TriangleDistanceResult r = triangleDistance(base, apex);
    EXPECT_NEAR(r.distance, 0.25, 1e-15);
    EXPECT_TRUE(r.pointOnFirst.isApprox(Vector3d(0.2, 0.3, 0), 1e-14));
  }
  // Skew edges: edge x in [0,1] (y = z = 0) against a segment along y at x = 0.5, z = 0.3.
  {
    const Triangle skew({0.5, -1, 0.3}, {0.5, 1, 0.3}, {0.5, 0, 2});
    const TriangleDistanceResult r = triangleDistance(base, skew);
    EXPECT_NEAR(r.distance, 0.3, 1e-15);
  }
  // Piercing: distance 0, both points equal and on both triangles.
  {
    const Triangle pierce({0.25, 0.25, -1}, {0.25, 0.25, 1}, {3, 3, 3});
    const TriangleDistanceResult r = triangleDistance(base, pierce);
    EXPECT_EQ(r.distance, 0.0);
    EXPECT_TRUE(r.pointOnFirst.isApprox(Vector3d(0.25, 0.25, 0), 1e-14));
    EXPECT_EQ(r.pointOnFirst, r.pointOnSecond);
  }
  // Coplanar, apart by 1 along x.
  {
    const Triangle apart({2, 0, 0}, {3, 0, 0}, {2, 1, 0});
    EXPECT_NEAR(triangleDistance(base, apart).distance, 1.0, 1e-15);
  }
  // Shared vertex and shared edge: 0.
  EXPECT_EQ(triangleDistance(base, Triangle({1, 0, 0}, {2, 0, 1}, {2, 1, 1})).distance, 0.0);
  EXPECT_EQ(triangleDistance(base, Triangle({1, 0, 0}, {0, 1, 0}, {1, 1, 1})).distance, 0.0);
  // Degenerate: a point above the face, a segment beside it.
  EXPECT_NEAR(triangleDistance(base, Triangle({0.1, 0.1, 2}, {0.1, 0.1, 2}, {0.1, 0.1, 2})).distance,
              2.0, 1e-15);
  EXPECT_NEAR(triangleDistance(Triangle({-1, 0.5, 0}, {-3, 0.5, 0}, {-2, 0.5, 0}), base).distance,
              1.0, 1e-15);
}

TEST(TriangleDistanceMethods, ArrayFormsMatchSinglePairsForAnyCount) {
  for (std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(7), std::size_t(8),
                            std::size_t(9), std::size_t(100)}) {
    const std::vector<TrianglePair> pairs = makePairs(randomPair, int(count), 11 + unsigned(count));
    std::vector<Triangle> first, second;
    splitPairs(pairs, first, second);
    std::vector<TriangleDistanceResult> exact(count), hybrid(count), penalty(count), oneVsMany(count);
    triangleDistances(first.data(), second.data(), count, exact.data());
    hybridTriangleDistances(first.data(), second.data(), count, HybridOptions{}, hybrid.data());
    penaltyTriangleDistances(first.data(), second.data(), count, PenaltyOptions{}, penalty.data());
    for (std::size_t k = 0; k < count; ++k) {
      const TriangleDistanceResult single = triangleDistance(first[k], second[k]);
      EXPECT_EQ(exact[k].distance, single.distance);
      EXPECT_LE(scaledError(hybrid[k].distance, single.distance, pairScale(pairs[k])), kTolerance);
      EXPECT_GE(penalty[k].distance, single.distance * (1 - 1e-12));  // admissible points
    }
    if (count == 0) continue;
    hybridTriangleDistances(first[0], second.data(), count, HybridOptions{}, oneVsMany.data());
    for (std::size_t k = 0; k < count; ++k)
      EXPECT_LE(scaledError(oneVsMany[k].distance, triangleDistance(first[0], second[k]).distance,
                            std::max(first[0].longestEdge(), second[k].longestEdge())),
                kTolerance);
  }
}

TEST(TriangleDistanceMethods, AllPairsFormsCoverEveryPairRowMajor) {
  for (std::size_t rows : {std::size_t(1), std::size_t(3), std::size_t(12)})
    for (std::size_t columns : {std::size_t(1), std::size_t(5), std::size_t(13)}) {
      const std::vector<TrianglePair> source = makePairs(randomPair, int(std::max(rows, columns)), 3);
      std::vector<Triangle> first, second;
      splitPairs(source, first, second);
      std::vector<TriangleDistanceResult> exact(rows * columns), penalty(rows * columns),
          hybrid(rows * columns);
      triangleDistancesOfAllPairs(first.data(), rows, second.data(), columns, exact.data());
      penaltyTriangleDistancesOfAllPairs(first.data(), rows, second.data(), columns,
                                         PenaltyOptions{}, penalty.data());
      HybridStatistics statistics;
      hybridTriangleDistancesOfAllPairs(first.data(), rows, second.data(), columns,
                                        HybridOptions{}, hybrid.data(), &statistics);
      EXPECT_EQ(statistics.pairs, rows * columns);
      for (std::size_t i = 0; i < rows; ++i)
        for (std::size_t j = 0; j < columns; ++j) {
          const std::size_t k = i * columns + j;
          const double d = triangleDistance(first[i], second[j]).distance;
          const double h = std::max(first[i].longestEdge(), second[j].longestEdge());
          EXPECT_EQ(exact[k].distance, d);
          EXPECT_LE(scaledError(hybrid[k].distance, d, h), kTolerance);
          EXPECT_GE(penalty[k].distance, d - 1e-12 * (d + 2 * h));  // admissible points
        }
    }
}

TEST(PenaltyTriangleDistance, RejectsIterationCountsOutsideTheTable) {
  TrianglePairBatch batch;
  const Triangle t({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  for (int l = 0; l < kTrianglePairBatchSize; ++l) batch.set(l, t, t);
  PenaltyBatchResult result;
  PenaltyOptions options;
  options.newtonIterations = 0;
  EXPECT_THROW(penaltyTriangleDistanceBatch(batch, options, result), std::invalid_argument);
  options.newtonIterations = kMaxNewtonIterations + 1;
  EXPECT_THROW(penaltyTriangleDistanceBatch(batch, options, result), std::invalid_argument);
}

TEST(SphereMesh, CountsAndRadius) {
  const std::vector<Triangle> mesh = latitudeLongitudeSphere(8, 5, 2.0);
  EXPECT_EQ(mesh.size(), 2u * 8u * 4u);
  for (const Triangle& t : mesh)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(t[i].norm(), 2.0, 1e-14);
  EXPECT_EQ(latitudeLongitudeSphereWithAbout(12, 1.0).size(), 12u);
  const std::size_t large = latitudeLongitudeSphereWithAbout(1000, 1.0).size();
  EXPECT_NEAR(double(large), 1000.0, 20.0);
  EXPECT_THROW(latitudeLongitudeSphere(2, 5, 1.0), std::invalid_argument);
}

#if SPACETREE_HAVE_TRIANGLE_ORACLES

namespace {

using IntervalKernel = CGAL::Simple_cartesian<CGAL::Interval_nt<false>>;
using ExactKernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;

template <class K>
typename K::Point_3 cgalPoint(const Vector3d& v) {
  return typename K::Point_3(v.x(), v.y(), v.z());
}
template <class K>
typename K::Triangle_3 cgalTriangle(const Triangle& t) {
  return typename K::Triangle_3(cgalPoint<K>(t[0]), cgalPoint<K>(t[1]), cgalPoint<K>(t[2]));
}

// CGAL's squared distance of two geometric objects, rigorous: first with interval arithmetic
// (valid enclosure or an exception when a comparison is undecided), accepted when the enclosure
// is 1e-14 tight; otherwise with exact rationals. Returns sqrt of it.
template <class MakeA, class MakeB>
double rigorousDistance(MakeA makeA, MakeB makeB) {
  {
    CGAL::Protect_FPU_rounding<true> upward;
    try {
      const CGAL::Interval_nt<false> d2 =
          CGAL::squared_distance(makeA(IntervalKernel()), makeB(IntervalKernel()));
      if (d2.sup() - d2.inf() <= 1e-14 * d2.sup()) {
        const double mid = 0.5 * (d2.inf() + d2.sup());
        CGAL::Protect_FPU_rounding<false> nearest;
        return std::sqrt(mid);
      }
    } catch (const CGAL::Uncertain_conversion_exception&) {
    }
  }
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(makeA(ExactKernel()), makeB(ExactKernel()))));
}

double cgalDistance(const Triangle& a, const Triangle& b) {
  return rigorousDistance([&](auto k) { return cgalTriangle<decltype(k)>(a); },
                          [&](auto k) { return cgalTriangle<decltype(k)>(b); });
}

// Distance of a point to a triangle; CGAL wants a proper triangle, so a degenerate one
// (collinear or repeated vertices) is taken as the union of its edges (segments or points).
double cgalPointTriangleDistance(const Vector3d& p, const Triangle& t) {
  const auto point = [&](auto k) { return cgalPoint<decltype(k)>(p); };
  if (!cgalTriangle<ExactKernel>(t).is_degenerate())
    return rigorousDistance(point, [&](auto k) { return cgalTriangle<decltype(k)>(t); });
  double d = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const Vector3d& a = t[i];
    const Vector3d& b = t[(i + 1) % 3];
    d = std::min(d, a == b ? (p - a).norm()
                           : rigorousDistance(point, [&](auto k) {
                               using K = decltype(k);
                               return typename K::Segment_3(cgalPoint<K>(a), cgalPoint<K>(b));
                             }));
  }
  return d;
}

double fclDistance(const Triangle& a, const Triangle& b) {
  Vector3d p, q;
  return fcl::detail::TriangleDistance<double>::triDistance(a[0], a[1], a[2], b[0], b[1], b[2], p, q);
}

struct Agreement {
  std::size_t pairs = 0, cgalChecks = 0, adjudicated = 0;
  double maxScaledError = 0.0;
  double maxRelativeError = 0.0;  // |d - ref| / ref over pairs with ref >= 1e-3 h
  double maxPointOffTriangle = 0.0;  // CGAL distance of a closest point to its triangle
                                     // over max(d, h)
  void add(double d, double ref, double h) {
    ++pairs;
    maxScaledError = std::max(maxScaledError, scaledError(d, ref, h));
    if (ref >= 1e-3 * h) maxRelativeError = std::max(maxRelativeError, std::abs(d - ref) / ref);
  }
  std::string summary() const {
    char s[256];
    std::snprintf(s, sizeof s,
                  "%zu pairs (%zu CGAL, %zu FCL disagreements adjudicated by CGAL): max error "
                  "%.2e of max(d,h), %.2e of d (d >= 1e-3 h), closest points off by %.2e h",
                  pairs, cgalChecks, adjudicated, maxScaledError, maxRelativeError,
                  maxPointOffTriangle);
    return s;
  }
};

// Reference distances: CGAL for every pair (cgalEvery = 1) or every n-th pair; in between FCL,
// and CGAL wherever FCL and `probe` (the method under test) differ by more than 1e-12 h.
std::vector<double> referenceDistances(const std::vector<TrianglePair>& pairs,
                                       const std::vector<TriangleDistanceResult>& probe,
                                       std::size_t cgalEvery, Agreement& stats) {
  std::vector<double> ref(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const TrianglePair& p = pairs[k];
    if (k % cgalEvery == 0) {
      ref[k] = cgalDistance(p.first, p.second);
      ++stats.cgalChecks;
      continue;
    }
    ref[k] = fclDistance(p.first, p.second);
    if (scaledError(probe[k].distance, ref[k], pairScale(p)) > 1e-12) {
      ref[k] = cgalDistance(p.first, p.second);
      ++stats.adjudicated;
    }
  }
  return ref;
}

// Checks distances and (on every `pointEvery`-th pair) closest points against the oracle.
Agreement checkAgainstOracle(const std::vector<TrianglePair>& pairs,
                             const std::vector<TriangleDistanceResult>& results,
                             std::size_t cgalEvery, std::size_t pointEvery, const char* what) {
  Agreement stats;
  const std::vector<double> ref = referenceDistances(pairs, results, cgalEvery, stats);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const double h = pairScale(pairs[k]);
    stats.add(results[k].distance, ref[k], h);
    EXPECT_LE(scaledError(results[k].distance, ref[k], h), kTolerance)
        << what << " pair " << k << ": " << results[k].distance << " vs " << ref[k];
    if (ref[k] >= 1e-3 * h) {  // separated pairs: also relative to the distance itself
      EXPECT_LE(std::abs(results[k].distance - ref[k]), kTolerance * ref[k])
          << what << " pair " << k << ": " << results[k].distance << " vs " << ref[k];
    }
    expectConsistentClosestPoints(pairs[k], results[k], what);
    if (k % pointEvery == 0) {
      const double scale = std::max({h, ref[k], 1e-300});  // as scaledError
      const double offA = cgalPointTriangleDistance(results[k].pointOnFirst, pairs[k].first) / scale;
      const double offB = cgalPointTriangleDistance(results[k].pointOnSecond, pairs[k].second) / scale;
      stats.maxPointOffTriangle = std::max({stats.maxPointOffTriangle, offA, offB});
      EXPECT_LE(offA, kTolerance) << what << " pair " << k;
      EXPECT_LE(offB, kTolerance) << what << " pair " << k;
    }
  }
  return stats;
}

// Contact decisions d < T of the hybrid equal the exact method's, for thresholds that put
// pairs right at the decision: quantiles of the set's distances and exact distances of
// individual pairs (a tie, d == T, must be decided "no contact" by both).
void expectIdenticalContactDecisions(const std::vector<TrianglePair>& pairs,
                                     const std::vector<TriangleDistanceResult>& exact,
                                     const char* what, HybridStatistics& total) {
  std::vector<double> distances;
  for (const TriangleDistanceResult& r : exact) distances.push_back(r.distance);
  // Quantiles, a fixed fraction of the triangle size (sets where every distance is 0), and the
  // exact distances of individual pairs.
  std::vector<double> thresholds = {quantile(distances, 0.1), quantile(distances, 0.5),
                                    0.01 * pairScale(pairs.front())};
  for (std::size_t k = 0; k < pairs.size(); k += pairs.size() / 7 + 1)
    if (exact[k].distance > 0.0)
      for (double f : {1.0 - 1e-15, 1.0, 1.0 + 1e-15}) thresholds.push_back(exact[k].distance * f);
  for (double threshold : thresholds) {
    if (!(threshold > 0.0)) continue;
    HybridOptions options;
    options.contactDistance = threshold;
    const std::vector<TriangleDistanceResult> hybrid = hybridDistances(pairs, options, &total);
    std::size_t differing = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k)
      differing += (hybrid[k].distance < threshold) != (exact[k].distance < threshold);
    EXPECT_EQ(differing, 0u) << what << ": contact threshold " << threshold;
  }
}

void report(const std::string& line) {
  std::printf("[ report   ] %s\n", line.c_str());
  ::testing::Test::RecordProperty("report", line);
}

}  // namespace

TEST(ExactTriangleDistance, AgreesWithFclAndCgalOnRandomPairs) {
  const std::vector<TrianglePair> pairs = makePairs(randomPair, 100000, 1);
  const std::vector<TriangleDistanceResult> exact = exactDistances(pairs);
  const Agreement stats = checkAgainstOracle(pairs, exact, 10, 10, "exact/random");
  report("exact vs oracle, random: " + stats.summary());
}

TEST(HybridTriangleDistance, AgreesWithFclAndCgalOnRandomPairs) {
  const std::vector<TrianglePair> pairs = makePairs(randomPair, 100000, 1);
  HybridStatistics fallbacks;
  const std::vector<TriangleDistanceResult> hybrid = hybridDistances(pairs, HybridOptions{}, &fallbacks);
  const Agreement stats = checkAgainstOracle(pairs, hybrid, 10, 10, "hybrid/random");
  char line[128];
  std::snprintf(line, sizeof line, "; fallback %.2f %% (residual %zu, contact band %zu)",
                100.0 * fallbacks.fallbackFraction(), fallbacks.residualFallbacks,
                fallbacks.contactBandFallbacks);
  report("hybrid vs oracle, random: " + stats.summary() + line);
  const std::vector<TrianglePair> subset(pairs.begin(), pairs.begin() + 20000);
  HybridStatistics unused;
  expectIdenticalContactDecisions(subset, exactDistances(subset), "random", unused);
}

TEST(ExactTriangleDistance, AgreesWithCgalOnAdversarialSets) {
  unsigned seed = 100;
  for (const NamedGenerator& set : adversarialSets()) {
    const std::vector<TrianglePair> pairs = makePairs(set.generator, 3000, ++seed, set.place);
    const std::vector<TriangleDistanceResult> exact = exactDistances(pairs);
    const Agreement stats = checkAgainstOracle(pairs, exact, 1, 3, set.name);
    report(std::string("exact vs CGAL, ") + set.name + ": " + stats.summary());
  }
}

TEST(HybridTriangleDistance, AgreesWithCgalAndDecidesContactsLikeExactOnAdversarialSets) {
  unsigned seed = 100;
  for (const NamedGenerator& set : adversarialSets()) {
    const std::vector<TrianglePair> pairs = makePairs(set.generator, 3000, ++seed, set.place);
    HybridStatistics fallbacks;
    const std::vector<TriangleDistanceResult> hybrid = hybridDistances(pairs, HybridOptions{}, &fallbacks);
    const Agreement stats = checkAgainstOracle(pairs, hybrid, 1, 3, set.name);
    HybridStatistics decisions;
    expectIdenticalContactDecisions(pairs, exactDistances(pairs), set.name, decisions);
    char line[160];
    std::snprintf(line, sizeof line,
                  "; fallback %.1f %%; contact-band fallbacks over %zu threshold runs: %zu",
                  100.0 * fallbacks.fallbackFraction(), decisions.pairs / pairs.size(),
                  decisions.contactBandFallbacks);
    report(std::string("hybrid vs CGAL, ") + set.name + ": " + stats.summary() + line);
  }
}

// The penalty method alone: its error distribution (reported), and the validity of the two
// bounds the hybrid relies on, on every pair of every set.
TEST(PenaltyTriangleDistance, BoundsHoldAndErrorDistributionIsReported) {
  struct Case {
    std::string name;
    std::vector<TrianglePair> pairs;
    std::size_t cgalEvery;  // CGAL on every n-th pair, FCL (adjudicated by CGAL) in between
  };
  std::vector<Case> cases;
  cases.push_back({"random", makePairs(randomPair, 20000, 5), 10});
  cases.push_back({"spheres-200", spherePairs(200, 0.01, 6), 10});
  unsigned seed = 200;
  for (const NamedGenerator& set : adversarialSets())
    cases.push_back({set.name, makePairs(set.generator, 1000, ++seed, set.place), 1});

  for (const Case& c : cases) {
    Agreement unused;
    const std::vector<double> reference =
        referenceDistances(c.pairs, exactDistances(c.pairs), c.cgalEvery, unused);
    for (int iterations : {4, 8}) {
      const std::vector<PenaltyOutcome> penalty = penaltyOutcomes(c.pairs, iterations);
      std::vector<double> errors;
      std::size_t above1e10 = 0, above1e6 = 0, above1e2 = 0;
      for (std::size_t k = 0; k < c.pairs.size(); ++k) {
        const PenaltyOutcome& o = penalty[k];
        const double slack = kRoundingSlack * (o.distance + 2.0 * o.lengthScale);
        EXPECT_GE(o.distance, reference[k] - slack) << c.name << " pair " << k;
        EXPECT_LE(o.lowerBound, reference[k] + slack) << c.name << " pair " << k;
        const double e = scaledError(o.distance, reference[k], pairScale(c.pairs[k]));
        errors.push_back(e);
        above1e10 += e > 1e-10;
        above1e6 += e > 1e-6;
        above1e2 += e > 1e-2;
      }
      const double n = double(c.pairs.size());
      char line[256];
      std::snprintf(line, sizeof line,
                    "penalty %d it, %-15s error of max(d,h): median %.1e q90 %.1e q99 %.1e "
                    "q99.9 %.1e max %.1e; > 1e-10: %.2f %%, > 1e-6: %.2f %%, > 1e-2: %.2f %%",
                    iterations, c.name.c_str(), quantile(errors, 0.5), quantile(errors, 0.9),
                    quantile(errors, 0.99), quantile(errors, 0.999), quantile(errors, 1.0),
                    100 * above1e10 / n, 100 * above1e6 / n, 100 * above1e2 / n);
      report(line);
    }
  }
}

// 10^6 random pairs (about 5 s): FCL for all, CGAL for every 100th pair and wherever FCL and the
// method differ; contact decisions of the hybrid at the 10 % distance quantile.
// Closest point of a triangle to a point (the sphere-triangle contacts): its distance equals
// CGAL's rigorous point-triangle distance, it lies on the triangle, and its feature says where
// (a vertex feature is that vertex, an edge feature lies on that edge). Random triangles,
// points near them, and degenerate triangles (collinear, repeated vertices).
TEST(PointTriangleDistance, ClosestPointAgreesWithCgal) {
  using spacetree::geometry::TriangleFeature;
  namespace geometry = spacetree::geometry;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto point = [&] { return Vector3d(u(rng), u(rng), u(rng)); };
  double maxError = 0.0, maxOff = 0.0;
  int features[7] = {};
  for (int k = 0; k < 10000; ++k) {
    Triangle t{point(), point(), point()};
    if (k % 50 == 0) t[2] = t[0] + 0.37 * (t[1] - t[0]);  // collinear
    if (k % 50 == 1) t[2] = t[1];                          // repeated vertex
    const Vector3d p = k % 3 == 0 ? Vector3d(point() * 3.0) : Vector3d(point() * 0.3 + t[k % 3]);
    const geometry::PointTriangleClosest r = geometry::closestPointOnTriangle(p, t);
    const Vector3d q = p - r.offset;
    const double h = t.longestEdge();
    const double reference = cgalPointTriangleDistance(p, t);
    const double err = std::abs(r.offset.norm() - reference) / std::max(reference, h);
    maxError = std::max(maxError, err);
    maxOff = std::max(maxOff, cgalPointTriangleDistance(q, t) / h);
    ++features[int(r.feature)];
    const int f = int(r.feature);
    if (f <= 2) {
      EXPECT_LT((q - t[f]).norm(), 1e-14 * h) << k;
    } else if (f <= 5) {
      const Vector3d& a = t[f - 3];
      const Vector3d& b = t[(f - 2) % 3];
      const Vector3d e = b - a;
      EXPECT_LT(e.cross(q - a).norm(), 1e-12 * h * h) << k;  // on the edge's line
    }
  }
  EXPECT_LT(maxError, 1e-13);
  EXPECT_LT(maxOff, 1e-13);
  for (int f = 0; f < 7; ++f) EXPECT_GT(features[f], 100) << "feature " << f;
  // The squared distance (the culls' form) is the same number.
  const Triangle t{Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  EXPECT_EQ(geometry::pointTriangleSquaredDistance(Vector3d(0.2, 0.3, 0.5), t), 0.25);
  EXPECT_EQ(geometry::closestPointOnTriangle(Vector3d(2, 2, 0), t).feature, TriangleFeature::Edge12);
  EXPECT_EQ(geometry::closestPointOnTriangle(Vector3d(-1, 0.5, 0), t).feature, TriangleFeature::Edge20);
}

TEST(TriangleDistanceMethods, MillionRandomPairsAgreeWithOracle) {
  const std::vector<TrianglePair> pairs = makePairs(randomPair, 1000000, 77);
  const std::vector<TriangleDistanceResult> exact = exactDistances(pairs);
  HybridStatistics fallbacks;
  const std::vector<TriangleDistanceResult> hybrid = hybridDistances(pairs, HybridOptions{}, &fallbacks);
  report("exact, 1e6 random: " + checkAgainstOracle(pairs, exact, 100, 100, "exact/1e6").summary());
  report("hybrid, 1e6 random: " + checkAgainstOracle(pairs, hybrid, 100, 100, "hybrid/1e6").summary());

  std::vector<double> distances;
  for (const TriangleDistanceResult& r : exact) distances.push_back(r.distance);
  HybridOptions contact;
  contact.contactDistance = quantile(distances, 0.1);
  HybridStatistics decided;
  const std::vector<TriangleDistanceResult> decisions = hybridDistances(pairs, contact, &decided);
  std::size_t differing = 0;
  for (std::size_t k = 0; k < pairs.size(); ++k)
    differing += (decisions[k].distance < contact.contactDistance) !=
                 (exact[k].distance < contact.contactDistance);
  EXPECT_EQ(differing, 0u);
  char line[160];
  std::snprintf(line, sizeof line,
                "hybrid on 1e6 random pairs: fallback %.3f %%; contact decisions at T = %.3g "
                "differing from exact: %zu",
                100.0 * fallbacks.fallbackFraction(), contact.contactDistance, differing);
  report(line);
}

#else

TEST(TriangleDistanceOracles, Unavailable) {
  GTEST_SKIP() << "CGAL and FCL not found at configure time: oracle comparisons skipped";
}

#endif
