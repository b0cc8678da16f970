// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/validity.hpp"

#include <algorithm>
#include <set>
#include <utility>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/biconnected_components.hpp>

namespace origamic {
namespace {

using Adjacency = std::vector<std::vector<std::pair<std::int32_t, std::int32_t>>>;  // (neighbour, line)

std::vector<bool> grow(const Adjacency& adjacency, std::int32_t from, std::int32_t never) {
  std::vector<bool> reached(adjacency.size(), false);
  std::vector<std::int32_t> stack = {from};
  reached[static_cast<std::size_t>(from)] = true;
  while (!stack.empty()) {
    const std::int32_t f = stack.back();
    stack.pop_back();
    for (const auto& [g, line] : adjacency[static_cast<std::size_t>(f)]) {
      if (g == never || reached[static_cast<std::size_t>(g)]) continue;
      reached[static_cast<std::size_t>(g)] = true;
      stack.push_back(g);
    }
  }
  return reached;
}

}  // namespace

std::string_view to_string(FaceStatus status) {
  switch (status) {
    case FaceStatus::Valid: return "valid";
    case FaceStatus::Indirect: return "indirect";
    case FaceStatus::Floating: return "floating";
    case FaceStatus::Dangling: return "dangling";
    case FaceStatus::Invalid: return "invalid";
    case FaceStatus::Removed: return "removed";
  }
  return "?";
}

namespace {

Adjacency adjacency_of(const FaceGraph& graph) {
  Adjacency adjacency(static_cast<std::size_t>(graph.faces));
  for (const Fold& fold : graph.folds) {
    if (fold.a == fold.b) continue;
    adjacency[static_cast<std::size_t>(fold.a)].emplace_back(fold.b, fold.line);
    adjacency[static_cast<std::size_t>(fold.b)].emplace_back(fold.a, fold.line);
  }
  return adjacency;
}

std::vector<int> fold_lines_per_face(const Adjacency& adjacency) {
  std::vector<int> fold_lines(adjacency.size(), 0);
  for (std::size_t f = 0; f < adjacency.size(); ++f) {
    std::set<std::int32_t> lines;
    for (const auto& [g, line] : adjacency[f]) lines.insert(line);
    fold_lines[f] = static_cast<int>(lines.size());
  }
  return fold_lines;
}

// Hinges set aside: a face whose folds to faces still standing lie on at most one line.
std::vector<bool> standing_faces(const Adjacency& adjacency) {
  const std::size_t n = adjacency.size();
  std::vector<bool> standing(n, true);
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t f = 2; f < n; ++f) {
      if (!standing[f]) continue;
      std::set<std::int32_t> lines;
      for (const auto& [g, line] : adjacency[f])
        if (standing[static_cast<std::size_t>(g)]) lines.insert(line);
      if (lines.size() <= 1) standing[f] = false, changed = true;
    }
  }
  return standing;
}

using BlockGraph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                         boost::property<boost::edge_index_t, std::size_t>>;

// The standing faces joined by their folds, once per pair, plus a node T (the last) joined to the
// back plane and the floor.
BlockGraph standing_with_T(const FaceGraph& graph, const std::vector<bool>& standing) {
  const std::size_t n = standing.size(), T = n;
  BlockGraph g(n + 1);
  std::size_t edges = 0;
  std::set<std::pair<std::int32_t, std::int32_t>> joined;
  auto join = [&](std::size_t a, std::size_t b) { boost::add_edge(a, b, edges++, g); };
  join(0, T);
  join(1, T);
  for (const Fold& fold : graph.folds) {
    const auto a = std::min(fold.a, fold.b), b = std::max(fold.a, fold.b);
    if (a == b || !standing[static_cast<std::size_t>(a)] || !standing[static_cast<std::size_t>(b)]) continue;
    if (joined.emplace(a, b).second) join(static_cast<std::size_t>(a), static_cast<std::size_t>(b));
  }
  return g;
}

// The back plane, the floor, and the faces in a block (biconnected component) of T.
std::vector<bool> held_faces(const BlockGraph& g) {
  const std::size_t T = boost::num_vertices(g) - 1;
  std::vector<std::size_t> block(boost::num_edges(g));
  boost::biconnected_components(g, boost::make_iterator_property_map(block.begin(), boost::get(boost::edge_index, g)));
  std::set<std::size_t> blocks_of_T;
  for (auto [e, end] = boost::out_edges(T, g); e != end; ++e)
    blocks_of_T.insert(block[boost::get(boost::edge_index, g, *e)]);
  std::vector<bool> held(T, false);
  held[0] = held[1] = true;
  for (auto [e, end] = boost::edges(g); e != end; ++e)
    if (blocks_of_T.contains(block[boost::get(boost::edge_index, g, *e)]))
      for (const std::size_t node : {boost::source(*e, g), boost::target(*e, g)})
        if (node != T) held[node] = true;
  return held;
}

// Seed §4.4: attached to the valid set by a fold, and by a connective face outside it that is
// itself attached to the valid set.
bool indirect(std::size_t f, const Adjacency& adjacency, const std::vector<bool>& held) {
  bool to_valid = false, via_connective = false;
  for (const auto& [g2, line] : adjacency[f]) {
    const auto c = static_cast<std::size_t>(g2);
    if (held[c]) {
      to_valid = true;
      continue;
    }
    for (const auto& [h2, line2] : adjacency[c])
      if (static_cast<std::size_t>(h2) != f && held[static_cast<std::size_t>(h2)]) via_connective = true;
  }
  return to_valid && via_connective;
}

FaceStatus status_of(std::size_t f, const FaceGraph& graph, const Validity& v, const Adjacency& adjacency,
                     const std::vector<bool>& held) {
  if (f < graph.holes.size() && graph.holes[f]) return FaceStatus::Removed;
  if (held[f] && v.fold_lines[f] >= 2) return FaceStatus::Valid;
  if (!v.reaches_back_plane[f] && !v.reaches_floor[f])  // no chain of folds reaches the card
    return FaceStatus::Floating;
  if (v.fold_lines[f] == 1) return FaceStatus::Dangling;
  return indirect(f, adjacency, held) ? FaceStatus::Indirect : FaceStatus::Invalid;
}

}  // namespace

Validity validity_of(const FaceGraph& graph) {
  const Adjacency adjacency = adjacency_of(graph);
  Validity v;
  v.fold_lines = fold_lines_per_face(adjacency);
  v.reaches_back_plane = grow(adjacency, 0, 1);
  v.reaches_floor = grow(adjacency, 1, 0);
  const std::vector<bool> held = held_faces(standing_with_T(graph, standing_faces(adjacency)));
  v.status.assign(adjacency.size(), FaceStatus::Valid);
  for (std::size_t f = 2; f < adjacency.size(); ++f) v.status[f] = status_of(f, graph, v, adjacency, held);
  count_statuses(v);
  return v;
}

void count_statuses(Validity& v) {
  for (std::size_t f = 2; f < v.status.size(); ++f) switch (v.status[f]) {
      case FaceStatus::Valid: ++v.valid; break;
      case FaceStatus::Indirect: ++v.indirect; break;
      case FaceStatus::Floating: ++v.floating; break;
      case FaceStatus::Dangling: ++v.dangling; break;
      case FaceStatus::Invalid: ++v.invalid; break;
      case FaceStatus::Removed: ++v.removed; break;
    }
}

}  // namespace origamic
