#pragma once

#include <numeric>
#include <vector>

namespace is_graphs {

/// Union-find over the integers 0 .. n-1 (path halving): which elements a set of pairwise joins
/// connects. The stair search's steps, the A-Graph's factor-graph pieces.
class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

  /// The representative of i's set.
  int Find(int i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }
  void Join(int a, int b) { parent_[Find(a)] = Find(b); }

 private:
  std::vector<int> parent_;
};

}  // namespace is_graphs
