// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23: where a face narrower than W ends in a tip (tip_walk.hpp), walked across the chord on
// exact numbers. One exact run at a time: see exact_runs.hpp.
#define CGAL_HAS_NO_THREADS 1

#include "tip_walk.hpp"

#include <algorithm>
#include <utility>

namespace origamic::tips {
namespace {

using analysis::Chord;
using analysis::Ring;
using exact::nearest_double;
using exact::Point;

// The stretches inside the face on the line at u (no vertex there): each between two edges.
struct Stretch {
  const UvEdge* lo;
  const UvEdge* hi;
};
std::vector<Stretch> stretches_at(const std::vector<UvEdge>& edges, const FT& u) {
  std::vector<std::pair<FT, const UvEdge*>> crossings;
  for (const UvEdge& e : edges)
    if (e.u0 < u && u < e.u1) crossings.emplace_back(e.v_at(u), &e);
  std::sort(crossings.begin(), crossings.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Stretch> out;
  for (std::size_t k = 0; k + 1 < crossings.size(); k += 2)
    out.push_back({crossings[k].second, crossings[k + 1].second});
  return out;
}

// A new cut's line goes no nearer another vertex's line of its face than this, a hundredth of a
// millimetre (below any cutter's kerf), or onto it: on the 37 models at W = 3 mm the places
// narrower than it went 41 -> 23 (37 before any tip), and the places narrower than W 4,256 ->
// 4,278, tips that would have parted such a sliver staying.
constexpr double kSliver_mm = 0.01;

// A forked tip's branches are followed this many steps (a branch from one vertex line to the next)
// in all, at most: a bound on the work for a face with very many vertex lines within a tip's reach.
constexpr int kMaxBranchSteps = 256;

}  // namespace

FaceLines face_lines(const std::vector<Ring>& rings, bool along_Y) {
  FaceLines face;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point &p = ring[i], &q = ring[(i + 1) % ring.size()];
      const FT pu = along_Y ? p.x() : p.y(), pv = along_Y ? p.y() : p.x();
      const FT qu = along_Y ? q.x() : q.y(), qv = along_Y ? q.y() : q.x();
      face.us.push_back(pu);
      if (pu != qu) face.edges.push_back(pu < qu ? UvEdge{pu, pv, qu, qv} : UvEdge{qu, qv, pu, pv});
    }
  std::sort(face.us.begin(), face.us.end());
  face.us.erase(std::unique(face.us.begin(), face.us.end()), face.us.end());
  return face;
}

std::optional<Tip> tip_of(const FaceLines& face, std::size_t region, bool along_Y, const Chord& chord, const FT& W,
                          const FT& wide, const FT& reach) {
  // Every edge ends on vertex lines, and every slab walked starts on one within reach of the chord:
  // an edge across a slab walked reaches within `reach` of the chord.
  std::vector<UvEdge> edges;
  const FT reach_lo = chord.at - reach, reach_hi = chord.at + reach;
  for (const UvEdge& e : face.edges)
    if (e.u0 <= reach_hi && reach_lo <= e.u1) edges.push_back(e);
  const std::vector<FT>& us = face.us;
  const auto at = static_cast<std::ptrdiff_t>(std::lower_bound(us.begin(), us.end(), chord.at) - us.begin());
  enum class End { Gone, Wide, Step, Fork, Far };
  struct Walk {
    End end = End::Far;
    FT u;           // where it widens to `wide`
    FT v_lo, v_hi;  // a Step's stretch
    const UvEdge* lo = nullptr;
    const UvEdge* hi = nullptr;
    std::optional<std::pair<FT, FT>> first_inside;  // a point inside the first stretch walked
    std::ptrdiff_t fork_k = -1;                     // a Fork's vertex line (us), and the stretch there
    FT fork_lo, fork_hi;
  };
  // The stretches of the face in the slab from the vertex line us[k] to the next on `step`'s side
  // that meet [lo, hi], its stretch on us[k].
  const auto stretches_from = [&](std::ptrdiff_t k, int step, const FT& lo, const FT& hi) {
    const FT &u0 = us[static_cast<std::size_t>(k)], &u1 = us[static_cast<std::size_t>(k + step)];
    std::vector<Stretch> met;
    for (const Stretch& s : stretches_at(edges, (u0 + u1) / 2))
      if (s.lo->v_at(u0) <= hi && lo <= s.hi->v_at(u0)) met.push_back(s);
    return met;
  };
  const auto walk = [&](int step) {
    Walk w;
    FT lo = chord.lo, hi = chord.hi;
    for (std::ptrdiff_t k = at; k + step >= 0 && k + step < static_cast<std::ptrdiff_t>(us.size()); k += step) {
      const FT &u0 = us[static_cast<std::size_t>(k)], &u1 = us[static_cast<std::size_t>(k + step)];
      if (CGAL::abs(u0 - chord.at) > reach) return w;
      const FT mid = (u0 + u1) / 2;
      const std::vector<Stretch> met = stretches_from(k, step, lo, hi);
      if (met.size() > 1) return w.end = End::Fork, w.fork_k = k, w.fork_lo = lo, w.fork_hi = hi, w;
      if (met.empty()) return w.end = End::Gone, w;
      const Stretch& next = met.front();
      if (!w.first_inside) w.first_inside = {mid, (next.lo->v_at(mid) + next.hi->v_at(mid)) / 2};
      const FT w0 = next.hi->v_at(u0) - next.lo->v_at(u0), w1 = next.hi->v_at(u1) - next.lo->v_at(u1);
      if (w0 >= wide) {  // it widens at a step of its sides: the tip ends there, as wide as it was
        w.end = End::Step, w.u = u0, w.v_lo = lo, w.v_hi = hi;
        return w;
      }
      if (w1 >= wide) {
        w.end = End::Wide, w.lo = next.lo, w.hi = next.hi;
        w.u = u0 + (u1 - u0) * (wide - w0) / (w1 - w0);
        return w;
      }
      lo = next.lo->v_at(u1), hi = next.hi->v_at(u1);
    }
    // Past the face's last vertex: it ends there, which must be within reach too.
    w.end = CGAL::abs(us[static_cast<std::size_t>(step > 0 ? us.size() - 1 : 0)] - chord.at) <= reach ? End::Gone
                                                                                                      : End::Far;
    return w;
  };
  // Whether the face beyond the vertex line us[k], from its stretch [lo, hi] there on `step`'s side,
  // ends within reach, however it branches, under W across all the way.
  const auto ends_within = [&](std::ptrdiff_t k, const FT& lo, const FT& hi, int step) {
    struct Branch {
      std::ptrdiff_t k;
      FT lo, hi;
    };
    std::vector<Branch> open{{k, lo, hi}};
    for (int walked = 0; !open.empty(); ++walked) {
      if (walked >= kMaxBranchSteps) return false;
      const Branch b = open.back();
      open.pop_back();
      const FT& u0 = us[static_cast<std::size_t>(b.k)];
      if (CGAL::abs(u0 - chord.at) > reach) return false;
      if (b.k + step < 0 || b.k + step >= static_cast<std::ptrdiff_t>(us.size())) continue;
      const FT& u1 = us[static_cast<std::size_t>(b.k + step)];
      for (const Stretch& s : stretches_from(b.k, step, b.lo, b.hi)) {
        if (!(s.hi->v_at(u0) - s.lo->v_at(u0) < W && s.hi->v_at(u1) - s.lo->v_at(u1) < W)) return false;
        open.push_back({b.k + step, s.lo->v_at(u1), s.hi->v_at(u1)});
      }
    }
    return true;
  };
  // Where the face forks on a walk (a corner of another face pokes into it), a branch that ends
  // within reach of the chord, under W across all the way, is a tip parted where it forks, on that
  // vertex line (a branch of no length there leaves nothing to cut). At W = 3 mm over the 37 models:
  // places 3,961 -> 3,922, chords under W 45,389 -> 44,410, the mean p95 1.717 -> 1.718 W, the
  // model-edge tests as they were (design_model_edges_test.cpp), a fork on the chord's own line
  // included. Parting a face that steps wide on the chord's line without a fork (above) as well
  // took places to 3,775, but its spikes, given across the model's silhouettes, took the turned
  // box's back edges under 90 % drawn.
  const auto branch_tip = [&](const Walk& w, int step) -> std::optional<Tip> {
    if (w.end != End::Fork) return std::nullopt;
    const FT &u0 = us[static_cast<std::size_t>(w.fork_k)], &u1 = us[static_cast<std::size_t>(w.fork_k + step)];
    const FT mid = (u0 + u1) / 2;
    for (const Stretch& s : stretches_from(w.fork_k, step, w.fork_lo, w.fork_hi)) {
      const FT lo = s.lo->v_at(u0), hi = s.hi->v_at(u0);
      if (lo < hi && hi - lo < W && s.hi->v_at(u1) - s.lo->v_at(u1) < W &&
          ends_within(w.fork_k + step, s.lo->v_at(u1), s.hi->v_at(u1), step))
        return Tip{region, along_Y, u0, lo, hi, mid, (s.lo->v_at(mid) + s.hi->v_at(mid)) / 2};
    }
    return std::nullopt;
  };
  const Walk down = walk(-1), up = walk(1);
  const auto widens = [](const Walk& w) { return w.end == End::Wide || w.end == End::Step; };
  const bool cut_up = down.end == End::Gone && widens(up);
  const bool cut_down = up.end == End::Gone && widens(down);
  if (!cut_up && !cut_down) {
    if (std::optional<Tip> tip = branch_tip(down, -1)) return tip;
    return branch_tip(up, 1);
  }
  const Walk& wide_side = cut_up ? up : down;
  const Walk& tip_side = cut_up ? down : up;
  if (CGAL::abs(wide_side.u - chord.at) > reach) return std::nullopt;
  if (wide_side.end == End::Step) {
    if (wide_side.u == chord.at) return std::nullopt;  // the chord itself ends at the step
    const auto& inside = tip_side.first_inside ? tip_side.first_inside : wide_side.first_inside;
    if (!inside) return std::nullopt;
    return Tip{region, along_Y, wide_side.u, wide_side.v_lo, wide_side.v_hi, inside->first, inside->second};
  }
  // The cut at a double, so that its ends on the face's sides are where the lines are drawn. Within
  // kSliver_mm of another vertex's line it would part a sliver that thin off the face (capitol: a
  // cut 0.00018 mm beside another): it goes on that line, past it or short of it while the face is
  // W wide there, or nowhere.
  FT u = nearest_double(wide_side.u);
  const auto line_near = [&](const FT& x, const FT& skip) {  // the nearest vertex line within kSliver_mm
    std::optional<FT> found;
    const auto next = std::lower_bound(us.begin(), us.end(), x);
    for (const auto it : {next, next == us.begin() ? next : next - 1})
      if (it != us.end() && *it != x && *it != skip && CGAL::abs(*it - x) < FT(kSliver_mm) &&
          (!found || CGAL::abs(*it - x) < CGAL::abs(*found - x)))
        found = *it;
    return found;
  };
  if (const std::optional<FT> line = line_near(u, u)) {
    const FT from = u;
    u = *line;
    if (line_near(u, from)) return std::nullopt;  // two lines that near: a sliver either way
  }
  if ((u - chord.at) * (wide_side.u - chord.at) <= 0 || (cut_up ? u < wide_side.lo->u0 : u > wide_side.lo->u1) ||
      u < CGAL::max(wide_side.lo->u0, wide_side.hi->u0) || u > CGAL::min(wide_side.lo->u1, wide_side.hi->u1))
    return std::nullopt;
  // Short of where the face is `wide`, it must still be W wide.
  if ((u - wide_side.u) * (wide_side.u - chord.at) < 0 && !(wide_side.hi->v_at(u) - wide_side.lo->v_at(u) >= W))
    return std::nullopt;
  Tip tip{region, along_Y, u, wide_side.lo->v_at(u), wide_side.hi->v_at(u), 0, 0};
  const auto& inside = tip_side.first_inside ? tip_side.first_inside : wide_side.first_inside;
  if (!inside) return std::nullopt;
  // The wide side's first point may lie past the cut: then the tip is the stretch before it.
  if (!tip_side.first_inside && (inside->first - u) * (chord.at - u) <= 0) return std::nullopt;
  tip.inside_u = inside->first, tip.inside_v = inside->second;
  return tip;
}

}  // namespace origamic::tips
