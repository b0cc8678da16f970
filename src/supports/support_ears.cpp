// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_ears.hpp"

#include <algorithm>
#include <boost/container/small_vector.hpp>
#include <cassert>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "origamic/plan.hpp"

namespace origamic {
namespace {

bool same_line(double a, double b) { return std::abs(a - b) <= kFoldLineTolerance_mm; }

// A path from a standing face into the open faces, as the search grows it.
struct Label {
  double dist;
  double picture;  // the likeness's part of dist
  std::int32_t face;
  double Y;              // the line it entered `face` on
  std::int32_t source;   // the standing face the path left
  std::int64_t prev;     // the label before, -1 at the source
  std::int64_t support;  // the support edge it came by, -1 for a fold
  bool cutting = false;  // some support on the path cuts a face in two
  std::uint32_t state = 0;  // of (face, Y)
};

}  // namespace

EarSearch::EarSearch(std::int32_t faces, std::span<const FoldEdge> folds, std::span<const SupportEdge> supports)
    : arcs_(static_cast<std::size_t>(faces)) {
  for (const FoldEdge& f : folds) {
    arcs_[static_cast<std::size_t>(f.a)].push_back({f.b, f.Y, f.Y, 0, 0, -1});
    arcs_[static_cast<std::size_t>(f.b)].push_back({f.a, f.Y, f.Y, 0, 0, -1});
  }
  for (std::size_t i = 0; i < supports.size(); ++i) {
    const SupportEdge& s = supports[i];
    const auto k = static_cast<std::int64_t>(i);
    arcs_[static_cast<std::size_t>(s.face)].push_back({s.target, s.face_Y, s.target_Y, s.cost, s.picture, k});
    arcs_[static_cast<std::size_t>(s.target)].push_back({s.face, s.target_Y, s.face_Y, s.cost, s.picture, k});
    cuts_.push_back(s.cuts);
  }
}

// Dijkstra from every standing face at once over (face, line it was entered on), each path labelled
// with the standing face it left; a state keeps the two cheapest labels of different sources. An
// open face's cheapest ear is then two of its labels of different sources, entering it on different
// lines, whose paths share no face.
EarSearch::Choice EarSearch::hardest(const std::vector<std::uint8_t>& standing, const std::vector<std::uint8_t>& open,
                                     const std::vector<double>& limit, const std::vector<std::uint8_t>& usable) const {
  return pick(standing, open, limit, usable, true);
}

EarSearch::Choice EarSearch::cheapest(const std::vector<std::uint8_t>& standing, const std::vector<std::uint8_t>& open,
                                      const std::vector<double>& limit, const std::vector<std::uint8_t>& usable) const {
  return pick(standing, open, limit, usable, false);
}

// The search's paths (the Dijkstra that hardest describes, for both picks): its labels, and per
// state (a face and the line it is entered on) the two cheapest labels of different sources.
class EarSearch::Paths {
 public:
  Paths(const EarSearch& graph, const std::vector<std::uint8_t>& open, const std::vector<std::uint8_t>& usable)
      : graph_(graph),
        open_(open),
        usable_(usable),
        states_of_(graph.arcs_.size()),
        first_arc_(graph.arcs_.size() + 1),
        first_open_arc_(graph.arcs_.size() + 1),
        end_open_arc_(graph.arcs_.size()) {
    for (std::size_t u = 0; u < graph.arcs_.size(); ++u) {
      first_arc_[u + 1] = first_arc_[u] + graph.arcs_[u].size();
      for (std::size_t a = 0; a < graph.arcs_[u].size(); ++a) {
        const Arc& arc = graph.arcs_[u][a];
        if (open_[static_cast<std::size_t>(arc.to)] && allowed(arc))
          open_arcs_.push_back(static_cast<std::uint32_t>(a));
      }
      first_open_arc_[u + 1] = end_open_arc_[u] = open_arcs_.size();
    }
    arc_state_.assign(first_arc_.back(), kNoState);
  }

