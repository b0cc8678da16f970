// SPDX-License-Identifier: GPL-3.0-or-later
// The exact geometry under a plan's analysis (plan_analysis.cpp): the plan's lines collected onto the
// sheet and the faces of their arrangement as rings (the narrowest chords across a face are
// plan_analysis_chords.cpp's). CGAL is heavy to compile: the analysis has these three translation
// units and no more. One exact run at a time: see exact_runs.hpp.
#define CGAL_HAS_NO_THREADS 1

#include "plan_analysis_geometry.hpp"

#include <CGAL/intersections.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "origamic/error.hpp"
#include "origamic/mm_text.hpp"

namespace origamic::analysis {
namespace {

using exact::Arrangement;
using exact::FT;
using exact::Kernel;
using exact::nearest_double;
using exact::Point;
using exact::Traits;
using Face = Arrangement::Face_const_handle;
using Halfedge = Arrangement::Halfedge_const_handle;

}  // namespace

// Numbers in messages: plan mm to 1e-6, small amounts with three significant digits.
std::string num(double value) {
  if (value == 0 || std::abs(value) >= 1e-3) return mm_text(value);
  char text[64];
  std::snprintf(text, sizeof text, "%.3g", value);
  return text;
}

std::string point_text(PlanPoint p) { return "(" + num(p.X) + ", " + num(p.Y) + ")"; }

PlanPoint plan_point(const Point& p) { return {exact::nearest_coordinate(p, 0), exact::nearest_coordinate(p, 1)}; }

std::string face_text(const Place& place) {
  if (!place.placed) return "unplaced";
  return std::string(place.orientation == Orientation::V ? "V(" : "H(") + num(exact::nearest_double(place.depth)) + ")";
}

// ---------------------------------------------------------------------------------------------
// The arrangement of every line, clipped to the sheet.

namespace {

FT exact_unit(DrawingUnit unit) {
  switch (unit) {
    case DrawingUnit::Millimetre:
      return FT(1);
    case DrawingUnit::Centimetre:
      return FT(10);
    case DrawingUnit::Metre:
      return FT(1000);
    case DrawingUnit::Inch:
      return FT(254) / FT(10);
    case DrawingUnit::Foot:
      return FT(3048) / FT(10);
  }
  return FT(1);
}

// A horizontal piece of a fold as drawn: the whole fold, a printed dash or a perforation cut.
struct FoldPiece {
  FT Y, lo, hi;
  LineKind kind;
  bool perforation;
};

// Folds drawn in pieces stand for whole folds: collinear pieces of one kind with no cut (or outline)
// reaching their line between them are one fold, which ends where they do; perforations keep clear
// of the cuts, so a fold drawn with them runs on to the cut on either side (the sheet's edge if
// none). The ends are exact: a joined fold meets its cut at their exact crossing.
void add_joined_folds(std::vector<FoldPiece> pieces, Input& in) {
  struct Cut {
    Point p, q;
    double lo, hi;  // its Y range, a millimetre wider than its doubles say
    std::size_t index;  // among the cuts as drawn
  };
  std::vector<Cut> cuts;
  for (const Traits::Curve_2& curve : in.curves)
    if (in.kind[static_cast<std::size_t>(curve.data())] != LineKind::Mountain &&
        in.kind[static_cast<std::size_t>(curve.data())] != LineKind::Valley) {
      const double a = exact::approx_y(curve.source()), b = exact::approx_y(curve.target());
      cuts.push_back({curve.source(), curve.target(), std::min(a, b) - 1, std::max(a, b) + 1, cuts.size()});
    }
  // The folds' lines bottom to top, and the cuts by where their ranges start: each line looks only at
  // the cuts whose ranges hold it (res_dragon_full: each looked at all 7,582 cut segments).
  std::ranges::sort(cuts, {}, &Cut::lo);
  std::ranges::sort(pieces, [](const FoldPiece& a, const FoldPiece& b) {
    return std::tie(a.Y, a.kind, a.lo) < std::tie(b.Y, b.kind, b.lo);
  });
  std::vector<const Cut*> near;
  std::size_t next_cut = 0;
  // Where a point lies against the line Y: on the doubles where both are doubles (most), no lazy
  // number made.
  const auto compare_to_line = [](const Point& p, const FT& Y) {
    const CGAL::Interval_nt<false>&py = p.approx().y(), &y = Y.approx();
    return py.is_point() && y.is_point() ? CGAL::compare(py.inf(), y.inf()) : CGAL::compare(p.y(), Y);
  };
  std::vector<FT> crossings;
  for (std::size_t i = 0; i < pieces.size();) {
    const FT Y = pieces[i].Y;
    const double Y_double = CGAL::to_double(Y);
    while (next_cut < cuts.size() && cuts[next_cut].lo <= Y_double) near.push_back(&cuts[next_cut++]);
    std::erase_if(near, [&](const Cut* cut) { return cut->hi < Y_double; });
    // In the order drawn, as before the sweep: the crossings' sort below is not stable, and which of
    // two equal crossings ends a fold follows the order they came in. They are one exact number but
    // may have different intervals, which the doubles of areas and lengths are read from.
    std::ranges::sort(near, {}, &Cut::index);
    crossings.clear();
    for (const Cut* cut : near) {
      const Point &p = cut->p, &q = cut->q;
      const CGAL::Comparison_result sp = compare_to_line(p, Y), sq = compare_to_line(q, Y);
      if (sp == sq && sp != CGAL::EQUAL) continue;
      if (sp == CGAL::EQUAL) crossings.push_back(p.x());
      if (sq == CGAL::EQUAL) crossings.push_back(q.x());
      if (sp != CGAL::EQUAL && sq != CGAL::EQUAL) crossings.push_back(crossing_v(p.y(), p.x(), q.y(), q.x(), Y));
    }
    std::ranges::sort(crossings);
    // Whether a cut reaches the line within [a, b].
    auto cut_between = [&](const FT& a, const FT& b) {
      const auto first = std::ranges::lower_bound(crossings, a);
      return first != crossings.end() && *first <= b;
    };
    std::size_t j = i;
    while (j < pieces.size() && pieces[j].Y == Y && pieces[j].kind == pieces[i].kind) ++j;
    for (std::size_t k = i; k < j;) {
      FT lo = pieces[k].lo, hi = pieces[k].hi;
      bool perforated = pieces[k].perforation;
      for (++k; k < j && !cut_between(hi, pieces[k].lo); ++k)
        hi = CGAL::max(hi, pieces[k].hi), perforated |= pieces[k].perforation;
      if (perforated) {
        const auto after = std::ranges::lower_bound(crossings, hi);
        const auto before = std::ranges::upper_bound(crossings, lo);
        hi = after != crossings.end() ? *after : in.max_X;
        lo = before != crossings.begin() ? *std::prev(before) : in.min_X;
      }
      in.curves.emplace_back(Kernel::Segment_2(Point(lo, Y), Point(hi, Y)), static_cast<std::int32_t>(in.kind.size()));
      in.kind.push_back(pieces[i].kind);
    }
    i = j;
  }
}

// The lines' points in exact plan mm; throws if a coordinate is not finite.
std::vector<std::vector<Point>> exact_points(const std::vector<PlanPolyline>& lines, DrawingUnit drawing_unit) {
  const FT unit = exact_unit(drawing_unit);
  const bool scaled = drawing_unit != DrawingUnit::Millimetre;
  auto exact = [&](PlanPoint p) {
    if (!std::isfinite(p.X) || !std::isfinite(p.Y)) throw InputError("lines", "a coordinate is not finite");
    return scaled ? Point(FT(p.X) * unit, FT(p.Y) * unit) : Point(p.X, p.Y);
  };
  std::vector<std::vector<Point>> points(lines.size());
  for (std::size_t i = 0; i < lines.size(); ++i)
    for (const PlanPoint& p : lines[i].points) points[i].push_back(exact(p));
  return points;
}

// What the lines of two points or more are drawn as.
struct Drawn {
  bool any_line = false;     // a cut or a fold
  bool any_outline = false;  // on OUTLINE
};

Drawn drawn_as(const std::vector<PlanPolyline>& lines) {
  Drawn drawn;
  for (const PlanPolyline& line : lines)
    if (line.points.size() >= 2) (line.kind == LineKind::Outline ? drawn.any_outline : drawn.any_line) = true;
  return drawn;
}

// An input holding only the sheet: the bounding box of the OUTLINE lines if any, else of every
// line. Throws if it has no area.
Input sheet_of(const std::vector<PlanPolyline>& lines, const std::vector<std::vector<Point>>& points,
               bool any_outline) {
  Input in;
  bool first = true;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (any_outline && lines[i].kind != LineKind::Outline) continue;
    for (const Point& p : points[i]) {
      if (first || p.x() < in.min_X) in.min_X = p.x();
      if (first || p.x() > in.max_X) in.max_X = p.x();
      if (first || p.y() < in.min_Y) in.min_Y = p.y();
      if (first || p.y() > in.max_Y) in.max_Y = p.y();
      first = false;
    }
  }
  if (!(in.min_X < in.max_X) || !(in.min_Y < in.max_Y))
    throw InputError("lines", "the sheet (X " + num(nearest_double(in.min_X)) + " to " + num(nearest_double(in.max_X)) +
                     ", Y " + num(nearest_double(in.min_Y)) + " to " + num(nearest_double(in.max_Y)) +
                     " mm) has no area");
  return in;
}

// The main fold: Y = 0 where the sheet straddles it (drawn from the main fold), else halfway up
// the sheet drawn on OUTLINE (from its lower-left corner, as origamic writes DXF and cutters
// expect): then its Y in the drawing. Every point moves by it exactly, so the analysis works in
// plan coordinates either way. Without an outline the lines' extent is no sheet to halve.
std::optional<FT> main_fold_off_zero(const Input& sheet, bool any_outline) {
  if (sheet.min_Y < FT(0) && FT(0) < sheet.max_Y) return std::nullopt;
  if (!any_outline)
    throw InputError("lines", "the lines (Y " + num(nearest_double(sheet.min_Y)) + " to " +
                                  num(nearest_double(sheet.max_Y)) +
                                  " mm) do not straddle the main fold Y = 0, and no OUTLINE gives the sheet "
                                  "whose middle it is: draw the sheet's edge on OUTLINE");
  return (sheet.min_Y + sheet.max_Y) / 2;
}

// The input's curves: the lines clipped to its sheet, with a warning per line that leaves it, and
// the horizontal folds drawn in pieces joined.
class SheetCurves {
 public:
  explicit SheetCurves(Input in)
      : in_(std::move(in)), sheet_(Point(in_.min_X, in_.min_Y), Point(in_.max_X, in_.max_Y)) {}

