// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: disjoint sets of 0 .. n-1 whose root is always the smallest member, so what joins what
// does not depend on the order of the joins (faces merged keep the smaller id, parts come out in
// the order of their first member).
#pragma once

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace origamic {

template <typename Index>
class UnionFind {
 public:
  explicit UnionFind(std::size_t n = 0) { reset(n); }

  /// n sets of one member each (the storage is kept: reuse one to avoid allocating).
  void reset(std::size_t n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), Index{0});
  }
  /// A new set of one member, the next index.
  Index add() {
    parent_.push_back(static_cast<Index>(parent_.size()));
    return parent_.back();
  }
  std::size_t size() const { return parent_.size(); }

  Index root(Index i) {
    const auto at = [](Index k) { return static_cast<std::size_t>(k); };
    while (parent_[at(i)] != i) i = parent_[at(i)] = parent_[at(parent_[at(i)])];
    return i;
  }
  /// Joins the sets of a and b under the smaller root; false if they were one set already.
  bool join(Index a, Index b) {
    a = root(a), b = root(b);
    if (a == b) return false;
    parent_[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
    return true;
  }

 private:
  std::vector<Index> parent_;
};

}  // namespace origamic