  void run(const std::vector<std::uint8_t>& standing) {
    for (std::size_t u = 0; u < graph_.arcs_.size(); ++u) {
      if (!standing[u]) continue;
      for (std::size_t a = 0; a < graph_.arcs_[u].size(); ++a) {
        const Arc& arc = graph_.arcs_[u][a];
        if (open_[static_cast<std::size_t>(arc.to)] && allowed(arc) && !breaks(-1, arc))
          push({arc.cost, arc.picture, arc.to, arc.there_Y, static_cast<std::int32_t>(u), -1, arc.support,
                !cuts_of(arc.support).empty(), state_entered(u, a)});
      }
    }
    while (!queue_.empty()) {
      const std::int64_t id = queue_.top().second;
      queue_.pop();
      const Label label = labels_[static_cast<std::size_t>(id)];
      {
        State& st = states_[label.state];  // before the arcs below add states and move them
        if (st.settled >= 2 || (st.best[0] != id && st.best[1] != id)) continue;  // superseded
        if (st.settled == 1 && st.best[0] == id) continue;
        if (st.best[st.settled] != id) std::swap(st.best[0], st.best[1]);  // the popped one is the next settled
        ++st.settled;
      }
      const auto u = static_cast<std::size_t>(label.face);
      // An arc into a state whose two labels are final leads nowhere again: it leaves u's list, which
      // keeps its order (seedlike/torus's 33 searches followed 9.4 million arcs, 4.0 million of them
      // into such states).
      std::size_t kept = first_open_arc_[u];
      for (std::size_t i = first_open_arc_[u]; i < end_open_arc_[u]; ++i) {
        const std::uint32_t a = open_arcs_[i];
        const Arc& arc = graph_.arcs_[u][a];
        if (same_line(arc.here_Y, label.Y)) {  // a face held on one line swings
          open_arcs_[kept++] = a;
          continue;
        }
        const std::uint32_t entered = state_entered(u, a);
        if (states_[entered].settled == 2) continue;
        open_arcs_[kept++] = a;
        // Straight back is no path; longer cycles cost more than their way round, and an ear found
        // through one is passed over below.
        const bool back = label.prev >= 0 && labels_[static_cast<std::size_t>(label.prev)].face == arc.to;
        if (back || breaks(id, arc)) continue;
        const bool cutting = label.cutting || !cuts_of(arc.support).empty();
        push({label.dist + arc.cost, label.picture + arc.picture, arc.to, arc.there_Y, label.source, id, arc.support,
              cutting, entered});
      }
      end_open_arc_[u] = kept;
    }
  }

  const Label& label(std::int64_t k) const { return labels_[static_cast<std::size_t>(k)]; }

  // The labels settled at face f, by distance (then id).
  std::vector<std::int64_t> settled_at(std::size_t f) const {
    std::vector<std::int64_t> kept;
    for (const std::uint32_t k : states_of_[f])
      for (int i = 0; i < states_[k].settled; ++i) kept.push_back(states_[k].best[i]);
    std::ranges::sort(kept, {}, [&](std::int64_t k) { return std::pair{label(k).dist, k}; });
    return kept;
  }

  // Whether the two paths into a face together visit some face twice, or a support of one cuts a
  // face of the other in two.
  bool shares_face(std::int64_t a, std::int64_t b) const {
    // On the stack: most paths are a few faces long, and the search asks of hundreds of thousands of
    // pairs (seedlike/torus: 2.1 million allocations here were a third of the design's).
    boost::container::small_vector<std::int32_t, 32> faces, cut;
    for (std::int64_t k = label(a).prev; k >= 0; k = label(k).prev) faces.push_back(label(k).face);
    for (std::int64_t k = b; k >= 0; k = label(k).prev) faces.push_back(label(k).face);
    for (const std::int64_t end : {a, b})
      if (label(end).cutting)
        for (std::int64_t k = end; k >= 0; k = label(k).prev)
          for (const std::int32_t x : cuts_of(label(k).support)) cut.push_back(x);
    std::ranges::sort(faces);
    if (std::ranges::adjacent_find(faces) != faces.end()) return true;
    return std::ranges::any_of(cut, [&](std::int32_t x) { return std::ranges::binary_search(faces, x); });
  }

  // The ear of two labels into one face: the first path from its source to the face, then the
  // second back from the face to its source.
  Ear ear(double cost, std::pair<std::int64_t, std::int64_t> pair) const {
    Ear ear;
    ear.cost = cost;
    ear.picture = label(pair.first).picture + label(pair.second).picture;
    std::vector<std::int32_t> there;
    for (std::int64_t k = pair.first; k >= 0; k = label(k).prev) {
      there.push_back(label(k).face);
      if (label(k).support >= 0) ear.supports.push_back(static_cast<std::size_t>(label(k).support));
    }
    ear.faces.assign(there.rbegin(), there.rend());
    for (std::int64_t k = label(pair.second).prev; k >= 0; k = label(k).prev) ear.faces.push_back(label(k).face);
    for (std::int64_t k = pair.second; k >= 0; k = label(k).prev)
      if (label(k).support >= 0) ear.supports.push_back(static_cast<std::size_t>(label(k).support));
    return ear;
  }

