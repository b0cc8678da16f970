// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23: where a face narrower than W ends in a tip (tips.hpp), walked across the chord on
// exact numbers. One exact run at a time: see exact_runs.hpp.
#define CGAL_HAS_NO_THREADS 1

#include <algorithm>
#include <utility>

#include "tips.hpp"

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

// How a walk across the chord, one way, ends: the face ends within reach (Gone), widens to `wide`
// between two vertex lines (Wide) or is that wide on one (Step), forks, or goes on past reach (Far).
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

// The point inside the tip: the first walked on the tip's side, else the first on the wide side.
const std::optional<std::pair<FT, FT>>& inside_point(const Walk& tip_side, const Walk& wide_side) {
  return tip_side.first_inside ? tip_side.first_inside : wide_side.first_inside;
}

// Every edge ends on vertex lines, and every slab walked starts on one within reach of the chord:
// an edge across a slab walked reaches within `reach` of the chord.
std::vector<UvEdge> edges_near(const std::vector<UvEdge>& edges, const Chord& chord, const FT& reach) {
  std::vector<UvEdge> near;
  const FT reach_lo = chord.at - reach, reach_hi = chord.at + reach;
  for (const UvEdge& e : edges)
    if (e.u0 <= reach_hi && reach_lo <= e.u1) near.push_back(e);
  return near;
}

// A face walked across a chord from its vertex line, one vertex line at a time (tip_of).
class TipWalk {
 public:
  TipWalk(const FaceLines& face, std::size_t region, bool along_Y, const Chord& chord, const FT& W, const FT& wide,
          const FT& reach)
      : edges_(edges_near(face.edges, chord, reach)),
        us_(face.us),
        at_(static_cast<std::ptrdiff_t>(std::lower_bound(us_.begin(), us_.end(), chord.at) - us_.begin())),
        region_(region),
        along_Y_(along_Y),
        chord_(chord),
        W_(W),
        wide_(wide),
        reach_(reach) {}
  TipWalk(const TipWalk&) = delete;  // a walk's edges point into edges_
  TipWalk& operator=(const TipWalk&) = delete;

  // From the chord to the next vertex line on `step`'s side (-1 or 1) and on, while the face meets
  // one stretch there, until it ends, forks, widens to `wide` or passes reach.
  Walk walk(int step) const {
    Walk w;
    FT lo = chord_.lo, hi = chord_.hi;
    for (std::ptrdiff_t k = at_; has_line(k + step); k += step) {
      const FT &u0 = u_of(k), &u1 = u_of(k + step);
      if (CGAL::abs(u0 - chord_.at) > reach_) return w;
      const FT mid = (u0 + u1) / 2;
      const std::vector<Stretch> met = stretches_from(k, step, lo, hi);
      if (met.size() > 1) return w.end = End::Fork, w.fork_k = k, w.fork_lo = lo, w.fork_hi = hi, w;
      if (met.empty()) return w.end = End::Gone, w;
      const Stretch& next = met.front();
      if (!w.first_inside) w.first_inside = {mid, (next.lo->v_at(mid) + next.hi->v_at(mid)) / 2};
      const FT w0 = next.hi->v_at(u0) - next.lo->v_at(u0), w1 = next.hi->v_at(u1) - next.lo->v_at(u1);
      if (w0 >= wide_) {  // it widens at a step of its sides: the tip ends there, as wide as it was
        w.end = End::Step, w.u = u0, w.v_lo = lo, w.v_hi = hi;
        return w;
      }
      if (w1 >= wide_) {
        w.end = End::Wide, w.lo = next.lo, w.hi = next.hi;
        w.u = u0 + (u1 - u0) * (wide_ - w0) / (w1 - w0);
        return w;
      }
      lo = next.lo->v_at(u1), hi = next.hi->v_at(u1);
    }
    // Past the face's last vertex: it ends there, which must be within reach too.
    w.end = CGAL::abs(us_[step > 0 ? us_.size() - 1 : 0] - chord_.at) <= reach_ ? End::Gone : End::Far;
    return w;
  }

