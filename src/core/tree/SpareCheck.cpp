#include "tree/SpareCheck.h"

#include "tree/ReluctantCriterion.h"

namespace spacetree {

void SpareCheck::begin(const Pass& pass) {
  pass_ = pass;
  pass_.count = pass.first && pass.second ? pass.count : 0;
  indexed_ = false;
  hostsIndexed_ = false;
}

void SpareCheck::indexPartners() {
  const int n = pass_.n;
  partnerStart_.assign(std::size_t(n) + 1, 0);
  auto forEachPair = [&](auto f) {
    if (pass_.first) {
      for (std::size_t k = 0; k < pass_.count; ++k) f(pass_.first[k], pass_.second[k]);
    } else {
      for (const auto& pair : *pass_.closePairs) f(pair.first, pair.second);
    }
  };
  auto valid = [n](int a, int b) { return a >= 0 && b >= 0 && a < n && b < n && a != b; };
  forEachPair([&](int a, int b) {
    if (!valid(a, b)) return;
    ++partnerStart_[std::size_t(a) + 1];
    ++partnerStart_[std::size_t(b) + 1];
  });
  for (int i = 0; i < n; ++i) partnerStart_[std::size_t(i) + 1] += partnerStart_[std::size_t(i)];
  partners_.resize(std::size_t(partnerStart_[std::size_t(n)]));
  std::vector<int>& fill = scratchNextAt_;  // borrowed: the host lists are built after this
  fill.assign(partnerStart_.begin(), partnerStart_.end() - 1);
  forEachPair([&](int a, int b) {
    if (!valid(a, b)) return;
    partners_[std::size_t(fill[std::size_t(a)]++)] = b;
    partners_[std::size_t(fill[std::size_t(b)]++)] = a;
  });
  indexed_ = true;
}

void SpareCheck::indexHosts() {
  const RefinedCells& cells = *pass_.cells;
  const int n = pass_.n;
  scratchFirstAt_.resize(std::size_t(cells.depth()) + 1);
  for (VertexCounters& m : scratchFirstAt_) m.reset(0);
  scratchNextAt_.assign(std::size_t(n), -1);
  for (int i = 0; i < n; ++i) {
    const int l = pass_.host[i];
    if (l <= cells.regularDepth()) continue;
    const Index3 w = cells.nearestVertex(l, pass_.x[i]);
    std::int64_t& head = scratchFirstAt_[std::size_t(l)][packVertexKey(w.i, w.j, w.k)];
    scratchNextAt_[std::size_t(i)] = int(head) - 1;
    head = i + 1;
  }
  hostsIndexed_ = true;
}

bool SpareCheck::wouldRefineAgain(int m, std::uint64_t cellKey) {
  if (!pass_.x || m + 1 > pass_.cells->depth()) return false;
  const RefinedCells& cells = *pass_.cells;
  const double (*x)[3] = pass_.x;
  const int* host = pass_.host;
  if (!indexed_) indexPartners();
  const bool tracked = pass_.firstAtVertex != nullptr;
  if (!tracked && !hostsIndexed_) indexHosts();
  const VertexIndex c = unpackVertexKey(cellKey);
  // p, hosted at a vertex of C's children, sits on level m (or coarser) once C is removed; the
  // criterion of the refinement there refines the parents of the 2^d cells around p's nearest
  // vertex on level m + 1 (its present host vertex, in C's closed patch): C among them.
  auto criterionHolds = [&](int p) {
    if (pass_.admissible[p] <= m) return false;  // would not drop
    const Index3 pc = cells.cellOf(m, x[p]);
    for (int t = partnerStart_[std::size_t(p)]; t < partnerStart_[std::size_t(p) + 1]; ++t) {
      const int q = partners_[std::size_t(t)];
      // A finer q is taken on level m too: under C it lifts with p; elsewhere that can only
      // spare more (a cell kept longer costs comparisons, never pairs).
      if (!heldByCell(cells, pass_.epsilon, m, pc, x[q], host[q], pass_.radius[q])) continue;
      if (!approaching(x, pass_.v, p, q)) continue;
      return true;
    }
    return false;
  };
  const std::vector<VertexCounters>& firstAt = tracked ? *pass_.firstAtVertex : scratchFirstAt_;
  const std::vector<int>& nextAt = tracked ? *pass_.nextAtVertex : scratchNextAt_;
  for (std::int64_t a = 3 * c.i; a <= 3 * c.i + 3; ++a)
    for (std::int64_t b = 3 * c.j; b <= 3 * c.j + 3; ++b)
      for (std::int64_t e = 3 * c.k; e <= 3 * c.k + 3; ++e)
        for (int p = int(firstAt[std::size_t(m) + 1].get(packVertexKey(a, b, e))) - 1; p >= 0;
             p = nextAt[std::size_t(p)])
          if (criterionHolds(p)) return true;
  return false;
}

}  // namespace spacetree
