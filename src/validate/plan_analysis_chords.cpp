// SPDX-License-Identifier: GPL-3.0-or-later
// Strips narrower than W: the narrowest chords of a face along Y and along X through each of its
// vertices, found on intervals and, where they cannot decide, exactly; and the analysis's check of
// them (Analyzer::check_strips), with the fold pairs among them. One exact run at a time: see
// exact_runs.hpp; the searches on intervals run in parallel.
#define CGAL_HAS_NO_THREADS 1

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plan_analysis_geometry.hpp"

namespace origamic::analysis {
namespace {

using exact::FT;
using exact::nearest_double;
using exact::Point;
using Interval = CGAL::Interval_nt<false>;

// A coordinate of a ring's point: its interval (no lazy number made) or its exact number.
template <typename NT>
NT coordinate(const Point& p, bool x);
template <>
Interval coordinate<Interval>(const Point& p, bool x) {
  return x ? p.approx().x() : p.approx().y();
}
template <>
FT coordinate<FT>(const Point& p, bool x) {
  return x ? p.x() : p.y();
}

// The v at u of the segment from (u0, v0) to (u1, v1), u0 <= u <= u1: at an end its own, else where
// it crosses the line at u.
template <typename NT>
NT v_at(const NT& u0, const NT& v0, const NT& u1, const NT& v1, const NT& u) {
  return u == u0 ? v0 : u == u1 ? v1 : crossing_v(u0, v0, u1, v1, u);
}

// What the chord search found: where the narrowest chord is, if any, where the others narrower than
// W are, and how many there are.
struct ChordSearch {
  std::optional<ChordPlace> narrowest;
  int narrow = 0;
  std::vector<ChordPlace> others;  // the other chords narrower than W, in the order found
};

// The shortest chord through a vertex, along Y (vertical chords at each vertex X) or along X, that is
// longer than zero (a corner's tip is no strip) and shorter than W, on one number type, where the
// other such chords are, and how many there are. A chord is a stretch of the face along the
// line just before it or just after it (half-open crossing rules on each side), each side on its
// own: where a side of the face runs along the line, as a notch's wall does, the face on the line's
// other side may be narrower than the closed face on the line. Taken as the union of the two sides,
// the strip under a notch or beside a hole, whose corners are its only vertices, was not seen: 4,447
// places at W = 3 mm over the 37 plans, 4,734 seen so (teeth of a traced line a fraction of a
// millimetre high, strips of a face between a notch and a fold).
template <typename NT>
ChordSearch search_chords(const std::vector<Ring>& rings, bool along_Y, const NT& W) {
  struct Edge {
    NT u0, v0, u1, v1;                 // u across the chord, v along it; u0 <= u1
    std::array<const Point*, 2> ends;  // at u0, at u1
  };
  struct Vertex {
    NT u, v;
    const Point* p;
  };
  struct End {
    NT v;
    const Edge* edge;
  };
  struct Piece {
    End lo, hi;
  };
  // One edge's ends on the line are one number, which its intervals, if not a point, cannot say.
  const auto less = [](const End& a, const End& b) -> bool { return a.edge != b.edge && a.v < b.v; };
  const auto same = [](const End& a, const End& b) -> bool { return a.edge == b.edge || a.v == b.v; };
  std::vector<Edge> edges;
  std::vector<Vertex> vertices;  // each coordinate read off its point once
  for (const Ring& ring : rings) {
    const std::size_t first = vertices.size();
    for (const Point& p : ring) vertices.push_back({coordinate<NT>(p, along_Y), coordinate<NT>(p, !along_Y), &p});
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Vertex &p = vertices[first + i], &q = vertices[first + (i + 1) % ring.size()];
      edges.push_back(p.u <= q.u ? Edge{p.u, p.v, q.u, q.v, {p.p, q.p}} : Edge{q.u, q.v, p.u, p.v, {q.p, p.p}});
    }
  }
  std::sort(vertices.begin(), vertices.end(),
            [](const Vertex& a, const Vertex& b) -> bool { return a.u < b.u || (!(b.u < a.u) && a.v < b.v); });
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) -> bool { return a.u0 < b.u0; });
  ChordSearch found;
  NT best_length = 0;
  std::vector<const Edge*> active;
  std::vector<End> after, before;
  std::vector<Piece> pieces;
  std::vector<std::uint8_t> counted;
  std::size_t next_edge = 0;
  for (std::size_t i = 0; i < vertices.size();) {
    const NT u = vertices[i].u;
    std::size_t j = i + 1;  // not i: a vertex's interval that is no point cannot say it equals itself
    while (j < vertices.size() && vertices[j].u == u) ++j;
    while (next_edge < edges.size() && edges[next_edge].u0 <= u) active.push_back(&edges[next_edge++]);
    std::erase_if(active, [&](const Edge* e) -> bool { return e->u1 < u; });
    after.clear(), before.clear();
    for (const Edge* e : active) {
      if (e->u0 == e->u1) continue;  // along the line: both faces' sides come from the other edges
      const NT v = v_at(e->u0, e->v0, e->u1, e->v1, u);
      if (e->u0 <= u && u < e->u1) after.push_back({v, e});
      if (e->u0 < u && u <= e->u1) before.push_back({v, e});
    }
    pieces.clear();
    for (std::vector<End>* side : {&after, &before}) {
      std::sort(side->begin(), side->end(), less);
      for (std::size_t k = 0; k + 1 < side->size(); k += 2) pieces.push_back({(*side)[k], (*side)[k + 1]});
    }
    // A stretch the same on both sides (the face crosses the line there) is one chord.
    std::sort(pieces.begin(), pieces.end(), [&](const Piece& a, const Piece& b) {
      return less(a.lo, b.lo) || (!less(b.lo, a.lo) && less(a.hi, b.hi));
    });
    pieces.erase(std::unique(pieces.begin(), pieces.end(),
                             [&](const Piece& a, const Piece& b) { return same(a.lo, b.lo) && same(a.hi, b.hi); }),
                 pieces.end());
    counted.assign(pieces.size(), 0);
    for (std::size_t k = i; k < j; ++k)
      for (std::size_t m = 0; m < pieces.size(); ++m) {
        const Piece& piece = pieces[m];
        if (vertices[k].v < piece.lo.v || piece.hi.v < vertices[k].v || counted[m]) continue;
        counted[m] = 1;  // vertices of one chord count it once
        const NT length = piece.hi.v - piece.lo.v;
        if (!CGAL::is_positive(length) || !(length < W)) continue;
        ++found.narrow;
        const ChordPlace place{vertices[i].p, piece.lo.edge->ends, piece.hi.edge->ends, CGAL::to_double(length)};
        if (!found.narrowest || length < best_length) {
          if (found.narrowest) found.others.push_back(*found.narrowest);
          found.narrowest = place, best_length = length;
        } else {
          found.others.push_back(place);
        }
      }
    i = j;
  }
  return found;
}