  // Where the face forks on a walk (a corner of another face pokes into it), a branch that ends
  // within reach of the chord, under W across all the way, is a tip parted where it forks, on that
  // vertex line (a branch of no length there leaves nothing to cut). At W = 3 mm over the 37 models:
  // places 3,961 -> 3,922, chords under W 45,389 -> 44,410, the mean p95 1.717 -> 1.718 W, the
  // model-edge tests as they were (design_model_edges_test.cpp), a fork on the chord's own line
  // included. Parting a face that steps wide on the chord's line without a fork (above) as well
  // took places to 3,775, but its spikes, given across the model's silhouettes, took the turned
  // box's back edges under 90 % drawn.
  std::optional<Tip> branch_tip(const Walk& w, int step) const {
    if (w.end != End::Fork) return std::nullopt;
    const FT &u0 = u_of(w.fork_k), &u1 = u_of(w.fork_k + step);
    const FT mid = (u0 + u1) / 2;
    for (const Stretch& s : stretches_from(w.fork_k, step, w.fork_lo, w.fork_hi)) {
      const FT lo = s.lo->v_at(u0), hi = s.hi->v_at(u0);
      if (lo < hi && hi - lo < W_ && s.hi->v_at(u1) - s.lo->v_at(u1) < W_ &&
          ends_within(w.fork_k + step, s.lo->v_at(u1), s.hi->v_at(u1), step))
        return Tip{region_, along_Y_, u0, lo, hi, mid, (s.lo->v_at(mid) + s.hi->v_at(mid)) / 2};
    }
    return std::nullopt;
  }

  // The cut where the face, ended on `tip_side`, widens on `wide_side` (up across the chord if
  // cut_up), if that is within reach.
  std::optional<Tip> cut_on_wide_side(const Walk& wide_side, const Walk& tip_side, bool cut_up) const {
    if (CGAL::abs(wide_side.u - chord_.at) > reach_) return std::nullopt;
    if (wide_side.end == End::Step) return cut_at_step(wide_side, tip_side);
    return cut_where_wide(wide_side, tip_side, cut_up);
  }

 private:
  std::vector<UvEdge> edges_;  // the face's edges near the chord (edges_near)
  const std::vector<FT>& us_;
  std::ptrdiff_t at_;  // the chord's vertex line (us_)
  std::size_t region_;
  bool along_Y_;
  const Chord& chord_;
  const FT &W_, &wide_, &reach_;

  const FT& u_of(std::ptrdiff_t k) const { return us_[static_cast<std::size_t>(k)]; }
  bool has_line(std::ptrdiff_t k) const { return k >= 0 && k < static_cast<std::ptrdiff_t>(us_.size()); }

  // The stretches of the face in the slab from the vertex line us[k] to the next on `step`'s side
  // that meet [lo, hi], its stretch on us[k].
  std::vector<Stretch> stretches_from(std::ptrdiff_t k, int step, const FT& lo, const FT& hi) const {
    const FT &u0 = u_of(k), &u1 = u_of(k + step);
    std::vector<Stretch> met;
    for (const Stretch& s : stretches_at(edges_, (u0 + u1) / 2))
      if (s.lo->v_at(u0) <= hi && lo <= s.hi->v_at(u0)) met.push_back(s);
    return met;
  }

  // Whether the face beyond the vertex line us[k], from its stretch [lo, hi] there on `step`'s side,
  // ends within reach, however it branches, under W across all the way.
  bool ends_within(std::ptrdiff_t k, const FT& lo, const FT& hi, int step) const {
    struct Branch {
      std::ptrdiff_t k;
      FT lo, hi;
    };
    std::vector<Branch> open{{k, lo, hi}};
    for (int walked = 0; !open.empty(); ++walked) {
      if (walked >= kMaxBranchSteps) return false;
      const Branch b = open.back();
      open.pop_back();
      const FT& u0 = u_of(b.k);
      if (CGAL::abs(u0 - chord_.at) > reach_) return false;
      if (!has_line(b.k + step)) continue;
      const FT& u1 = u_of(b.k + step);
      for (const Stretch& s : stretches_from(b.k, step, b.lo, b.hi)) {
        if (!(s.hi->v_at(u0) - s.lo->v_at(u0) < W_ && s.hi->v_at(u1) - s.lo->v_at(u1) < W_)) return false;
        open.push_back({b.k + step, s.lo->v_at(u1), s.hi->v_at(u1)});
      }
    }
    return true;
  }