  void add_outline() {
    const Point corners[4] = {
        {in_.min_X, in_.min_Y}, {in_.max_X, in_.min_Y}, {in_.max_X, in_.max_Y}, {in_.min_X, in_.max_Y}};
    for (int k = 0; k < 4; ++k) add(corners[k], corners[(k + 1) % 4], LineKind::Outline, false);
  }

  void add_line(const std::vector<Point>& points, LineKind kind, bool perforation) {
    bool reported = false;
    for (std::size_t k = 1; k < points.size(); ++k) {
      const Point &p = points[k - 1], &q = points[k];
      if (!sheet_.has_on_unbounded_side(p) && !sheet_.has_on_unbounded_side(q)) {
        add(p, q, kind, perforation);
        continue;
      }
      if (!reported) {
        reported = true;
        warn_outside(p, q);
      }
      const auto clipped = CGAL::intersection(Kernel::Segment_2(p, q), sheet_);
      if (!clipped) continue;
      if (const auto* s = boost::get<Kernel::Segment_2>(&*clipped)) add(s->source(), s->target(), kind, perforation);
    }
  }

  Input with_folds_joined() && {
    add_joined_folds(std::move(fold_pieces_), in_);
    return std::move(in_);
  }

 private:
  void add(const Point& p, const Point& q, LineKind kind, bool perforation) {
    if (p == q) return;
    if ((kind == LineKind::Mountain || kind == LineKind::Valley) && p.y() == q.y()) {
      fold_pieces_.push_back({p.y(), CGAL::min(p.x(), q.x()), CGAL::max(p.x(), q.x()), kind, perforation});
      return;
    }
    in_.curves.emplace_back(Kernel::Segment_2(p, q), static_cast<std::int32_t>(in_.kind.size()));
    in_.kind.push_back(kind);
  }

