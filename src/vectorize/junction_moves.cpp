// SPDX-License-Identifier: GPL-3.0-or-later
// Junctions moved onto the model's edge (moved_junctions, chain_points.hpp): where the legs
// meeting at them cross, and where a straight run's other end follows; elsewhere onto the line their
// folds snap onto.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "chain_legs.hpp"
#include "chain_points.hpp"
#include "union_find.hpp"

namespace origamic::chains {
namespace {

// Where the two legs most across each other meet, one of them on a break, if they cross at
// kLegMinSine or more; on a lattice leg's line exactly. Where a chain snaps onto its fold at the
// junction, on that fold's line: the junction then is the fold's end (and another fold ending
// there meets it by a connector, as ever).
// A level contour keeps to the pixel edges within a pixel of a third face (breaks_and_levels): a
// junction's legs reach past that many of them to the contour's run, and the junction moves to where
// the runs meet, not the contour bent into the lattice corner. Not at a junction where a support's
// side ends: W wide on the lattice, it would tilt and be narrower than W (there too, the 37 models
// at W = 3 mm had 3,990 places, 69 more). Places at W = 2 / 3 / 5 mm 6,588 / 3,921 / 2,207 ->
// 6,548 / 3,880 / 2,192, chords under W 68,281 / 46,673 / 32,617 -> 66,598 / 45,323 / 31,758; the
// mean p95 1.981 / 1.832 / 1.880 -> 1.988 / 1.831 / 1.879 W (at 2 mm res_bunny's supports land
// otherwise, 1.67 -> 1.83 W). Past 1, 2 or 3 edges: 3,880 places at 3 mm each, chords 45,347,
// 45,323 and 45,334.
constexpr std::size_t kContourLatticeEdges = 2;

std::optional<MovedJunction> meeting_point(const std::vector<Leg>& legs) {
  const auto folds = std::ranges::count_if(legs, [](const Leg& leg) { return leg.fold_chain >= 0; });
  double best_sine = kLegMinSine;
  std::optional<MovedJunction> best;
  for (const Leg& p : legs)
    for (const Leg& q : legs) {
      if (!p.on_break || &p == &q || (folds > 0 && q.fold_chain < 0)) continue;
      const double sine = p.dx * q.dy - p.dy * q.dx;
      if (!(std::abs(sine) > best_sine)) continue;
      const double t = ((q.X - p.X) * q.dy - (q.Y - p.Y) * q.dx) / sine;
      MovedJunction at{{}, p.X + t * p.dx, p.Y + t * p.dy};
      if (q.fold_chain >= 0)
        at.Y = q.Y, at.on_fold_of = q.fold_chain;
      else if (!q.on_break)
        (q.dy == 0 ? at.v_on_lattice : at.u_on_lattice) = q.dy == 0 ? q.through.v : q.through.u;
      best_sine = std::abs(sine);
      best = at;
    }
  return best;
}

// Two legs on the model's edge, opposite ways, are taken as one edge through their junction where
// they cross at under this sine (14.5 degrees) and each one's point lies within this distance of
// the other's line, the tolerance for a drawn edge. Over the 27 MANIFEST models at
// W = 3 mm, against the places under 0.25 mm wide these leave: a sine of 0.1 left 9 more; no
// distance bound, 2 fewer; 0.02 mm, 6 more.
constexpr double kEdgeThroughSine = 0.25, kEdgeThroughOff_mm = 0.05;

// Where the model's edge runs through a junction of one corner (two of its legs on a break, as
// above) and no other leg crosses it within a pixel (a level contour gives no leg, mostly; a
// contour's leg on a break may cross it at a shallow angle far off), the junction moves to the foot
// of the perpendicular from its corner onto the edge: the contour ends on the edge, where from the
// lattice corner, a fraction of a pixel beside it, a connector went to the edge and left a notch.
// Over the 27 MANIFEST models at W = 3 mm: places under 0.25 mm wide 1,314 -> 1,209, chords under W
// 41,583 -> 40,695, but places 3,519 -> 3,522 (their faces keep other chords under W, 12 a place:
// the notch gone, the next chord stands). A third leg crossing the edge more than a pixel off had
// held the junction on its corner, a notch a tenth of a millimetre deep (res_dragon_res4 at (96,
// 107.75), the crossing 0.36 mm off): moved onto the edge, the 37 models' chords under W at W = 3
// mm went 44,476 -> 43,387, their places 3,833 -> 3,824, the mean p95 the same (1.72 W). Not where a
// fold ends (it stays on its line), nor where a support's side ends (W wide on its lattice column,
// it would tilt; allowed there too, 3,826 places, 43,385 chords).
std::optional<MovedJunction> onto_the_edge(const std::vector<Leg>& legs, const std::vector<LatticePoint>& members,
                                           const LatticeScale& lattice, bool by_support) {
  if (members.size() != 1 || by_support ||
      std::ranges::any_of(legs, [](const Leg& leg) { return leg.fold_chain >= 0; }))
    return std::nullopt;
  const auto off_line = [](const Leg& leg, const Leg& of) {
    return std::abs((leg.X - of.X) * of.dy - (leg.Y - of.Y) * of.dx);
  };
  // Of the pairs of legs the edge may run through, the most nearly one line: whatever the chains'
  // order, the same pair.
  const Leg *p = nullptr, *q = nullptr;
  double best_sine = kEdgeThroughSine;
  for (const Leg& a : legs)
    for (const Leg& b : legs) {
      const double sine = std::abs(a.dx * b.dy - a.dy * b.dx);
      if (&a < &b && a.on_break && b.on_break && sine < best_sine && a.dx * b.dx + a.dy * b.dy < 0 &&
          off_line(a, b) <= kEdgeThroughOff_mm && off_line(b, a) <= kEdgeThroughOff_mm)
        best_sine = sine, p = &a, q = &b;
    }
  if (!p) return std::nullopt;
  // Along the legs' mean direction (|p - q| > sqrt 2 for unit legs at over 90 degrees), through
  // the midpoint of their points.
  const double along_X = p->dx - q->dx, along_Y = p->dy - q->dy, length = std::hypot(along_X, along_Y);
  const double dx = along_X / length, dy = along_Y / length;
  const double X0 = (p->X + q->X) / 2, Y0 = (p->Y + q->Y) / 2;
  const double t = (lattice.X(members.front().u) - X0) * dx + (lattice.Y(members.front().v) - Y0) * dy;
  return MovedJunction{{}, X0 + t * dx, Y0 + t * dy};
}

// The line the folds snapping at a junction end on (with one of those folds), if they all end on one.
std::optional<std::pair<double, std::int32_t>> fold_line_of(const std::vector<Leg>& legs) {
  std::optional<std::pair<double, std::int32_t>> line;
  for (const Leg& leg : legs)
    if (leg.fold_chain >= 0) {
      if (line && line->first != leg.Y) return std::nullopt;
      if (!line) line = std::pair{leg.Y, leg.fold_chain};
    }
  return line;
}

// Where no model edge passes a junction of one corner and its folds all snap onto one line, the
// junction moves square onto that line: the fold ends where the cuts meet, not a connector's length
// away, beside which a cut drawn slanted left a sliver (res_dragon_full: 0.024 mm wide at (100,
// -35.5); over the 37 models at W = 3 mm places under 0.1 mm wide 768 -> 454). A chain leaving it
// along the lattice row goes along where it runs straight to another junction (follow_along_rows)
// or is a support's edge (add_cut in exact_plan_chains.cpp, up to its corner); others tilt by the
// move. Kept in place for any such chain, as it was, the junction left the 37 models at W = 3 mm
// 97 places more (4,021 against 3,924). Not where a cluster of several corners would need one X
// for all.
std::optional<MovedJunction> onto_the_fold(const std::vector<Leg>& legs, const std::vector<LatticePoint>& members,
                                           const LatticeScale& lattice) {
  if (members.size() != 1 || std::ranges::any_of(legs, &Leg::on_break)) return std::nullopt;
  const auto line = fold_line_of(legs);
  if (!line) return std::nullopt;
  const LatticePoint p = members.front();
  return MovedJunction{{}, lattice.X(p.u), line->first, p.u, -1, line->second};
}

// The junctions of moved_junctions, by id; those one pixel edge apart are one cluster, named by
// its root's id (the other ids' entries stay empty): per chain the clusters of its ends (a loop's
// are not set), per cluster its junctions, the legs meeting there, whether it is held and where it
// moves.
struct Clusters {
  explicit Clusters(std::size_t chains, std::size_t junctions)
      : of_chain(chains), members(junctions), legs(junctions), held(junctions, false), moved_to(junctions) {}
  // How far cluster c's farthest junction goes to `at`.
  double moves_by(std::size_t c, const MovedJunction& at, const LatticeScale& lattice) const {
    double farthest = 0;
    for (const LatticePoint p : members[c])
      farthest = std::max(farthest, std::hypot(at.X - lattice.X(p.u), at.Y - lattice.Y(p.v)));
    return farthest;
  }
  std::vector<std::array<std::size_t, 2>> of_chain;
  std::vector<std::vector<LatticePoint>> members;
  std::vector<std::vector<Leg>> legs;
  std::vector<bool> held;
  std::vector<std::optional<MovedJunction>> moved_to;
};

// The chains straight along one lattice column (along_row false) or row, not loops, not short.
std::vector<std::size_t> straight_runs(const std::vector<Chain>& chains, bool along_row) {
  std::vector<std::size_t> runs;
  for (std::size_t i = 0; i < chains.size(); ++i) {
    const std::vector<LatticePoint>& corners = chains[i].corners;
    const auto on_its_line = [&](LatticePoint p) {
      return along_row ? p.v == corners.front().v : p.u == corners.front().u;
    };
    if (!is_short(chains[i]) && !is_loop(chains[i]) && std::ranges::all_of(corners, on_its_line)) runs.push_back(i);
  }
  return runs;
}

// Pass after pass until nothing moves, each run whose junction at one end moved takes the one at its
// other end where `follow(run, moved end, other end)` says. Each pass decides on the moves before
// it, so the chains' order does not matter; runs that would take one end two ways leave it.
template <typename Follow>
void follow_runs(const std::vector<std::size_t>& runs, Clusters& clusters, Follow follow) {
  for (bool moved = true; moved;) {
    std::map<std::size_t, std::optional<MovedJunction>> proposed;  // nullopt: two ways
    for (const std::size_t i : runs) {
      const auto [front, back] = clusters.of_chain[i];
      for (const auto& [from, to] : {std::pair{front, back}, std::pair{back, front}}) {
        if (from == to || !clusters.moved_to[from] || clusters.moved_to[to] || clusters.held[to]) continue;
        const std::optional<MovedJunction> at = follow(i, *clusters.moved_to[from], to);
        if (!at) continue;
        const auto [it, fresh] = proposed.try_emplace(to, *at);
        const auto differs = [&](const MovedJunction& a) {
          return a.X != at->X || a.Y != at->Y || a.on_fold_of != at->on_fold_of;
        };
        if (!fresh && it->second && differs(*it->second)) it->second.reset();
      }
    }
    moved = false;
    for (const auto& [to, at] : proposed)
      if (at) clusters.moved_to[to] = at, moved = true;
  }
}

// A straight run down one lattice column whose junction at one end moved across it onto the model's
// edge takes its other end along where folds end there (on one line): along that line, as far, so
// that the run stays straight and square to the fold. A support's side below a wall's edge, ending
// on the main fold, slanted from the wall's edge to the fold's end on the lattice, a pixel's fraction
// over, and left slivers either side (the demo house: 11 places narrower than W -> 8; the 37 models
// at W = 3 mm: 4,390 -> 4,391, their likeness the same). Taking a lattice line's end along too, not
// only a fold's, made arch_city_block's supports choose otherwise: p95 3.3 -> 4.7 W.
void follow_across_runs(const std::vector<Chain>& chains, const LatticeScale& lattice, Clusters& clusters) {
  follow_runs(straight_runs(chains, false), clusters,
              [&](std::size_t i, const MovedJunction& moved, std::size_t to) -> std::optional<MovedJunction> {
                const auto line = fold_line_of(clusters.legs[to]);
                if (std::abs(moved.X - lattice.X(chains[i].corners.front().u)) < kLeastMove_mm || !line)
                  return std::nullopt;
                const MovedJunction at{{}, moved.X, line->first, -1, -1, line->second};
                if (!(clusters.moves_by(to, at, lattice) <= kJunctionMove_px * lattice.px_mm)) return std::nullopt;
                return at;
              });
}

// A straight run along one lattice row whose junction at one end moved onto a fold's line takes
// its other junction onto that line too, square above or below it, so that the run stays straight
// rather than tilt by a pixel's fraction (measured while every chain's row run went along, not
// only a support's: the 37 models at W = 3 mm, places 3,917 -> 3,903). Not for a run that snaps
// onto a fold itself, nor where the other junction is on the model's edge, on another fold's line,
// or where another run leaves it along the row. Fold lines are exact: no move is too small.
void follow_along_rows(const std::vector<Chain>& chains, const std::vector<ChainEnds>& ends,
                       const LatticeScale& lattice, Clusters& clusters) {
  std::vector<std::size_t> runs = straight_runs(chains, true);
  std::erase_if(runs, [&](std::size_t i) { return ends[i].fold_Y[0] || ends[i].fold_Y[1]; });
  const auto movable = [&](std::size_t to, double Y) {
    if (clusters.members[to].size() != 1) return false;
    int rows = 0;
    for (const Leg& leg : clusters.legs[to]) {
      if (leg.on_break || (leg.fold_chain >= 0 && leg.Y != Y)) return false;
      rows += leg.fold_chain < 0 && leg.dy == 0;
    }
    return rows <= 1;
  };
  follow_runs(runs, clusters,
              [&](std::size_t i, const MovedJunction& moved, std::size_t to) -> std::optional<MovedJunction> {
                const double row_Y = lattice.Y(chains[i].corners.front().v);
                if (moved.on_fold_of < 0 || moved.Y == row_Y || !movable(to, moved.Y))
                  return std::nullopt;
                const LatticePoint p = clusters.members[to].front();
                const MovedJunction at{{}, lattice.X(p.u), moved.Y, p.u, -1, moved.on_fold_of};
                if (!(clusters.moves_by(to, at, lattice) <= kJunctionMove_px * lattice.px_mm)) return std::nullopt;
                return at;
              });
}

}  // namespace

JunctionMoves moved_junctions(const std::vector<Chain>& chains, const LatticeScale& lattice,
                              const PictureBreaks& breaks, const std::vector<ChainEnds>& ends) {
  assert(ends.size() == chains.size());
  JunctionMoves result;
  result.collapsed.assign(chains.size(), false);
  if (breaks.right.size() == 0) return result;
  // Junctions one pixel edge apart are one place on the model's edge (where it crosses the main
  // fold, say, between the back plane and the floor): the short chains between them form clusters.
  std::map<std::pair<int, int>, std::int32_t> junction_of;
  std::vector<LatticePoint> corner_of;
  const auto id = [&](LatticePoint p) {
    const auto [it, fresh] = junction_of.try_emplace({p.u, p.v}, static_cast<std::int32_t>(corner_of.size()));
    if (fresh) corner_of.push_back(p);
    return it->second;
  };
  for (const Chain& chain : chains)
    if (!is_loop(chain)) id(chain.corners.front()), id(chain.corners.back());
  UnionFind<std::int32_t> union_of(corner_of.size());
  for (const Chain& chain : chains)
    if (!is_loop(chain) && is_short(chain)) union_of.join(id(chain.corners.front()), id(chain.corners.back()));
  const auto cluster = [&](LatticePoint p) { return static_cast<std::size_t>(union_of.root(id(p))); };
  Clusters clusters(chains.size(), corner_of.size());
  for (std::size_t j = 0; j < corner_of.size(); ++j) clusters.members[cluster(corner_of[j])].push_back(corner_of[j]);
  std::vector<bool> by_support(corner_of.size(), false);
  for (std::size_t i = 0; i < chains.size(); ++i)
    if (!is_loop(chains[i]) && ends[i].beside_support)
      by_support[cluster(chains[i].corners.front())] = by_support[cluster(chains[i].corners.back())] = true;
  for (std::size_t i = 0; i < chains.size(); ++i) {
    const Chain& chain = chains[i];
    if (is_loop(chain)) continue;
    clusters.of_chain[i] = {cluster(chain.corners.front()), cluster(chain.corners.back())};
    for (const bool front : {true, false}) {
      const LatticePoint end = front ? chain.corners.front() : chain.corners.back();
      const std::size_t c = cluster(end);
      if (ends[i].pinned) clusters.held[c] = true;
      if (const std::optional<double> fold_Y = ends[i].fold_Y[front ? 0 : 1])
        clusters.legs[c].push_back({lattice.X(end.u), *fold_Y, 1, 0, false, end, static_cast<std::int32_t>(i)});
      else if (const std::optional<Leg> leg =
                   leg_of(chain, front, lattice, breaks, by_support[c] ? 0 : kContourLatticeEdges))
        clusters.legs[c].push_back(*leg);
    }
  }
  // A cluster moves whole or not at all; by a pixel at most, and not by the rays' rounding alone.
  const double reach = kJunctionMove_px * lattice.px_mm;
  for (std::size_t c = 0; c < corner_of.size(); ++c) {
    if (clusters.members[c].empty() || clusters.held[c]) continue;
    std::optional<MovedJunction> at = meeting_point(clusters.legs[c]);
    if (at && !(clusters.moves_by(c, *at, lattice) <= reach)) at.reset();
    if (!at) at = onto_the_edge(clusters.legs[c], clusters.members[c], lattice, by_support[c]);
    if (!at) continue;
    const double move = clusters.moves_by(c, *at, lattice);
    if (move <= reach && move >= kLeastMove_mm) clusters.moved_to[c] = at;
  }
  follow_across_runs(chains, lattice, clusters);
  for (std::size_t c = 0; c < corner_of.size(); ++c) {
    if (clusters.members[c].empty() || clusters.held[c] || clusters.moved_to[c]) continue;
    const std::optional<MovedJunction> at = onto_the_fold(clusters.legs[c], clusters.members[c], lattice);
    if (!at) continue;
    // Exact lines: no move is too small to make, unlike one read off the rays.
    const double move = clusters.moves_by(c, *at, lattice);
    if (move > 0 && move <= reach) clusters.moved_to[c] = at;
  }
  follow_along_rows(chains, ends, lattice, clusters);
  for (std::size_t j = 0; j < corner_of.size(); ++j)
    if (const auto& at = clusters.moved_to[cluster(corner_of[j])]) {
      MovedJunction moved = *at;
      moved.corner = corner_of[j];
      result.moved.push_back(moved);
    }
  for (std::size_t i = 0; i < chains.size(); ++i) {
    const Chain& chain = chains[i];
    if (is_loop(chain) || !is_short(chain)) continue;
    result.collapsed[i] = clusters.moved_to[cluster(chain.corners.front())].has_value();
  }
  return result;
}

}  // namespace origamic::chains
