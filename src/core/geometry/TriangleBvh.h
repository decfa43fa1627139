// Static bounding-volume hierarchy over the bounding spheres of a shape's triangles (built once
// per RigidShape, in its body frame): the contact search asks it for the triangles whose sphere
// reaches a query sphere (the other body's bounding sphere + 2 eps) in O(log n + k) instead of
// visiting all n triangles (a hopper of 1536 triangles against a grain of 40).
//
// Nodes are axis-aligned boxes around the spheres [c - r, c + r] of their triangles, split at
// the median of the centres along the longest axis of the node's centre box, down to leaves of
// at most kLeafSize triangles; stored depth first (left child = node + 1).
//
// The box test is conservative: forEachCandidate() visits (at least) every triangle i with
// |c_i - q| < r_i + radius + slack, slack = kRelativeSlack (radius + |q| + extent), extent the
// largest |c_i| + r_i, so that a caller can apply its own exact test to the candidates and get
// the same set as a brute-force loop evaluating that test, even when its q was computed in
// another frame (a rotation and a shift with rounding errors ~1e-16 of the magnitudes).
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace spacetree::geometry {

class TriangleBvh {
 public:
  static constexpr int kLeafSize = 4;
  static constexpr double kRelativeSlack = 1e-9;

  TriangleBvh() = default;
  // Spheres (centres[i], radii[i]); the sizes must agree (std::invalid_argument otherwise).
  TriangleBvh(const std::vector<Eigen::Vector3d>& centres, const std::vector<double>& radii);

  bool empty() const { return nodes_.empty(); }
  std::size_t size() const { return order_.size(); }
  std::size_t nodeCount() const { return nodes_.size(); }

  // radius >= 0 (a negative one finds nothing).
  // Calls visit(i) for every triangle i of the leaves whose box comes within radius + slack of
  // q (a superset of the spheres reaching the query sphere; each i at most once, in no
  // particular order).
  template <class Visit>
  void forEachCandidate(const Eigen::Vector3d& q, double radius, Visit&& visit) const;

  // The exact set {i : |c_i - q| < r_i + radius}, ascending (what a loop over all triangles
  // gives); `out` is overwritten.
  void query(const Eigen::Vector3d& q, double radius, std::vector<int>& out) const;

 private:
  struct Node {
    Eigen::Vector3d lo, hi;  // box of the node's triangle spheres
    int begin = 0, count = 0;  // leaf: order_[begin, begin + count); inner: count = 0
    int right = -1;            // inner: index of the right child (left child = this + 1)
  };
  int build(int begin, int end, const std::vector<Eigen::Vector3d>& centres,
            const std::vector<double>& radii);

  std::vector<Node> nodes_;
  std::vector<int> order_;
  std::vector<Eigen::Vector3d> centres_;
  std::vector<double> radii_;
  double extent_ = 0.0;
};

template <class Visit>
void TriangleBvh::forEachCandidate(const Eigen::Vector3d& q, double radius, Visit&& visit) const {
  if (nodes_.empty()) return;
  const double reach = radius + kRelativeSlack * (std::abs(radius) + q.norm() + extent_);
  if (!(radius >= 0.0)) return;
  const double reach2 = reach * reach;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[std::size_t(stack[--top])];
    const Eigen::Vector3d below = (node.lo - q).cwiseMax(0.0);
    const Eigen::Vector3d above = (q - node.hi).cwiseMax(0.0);
    if ((below + above).squaredNorm() > reach2) continue;
    if (node.count > 0) {
      for (int k = node.begin; k < node.begin + node.count; ++k) visit(order_[std::size_t(k)]);
    } else {
      const int self = int(&node - nodes_.data());
      stack[top++] = node.right;
      stack[top++] = self + 1;
    }
  }
}

}  // namespace spacetree::geometry