 private:
  // A state: a face and the line it is entered on. It keeps the two cheapest labels of different
  // sources seen so far (the first two settled are final); a label no better than those is dropped
  // before it is queued, so each state queues a few labels, not one per path into it.
  struct State {
    double Y;
    std::int64_t step;                // Y in fold tolerances
    std::int64_t best[2] = {-1, -1};  // the two cheapest labels of different sources, cheaper first
    int settled = 0;                  // of them, popped
  };

  // States by face and line, the line to the fold tolerance (two lines a rounding apart may fall on
  // either side of a step and make two states: harmless, the hinge rule compares the lines). Found by
  // a hash: a face that many candidate supports reach is entered on hundreds of lines (the first
  // round of seedlike/torus: 54 faces, 13,684 arcs), where a walk along them took 35-75 ms a search.
  std::uint32_t state_of(std::int32_t face, double Y) {
    const auto step = static_cast<std::int64_t>(std::llround(Y / kFoldLineTolerance_mm));
    // Lines lie within the sheet, some 10^9 tolerances from the main fold: 42 bits hold them.
    assert(0 <= face && face < (1 << 22) && std::abs(step) < (std::int64_t{1} << 41));
    const std::uint64_t key =
        static_cast<std::uint64_t>(face) << 42 ^ static_cast<std::uint64_t>(step + (std::int64_t{1} << 41));
    const auto [it, fresh] = state_at_.try_emplace(key, static_cast<std::uint32_t>(states_.size()));
    if (fresh) {
      states_of_[static_cast<std::size_t>(face)].push_back(it->second);
      states_.push_back(State{Y, step});
    }
    return it->second;
  }

  bool allowed(const Arc& arc) const { return arc.support < 0 || usable_[static_cast<std::size_t>(arc.support)]; }

  // The state arc a of face u enters, looked up once: a search follows each arc once per label
  // settled at u (the first round of seedlike/torus: 2.2 million times, its 13,684 arcs).
  std::uint32_t state_entered(std::size_t u, std::size_t a) {
    std::uint32_t& state = arc_state_[first_arc_[u] + a];
    if (state == kNoState) {
      const Arc& arc = graph_.arcs_[u][a];
      state = state_of(arc.to, arc.there_Y);
    }
    return state;
  }

  // Keeps the label if it is among its state's two cheapest of different sources, and queues it.
  void push(const Label& label) {
    State& st = states_[label.state];
    std::int64_t* best = st.best;
    const auto id = static_cast<std::int64_t>(labels_.size());
    const auto dist_of = [&](std::int64_t k) { return labels_[static_cast<std::size_t>(k)].dist; };
    int same = -1;
    for (int i = 0; i < 2; ++i)
      if (best[i] >= 0 && labels_[static_cast<std::size_t>(best[i])].source == label.source) same = i;
    if (same >= 0) {
      if (same < st.settled || dist_of(best[same]) <= label.dist) return;
      best[same] = id;
    } else if (best[1] < 0 || dist_of(best[1]) > label.dist) {
      if (st.settled == 2) return;
      if (best[0] < 0)
        best[0] = id;
      else
        best[1] = id;
    } else {
      return;
    }
    labels_.push_back(label);  // before the order below reads its distance
    if (st.settled == 0 && best[0] >= 0 && best[1] >= 0 && dist_of(best[1]) < dist_of(best[0]))
      std::swap(best[0], best[1]);
    queue_.emplace(label.dist, id);
  }

  const std::vector<std::int32_t>& cuts_of(std::int64_t support) const {
    static const std::vector<std::int32_t> none;
    return support < 0 ? none : graph_.cuts_[static_cast<std::size_t>(support)];
  }

  // Whether a path would cut one of its own faces in two: the arc's support cuts a face of the path
  // or the one it enters, or a support on the path cuts the face it enters.
  bool breaks(std::int64_t from, const Arc& arc) const {
    const std::vector<std::int32_t>& cuts = cuts_of(arc.support);
    if (std::ranges::find(cuts, arc.to) != cuts.end()) return true;
    if (cuts.empty() && (from < 0 || !labels_[static_cast<std::size_t>(from)].cutting)) return false;
    for (std::int64_t k = from; k >= 0; k = labels_[static_cast<std::size_t>(k)].prev) {
      const Label& l = labels_[static_cast<std::size_t>(k)];
      if (std::ranges::find(cuts, l.face) != cuts.end()) return true;
      const std::vector<std::int32_t>& earlier = cuts_of(l.support);
      if (std::ranges::find(earlier, arc.to) != earlier.end()) return true;
    }
    return false;
  }