// The exact v at u of an edge (its ends at u0 and u1, u0 <= u <= u1), as the chord search made it.
FT exact_v(const std::array<const Point*, 2>& edge, bool along_Y, const FT& u) {
  const FT u0 = coordinate<FT>(*edge[0], along_Y), v0 = coordinate<FT>(*edge[0], !along_Y);
  const FT u1 = coordinate<FT>(*edge[1], along_Y), v1 = coordinate<FT>(*edge[1], !along_Y);
  return v_at(u0, v0, u1, v1, u);
}

}  // namespace

Chord chord_of(const ChordPlace& place, bool along_Y) {
  const FT at = coordinate<FT>(*place.vertex, along_Y);
  return Chord{at, exact_v(place.lo, along_Y, at), exact_v(place.hi, along_Y, at)};
}

// The searches run on the vertices' intervals, which make no lazy number and decide all but a few
// faces' comparisons (an uncertain one throws: res_dragon_full, 31 of 4,272 searches), in parallel:
// they only read the intervals, which no exact number is made to change meanwhile. Then, one after
// another, those left on exact numbers, and the exact chords. Both searches give the same chord:
// every comparison the intervals decide, they decide as the exact numbers do.
std::vector<FaceChords> narrowest_chords(const std::vector<std::vector<Ring>>& rings,
                                         const std::vector<std::uint8_t>& skip, const FT& W) {
  std::vector<std::array<std::optional<ChordSearch>, 2>> found(rings.size());  // none: undecided
  const Interval W_interval = W.approx();
  tbb::parallel_for(std::size_t{0}, rings.size(), [&](std::size_t f) {
    if (skip[f]) return;
    for (const int axis : {0, 1}) {
      try {
        const CGAL::Protect_FPU_rounding<true> rounding;
        found[f][static_cast<std::size_t>(axis)] = search_chords<Interval>(rings[f], axis == 0, W_interval);
      } catch (const CGAL::Uncertain_conversion_exception&) {  // left undecided
      }
    }
  });
  std::vector<FaceChords> chords(rings.size());
  for (std::size_t f = 0; f < rings.size(); ++f) {
    if (skip[f]) continue;
    for (const int axis : {0, 1}) {
      const bool along_Y = axis == 0;
      std::optional<ChordSearch>& in = found[f][static_cast<std::size_t>(axis)];
      if (!in) in = search_chords<FT>(rings[f], along_Y, W);
      chords[f].narrow[static_cast<std::size_t>(axis)] = in->narrow;
      if (!in->narrowest) continue;
      chords[f].narrowest[static_cast<std::size_t>(axis)] = chord_of(*in->narrowest, along_Y);
      std::vector<ChordPlace>& others = chords[f].others[static_cast<std::size_t>(axis)] = std::move(in->others);
      std::ranges::stable_sort(others, {}, &ChordPlace::length);
    }
  }
  return chords;
}

// ---------------------------------------------------------------------------------------------
// The analysis's strips narrower than W (Analyzer::check_strips), and the fold pairs among them.

