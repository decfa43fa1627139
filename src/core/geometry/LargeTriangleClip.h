// A triangle pair of very different sizes (a grain's small triangle against a coarse obstacle's
// large one) reduced to a pair of comparable sizes with the same distance: the hybrid's
// scale-aware path (HybridTriangleDistance.h). The penalty kernel works in units of the pair's
// mean squared edge length, so at a size ratio of 1:10^4 its final constraint violation, ~1e-12
// of the large triangle's parameters, is ~1e-8 of the small triangle: too loose to certify.
//
// Why the clip keeps the distance (and so the hybrid's decisions) exact. Let S be the small
// triangle with centroid c and radius r = max |S_j - c|, L the large one, and D any upper bound
// of dist(S, L) (here the distance of a vertex of S to a point of L). A closest point p of L
// has a partner q in S with |p - q| = dist(S, L) <= D, and |q - c| <= r, so |p - c| <= D + r:
// every closest point of L lies in the ball B(c, D + r). In L's parameters
// x(u) = L0 + u1 e1 + u2 e2 that ball is the ellipse (u - u*)^T G (u - u*) <= kappa^2 around
// the projection u* of c (G = E^T E, kappa^2 = (D + r)^2 - h^2, h the distance of c to L's
// plane), whose extent is u1* +- kappa |e2| / |e1 x e2|, u2* +- kappa |e1| / |e1 x e2| and
// (u1 + u2)* + kappa |e2 - e1| / |e1 x e2|. The sub-triangle
//   {u1 >= a1, u2 >= a2, u1 + u2 <= b},  a_i = max(0, lower end), b = min(1, upper end),
// lies in L and contains the part of the ellipse inside L, hence every closest point: dist(S, part) = dist(S, L),
// with the same closest points. It is L shrunk towards S (parallel edges, same orientation),
// of about the size D + r, i.e. of the small triangle's size when the two are close.
// In floating point the part's vertices are L0 + e1 a + e2 b, off the exact ones by a few ulps
// of L's extent, and so are the bounds computed on it; the hybrid therefore certifies a
// clipped pair with the original pair's length scale (its rounding slack covers them).
//
// The same pass gives cheap rigorous bounds for the configurations a small triangle near a
// large one has. Upper bound: the best of each vertex of S against its projection onto L
// (clamped into L: always a point of L) and, where the part reaches one of L's own edges, of
// S's edges and vertices against that edge (segment distances). Lower bound: separating axes
// along L's normal, along the direction of the best pair of points and, for an edge-edge
// pair, along the two edges' cross product. Both equal dist(S, L) when the closest features
// are a vertex of S over L's face, a vertex of S and an edge of L, or two edges.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "geometry/Triangle.h"

namespace spacetree::geometry {

// A pair is clipped when one triangle's longest edge exceeds the other's this many times...
constexpr double kClipSizeRatio = 4.0;
// ... and the part is at most this fraction of the large triangle (linear size).
constexpr double kClipMaximumScale = 0.5;

struct LargeTriangleClip {
  bool bounded = false;        // the bounds below are set (false: degenerate large triangle)
  bool clipped = false;        // the part is set (false: keep the pair as it is)
  Triangle part;               // the sub-triangle of the large triangle (same vertex order)
  double upperBound = 0.0;     // |pointOnSmall - pointOnLarge|, a distance of the two triangles
  Eigen::Vector3d pointOnSmall = Eigen::Vector3d::Zero();  // a point of the small triangle
  Eigen::Vector3d pointOnLarge = Eigen::Vector3d::Zero();  // a point of the large triangle
  double lowerBound = 0.0;     // separating-axis bound (>= 0), <= the distance
};

// Gap at which the bounds are good enough: upperBound - lowerBound <= relative * upperBound +
// absolute. Negative relative: never (always the part and every bound).
struct ClipAcceptance {
  double relative = -1.0;
  double absolute = 0.0;
};

// The clip of `large` against `small` (see above). The vertex-over-face bounds come first; if
// they already meet `accept`, the result is bounded but not clipped (no part, no edge bounds:
// the caller needs neither). Otherwise clipped = false when the large triangle is degenerate
// or the part would not be smaller than kClipMaximumScale of it.
LargeTriangleClip clipLargeTriangle(const Triangle& large, const Triangle& small,
                                    const ClipAcceptance& accept = ClipAcceptance{});

// Which triangle of a pair to clip: 0 (the first), 1 (the second) or -1 (sizes within
// kClipSizeRatio of each other, or a degenerate one).
int largeTriangleOfPair(const Triangle& first, const Triangle& second);

}  // namespace spacetree::geometry