  using Entry = std::pair<double, std::int64_t>;
  const EarSearch& graph_;
  const std::vector<std::uint8_t>& open_;
  const std::vector<std::uint8_t>& usable_;
  std::vector<Label> labels_;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue_;
  std::vector<State> states_;
  std::vector<std::vector<std::uint32_t>> states_of_;  // per face
  std::unordered_map<std::uint64_t, std::uint32_t> state_at_;  // by face and line step
  static constexpr std::uint32_t kNoState = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::size_t> first_arc_;    // per face, the index of its first arc among all
  std::vector<std::uint32_t> arc_state_;  // per arc, the state it enters, kNoState until looked up
  // Per face, the arcs a path may take out of it (usable, into an open face, into a state not yet
  // final), by their index among its arcs: first_open_arc_[u] to end_open_arc_[u] in open_arcs_.
  std::vector<std::size_t> first_open_arc_, end_open_arc_;
  std::vector<std::uint32_t> open_arcs_;
};

namespace {

// An open face's cheapest ear: its cost and its two labels.
struct FoundEar {
  double cost;
  std::int32_t face;
  std::pair<std::int64_t, std::int64_t> pair;
};

}  // namespace

EarSearch::Choice EarSearch::pick(const std::vector<std::uint8_t>& standing, const std::vector<std::uint8_t>& open,
                                  const std::vector<double>& limit, const std::vector<std::uint8_t>& usable,
                                  bool hardest) const {
  Paths paths(*this, open, usable);
  paths.run(standing);
  Choice choice;
  // Each open face's cheapest ear: two labels of different sources, entering it on different lines,
  // whose paths share no face.
  std::vector<FoundEar> found;
  for (std::size_t f = 0; f < arcs_.size(); ++f) {
    if (!open[f]) continue;
    const std::vector<std::int64_t> kept = paths.settled_at(f);
    double best = std::numeric_limits<double>::infinity(), best_picture = 0;
    std::pair<std::int64_t, std::int64_t> best_pair{-1, -1};
    for (std::size_t i = 0; i < kept.size(); ++i)
      for (std::size_t j = i + 1; j < kept.size(); ++j) {
        const Label &a = paths.label(kept[i]), &b = paths.label(kept[j]);
        if (a.dist + b.dist >= best) break;  // sorted: no cheaper pair with this i
        if (a.source == b.source || same_line(a.Y, b.Y)) continue;
        if (paths.shares_face(kept[i], kept[j])) continue;
        best = a.dist + b.dist, best_picture = a.picture + b.picture, best_pair = {kept[i], kept[j]};
      }
    if (best_pair.first < 0) continue;
    if (best_picture > limit[f])
      choice.beyond_limit.emplace_back(static_cast<std::int32_t>(f), best_picture);
    else
      found.push_back({best, static_cast<std::int32_t>(f), best_pair});
  }
  // Hardest (or cheapest) first; an ear that shares a face or a support with one taken before it
  // waits for the next search, which sees the faces taken standing.
  std::ranges::sort(found, [&](const FoundEar& a, const FoundEar& b) {
    return hardest ? std::tie(b.cost, a.face) < std::tie(a.cost, b.face)
                   : std::tie(a.cost, a.face) < std::tie(b.cost, b.face);
  });
  std::vector<std::uint8_t> taken_face(arcs_.size(), 0);
  std::vector<std::size_t> taken_support;
  for (const FoundEar& f : found) {
    Ear ear = paths.ear(f.cost, f.pair);
    const bool apart =
        std::ranges::none_of(ear.faces, [&](std::int32_t x) { return taken_face[static_cast<std::size_t>(x)] != 0; }) &&
        std::ranges::none_of(ear.supports,
                             [&](std::size_t k) { return std::ranges::find(taken_support, k) != taken_support.end(); });
    if (!apart) continue;
    for (const std::int32_t x : ear.faces) taken_face[static_cast<std::size_t>(x)] = 1;
    taken_support.insert(taken_support.end(), ear.supports.begin(), ear.supports.end());
    choice.ears.push_back(std::move(ear));
  }
  return choice;
}

}  // namespace origamic