std::optional<Analyzer::FoldPair> Analyzer::nearest_fold_pair(std::size_t r) const {
  std::optional<FoldPair> best;
  const auto region = static_cast<std::int32_t>(r);
  for (const std::size_t i : folds_of[r]) {
    const FoldEdge& below = folds[i];
    if (below.upper != region) continue;
    for (const std::size_t j : folds_of[r]) {
      const FoldEdge& above = folds[j];
      if (above.lower != region || !(below.Y < above.Y) || !(above.Y - below.Y < W)) continue;
      if (best && !(above.Y - below.Y < best->hi - best->lo)) continue;
      const FT X_lo = CGAL::max(below.X_lo, above.X_lo), X_hi = CGAL::min(below.X_hi, above.X_hi);
      if (!(X_lo < X_hi)) continue;
      if (const std::optional<FT> X = open_between(r, X_lo, X_hi, below.Y, above.Y))
        best = FoldPair{*X, below.Y, above.Y};
    }
  }
  return best;
}

std::optional<FT> Analyzer::open_between(std::size_t r, const FT& X_lo, const FT& X_hi, const FT& lo,
                                         const FT& hi) const {
  std::vector<FT> breaks{X_lo, X_hi};
  for (const Ring& ring : rings[r])
    for (const Point& p : ring)
      if (X_lo < p.x() && p.x() < X_hi) breaks.push_back(p.x());
  std::sort(breaks.begin(), breaks.end());
  const auto middle = (X_lo + X_hi) / 2;
  if (!crosses_between(r, middle, lo, hi)) return middle;
  for (std::size_t k = 1; k < breaks.size(); ++k)
    if (breaks[k - 1] < breaks[k]) {
      const FT X = (breaks[k - 1] + breaks[k]) / 2;
      if (!crosses_between(r, X, lo, hi)) return X;
    }
  return std::nullopt;
}

bool Analyzer::crosses_between(std::size_t r, const FT& X, const FT& lo, const FT& hi) const {
  for (const Ring& ring : rings[r])
    for (std::size_t k = 0; k < ring.size(); ++k) {
      const Point &p = ring[k], &q = ring[(k + 1) % ring.size()];
      if ((p.x() < X && q.x() < X) || (X < p.x() && X < q.x())) continue;
      if (p.x() == q.x()) {  // along the segment's line: it meets it where their Y ranges overlap
        if (CGAL::min(p.y(), q.y()) < hi && lo < CGAL::max(p.y(), q.y())) return true;
        continue;
      }
      const FT Y = crossing_v(p.x(), p.y(), q.x(), q.y(), X);
      if (lo < Y && Y < hi) return true;
    }
  return false;
}

void Analyzer::check_strips() {
  std::vector<FaceChords> chords = narrowest_chords(rings, cut_out, W);
  narrowest.assign(faces.size(), {});
  other_chords.assign(faces.size(), {});
  for (std::size_t r = 0; r < faces.size(); ++r)
    for (const bool along_Y : {true, false}) {
      const std::size_t axis = along_Y ? 0 : 1;
      const int narrow = chords[r].narrow[axis];
      other_chords[r][axis] = std::move(chords[r].others[axis]);
      const std::optional<Chord>& chord = narrowest[r][axis] = chords[r].narrowest[axis];
      if (!chord) continue;
      const Point a = along_Y ? Point(chord->at, chord->lo) : Point(chord->lo, chord->at);
      const Point b = along_Y ? Point(chord->at, chord->hi) : Point(chord->hi, chord->at);
      const PlanPoint from = plan_point(a), to = plan_point(b);
      const double width = nearest_double(chord->hi - chord->lo);
      const std::string where = along_Y ? "at X = " + num(from.X) + " from Y = " + num(from.Y) + " to " + num(to.Y)
                                        : "at Y = " + num(from.Y) + " from X = " + num(from.X) + " to " + num(to.X);
      PlanProblem problem{PlanProblemKind::NarrowStrip,
                          plan_point(CGAL::midpoint(a, b)),
                          from,
                          to,
                          static_cast<std::int32_t>(r),
                          width,
                          "face " + (place[r].placed ? face_text(place[r]) + " " : "") + "at " +
                              point_text(result.regions[r].inside) + " is " + num(width) + " mm wide along " +
                              (along_Y ? "Y " : "X ") + where + ", under W = " + num(options.min_strip_mm) + " mm" +
                              (narrow > 1 ? " (" + std::to_string(narrow) + " such places)" : "")};
      problem.narrow_chords = narrow;
      if (const std::optional<FoldPair> pair = along_Y ? nearest_fold_pair(r) : std::nullopt) {
        const PlanPoint lo = plan_point(Point(pair->X, pair->lo)), hi = plan_point(Point(pair->X, pair->hi));
        problem.folds_apart_mm = nearest_double(pair->hi - pair->lo);
        problem.message += "; two of its folds, at Y = " + num(lo.Y) + " and " + num(hi.Y) + ", lie " +
                           num(problem.folds_apart_mm) + " mm apart at X = " + num(lo.X);
        ++result.narrow_between_folds;
      }
      add(std::move(problem));
    }
}

}  // namespace origamic::analysis