  void warn_outside(const Point& p, const Point& q) {
    const PlanPoint at = plan_point(sheet_.has_on_unbounded_side(p) ? p : q);
    in_.warnings.push_back({PlanProblemKind::OutsideSheet, at, plan_point(p), plan_point(q), -1, 0,
                            "a line leaves the sheet at " + point_text(at) + ": clipped to the sheet"});
  }

  Input in_;
  const Kernel::Iso_rectangle_2 sheet_;
  std::vector<FoldPiece> fold_pieces_;  // horizontal folds, to be joined
};

}  // namespace

Input collect(const std::vector<PlanPolyline>& lines, const AnalysisOptions& options) {
  std::vector<std::vector<Point>> points = exact_points(lines, options.unit);
  const Drawn drawn = drawn_as(lines);
  if (!drawn.any_line) throw InputError("lines", "no cut or fold line");
  Input in = sheet_of(lines, points, drawn.any_outline);
  if (const std::optional<FT> main_fold_Y = main_fold_off_zero(in, drawn.any_outline)) {
    in.main_fold_Y = *main_fold_Y;
    for (auto& line : points)
      for (Point& p : line) p = Point(p.x(), p.y() - in.main_fold_Y);
    in.min_Y -= in.main_fold_Y;
    in.max_Y -= in.main_fold_Y;
  }
  SheetCurves curves(std::move(in));
  curves.add_outline();
  for (std::size_t i = 0; i < lines.size(); ++i) curves.add_line(points[i], lines[i].kind, lines[i].perforation);
  return std::move(curves).with_folds_joined();
}