  // At a step of its sides the tip ends on that vertex line, as wide as it was.
  std::optional<Tip> cut_at_step(const Walk& wide_side, const Walk& tip_side) const {
    if (wide_side.u == chord_.at) return std::nullopt;  // the chord itself ends at the step
    const auto& inside = inside_point(tip_side, wide_side);
    if (!inside) return std::nullopt;
    return Tip{region_, along_Y_, wide_side.u, wide_side.v_lo, wide_side.v_hi, inside->first, inside->second};
  }

  // Where it widens between two vertex lines the cut goes there or on a vertex line near it
  // (cut_u), on the chord's wide side, across the two edges it widens between.
  std::optional<Tip> cut_where_wide(const Walk& wide_side, const Walk& tip_side, bool cut_up) const {
    const std::optional<FT> cut = cut_u(wide_side.u);
    if (!cut) return std::nullopt;
    const FT& u = *cut;
    if ((u - chord_.at) * (wide_side.u - chord_.at) <= 0 || (cut_up ? u < wide_side.lo->u0 : u > wide_side.lo->u1) ||
        u < CGAL::max(wide_side.lo->u0, wide_side.hi->u0) || u > CGAL::min(wide_side.lo->u1, wide_side.hi->u1))
      return std::nullopt;
    // Short of where the face is `wide`, it must still be W wide.
    if ((u - wide_side.u) * (wide_side.u - chord_.at) < 0 && !(wide_side.hi->v_at(u) - wide_side.lo->v_at(u) >= W_))
      return std::nullopt;
    Tip tip{region_, along_Y_, u, wide_side.lo->v_at(u), wide_side.hi->v_at(u), 0, 0};
    const auto& inside = inside_point(tip_side, wide_side);
    if (!inside) return std::nullopt;
    // The wide side's first point may lie past the cut: then the tip is the stretch before it.
    if (!tip_side.first_inside && (inside->first - u) * (chord_.at - u) <= 0) return std::nullopt;
    tip.inside_u = inside->first, tip.inside_v = inside->second;
    return tip;
  }

  // The cut at a double, so that its ends on the face's sides are where the lines are drawn. Within
  // kSliver_mm of another vertex's line it would part a sliver that thin off the face (capitol: a
  // cut 0.00018 mm beside another): it goes on that line, past it or short of it while the face is
  // W wide there (cut_where_wide), or nowhere.
  std::optional<FT> cut_u(const FT& wide_u) const {
    FT u = nearest_double(wide_u);
    if (const std::optional<FT> line = line_near(u, u)) {
      const FT from = u;
      u = *line;
      if (line_near(u, from)) return std::nullopt;  // two lines that near: a sliver either way
    }
    return u;
  }

  // The nearest vertex line within kSliver_mm of x, other than x and `skip`.
  std::optional<FT> line_near(const FT& x, const FT& skip) const {
    std::optional<FT> found;
    const auto next = std::lower_bound(us_.begin(), us_.end(), x);
    for (const auto it : {next, next == us_.begin() ? next : next - 1})
      if (it != us_.end() && *it != x && *it != skip && CGAL::abs(*it - x) < FT(kSliver_mm) &&
          (!found || CGAL::abs(*it - x) < CGAL::abs(*found - x)))
        found = *it;
    return found;
  }
};

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
  const TipWalk across(face, region, along_Y, chord, W, wide, reach);
  const Walk down = across.walk(-1), up = across.walk(1);
  const auto widens = [](const Walk& w) { return w.end == End::Wide || w.end == End::Step; };
  const bool cut_up = down.end == End::Gone && widens(up);
  const bool cut_down = up.end == End::Gone && widens(down);
  if (!cut_up && !cut_down) {
    if (std::optional<Tip> tip = across.branch_tip(down, -1)) return tip;
    return across.branch_tip(up, 1);
  }
  return cut_up ? across.cut_on_wide_side(up, down, true) : across.cut_on_wide_side(down, up, false);
}

}  // namespace origamic::tips