// ---------------------------------------------------------------------------------------------
// Faces as rings.

// The boundary of a face without the edges that have it on both sides (slits and loose ends): from
// each remaining halfedge, the next one around its target vertex that still bounds another face.
std::vector<Ring> rings_of(Face f) {
  std::vector<Halfedge> real;
  auto collect = [&](Arrangement::Ccb_halfedge_const_circulator first) {
    auto he = first;
    do
      if (he->twin()->face() != f) real.push_back(he);
    while (++he != first);
  };
  for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) collect(*ccb);
  for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) collect(*ccb);
  std::unordered_map<const void*, bool> used;
  for (const Halfedge& he : real) used[&*he] = false;
  std::vector<Ring> found;
  for (const Halfedge& start : real) {
    if (used[&*start]) continue;
    Ring& ring = found.emplace_back();
    Halfedge he = start;
    do {
      used[&*he] = true;
      ring.push_back(he->source()->point());
      Halfedge next = he->next();
      while (next->twin()->face() == f) next = next->twin()->next();
      he = next;
    } while (he != start);
  }
  if (found.size() == 1) return found;     // the one ring is outer: no area needed (most faces)
  std::vector<std::pair<FT, Ring>> rings;  // (twice the signed area, ring)
  for (Ring& ring : found) {
    FT twice = 0;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point &p = ring[i], &q = ring[(i + 1) % ring.size()];
      twice += p.x() * q.y() - q.x() * p.y();
    }
    rings.emplace_back(twice, std::move(ring));
  }
  // Counter-clockwise rings (positive area) are outer boundaries: the largest first, then the holes.
  std::stable_sort(rings.begin(), rings.end(), [](const auto& a, const auto& b) {
    const bool outer_a = CGAL::is_positive(a.first), outer_b = CGAL::is_positive(b.first);
    if (outer_a != outer_b) return outer_a;
    return outer_a && a.first > b.first;
  });
  std::vector<Ring> out;
  for (auto& [area, ring] : rings) out.push_back(std::move(ring));
  return out;
}

double ring_area(const Ring& ring) {
  double twice = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point &p = ring[i], &q = ring[(i + 1) % ring.size()];
    twice += CGAL::to_double(p.x()) * CGAL::to_double(q.y()) - CGAL::to_double(q.x()) * CGAL::to_double(p.y());
  }
  return twice / 2;
}

// A point strictly inside: on the horizontal line midway across the widest gap between vertex
// heights, the middle of the widest stretch inside.
Point inside_point(const std::vector<Ring>& rings) {
  std::vector<FT> ys;
  for (const Ring& ring : rings)
    for (const Point& p : ring) ys.push_back(p.y());
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::size_t gap = 0;
  for (std::size_t i = 1; i + 1 < ys.size(); ++i)
    if (ys[i + 1] - ys[i] > ys[gap + 1] - ys[gap]) gap = i;
  const FT y = (ys[gap] + ys[gap + 1]) / 2;
  std::vector<FT> xs;
  for (const Ring& ring : rings)
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point &p = ring[i], &q = ring[(i + 1) % ring.size()];
      if ((p.y() < y) != (q.y() < y)) xs.push_back(crossing_v(p.y(), p.x(), q.y(), q.x(), y));
    }
  std::sort(xs.begin(), xs.end());
  std::size_t best = 0;
  for (std::size_t i = 2; i + 1 < xs.size(); i += 2)
    if (xs[i + 1] - xs[i] > xs[best + 1] - xs[best]) best = i;
  return {(xs[best] + xs[best + 1]) / 2, y};
}

}  // namespace origamic::analysis
