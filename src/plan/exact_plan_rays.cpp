// SPDX-License-Identifier: GPL-3.0-or-later
// Vertical ray shooting on the exact plan (ExactPlan::faces_reached): where a support leaving a face
// can fold onto another, decided exactly.

// Exact numbers here are never shared between threads, but for the lines read under the lock (see
// exact_kernel.hpp and ExactPlan::State).
#define CGAL_HAS_NO_THREADS 1

#include <algorithm>
#include <cmath>
#include <iterator>
#include <map>
#include <mutex>
#include <vector>

#include "exact_plan_state.hpp"

namespace origamic {
namespace {

using exact::Arrangement;
using exact::FT;
using exact::kNoLabel;
using exact::nearest_double;
using exact::Point;

}  // namespace

// The edges the vertical line X = x crosses, bottom to top. An edge is crossed where x lies in
// [its left end's x, its right end's x): a line through a vertex takes the edges to its right, as a
// line a hair to the right would, and no vertical edge.
const std::vector<ExactPlan::State::Crossing>& ExactPlan::State::line_at(double x) {
  const std::lock_guard lock(mutex);
  if (const auto known = lines.find(x); known != lines.end()) return known->second;
  const Arrangement& arr = built.arrangement;
  const auto columns = static_cast<std::size_t>(std::ceil(plan.sheet.width_mm * grid.px_per_mm)) + 1;
  const auto column_of = [&](double at) {
    return static_cast<std::size_t>(std::clamp(std::floor(at * grid.px_per_mm), 0.0, static_cast<double>(columns - 1)));
  };
  if (spans_by_column.empty()) {
    spans_by_column.resize(columns);
    for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
      Arrangement::Halfedge_const_handle he = e;
      if (he->direction() != CGAL::ARR_LEFT_TO_RIGHT) he = he->twin();
      const double lo = he->source()->point().approx().x().inf();
      const double hi = he->target()->point().approx().x().sup();
      for (std::size_t c = column_of(lo); c <= column_of(hi); ++c) spans_by_column[c].push_back({lo, hi, he});
    }
  }
  const std::vector<EdgeSpan>& spans = spans_by_column[column_of(x)];
  const FT X(x);
  const Point on_line(X, FT(0));
  struct Met {
    FT Y, slope;  // edges through one vertex on the line: the lower one right of it first
    std::int32_t above;
  };
  std::vector<Met> met;
  for (const EdgeSpan& span : spans) {
    if (x < span.x_lo || x > span.x_hi) continue;
    const Point &p = span.he->source()->point(), &q = span.he->target()->point();
    if (CGAL::compare_x(p, on_line) == CGAL::LARGER || CGAL::compare_x(on_line, q) != CGAL::SMALLER) continue;
    const Arrangement::Face_const_handle f = span.he->face();
    // A crumb cut out of the sheet holds nothing either: it is passed over like a hole.
    const bool paper = !f->is_unbounded() && f->data() >= 0 && !cut_out[static_cast<std::size_t>(pieces.of.at(f))];
    const std::int32_t above = paper ? f->data() : kNoLabel;
    if (p.y() == q.y()) {  // most edges (folds, and cuts along rows): no arithmetic
      met.push_back({p.y(), FT(0), above});
      continue;
    }
    const FT slope = (q.y() - p.y()) / (q.x() - p.x());
    met.push_back({p.y() + (X - p.x()) * slope, slope, above});
  }
  std::ranges::sort(met, [](const Met& a, const Met& b) {
    const CGAL::Comparison_result order = CGAL::compare(a.Y, b.Y);
    return order == CGAL::SMALLER || (order == CGAL::EQUAL && a.slope < b.slope);
  });
  std::vector<Crossing> line;
  for (const Met& m : met) {
    // Most crossings lie on pixel edges, doubles exactly: their rationals need no exact evaluation.
    const auto [lo, hi] = CGAL::to_interval(m.Y);
    line.push_back(lo == hi ? State::Crossing{exact::Rational(lo), lo + 0.0, m.above}
                            : State::Crossing{m.Y.exact(), nearest_double(m.Y.exact()), m.above});
  }
  return lines.emplace(x, std::move(line)).first->second;
}

namespace {

// Painted band k crossing a ray is labelled kPainted - k on the line, below every face label.
constexpr std::int32_t kPainted = -2;

exact::Rational exact_Y(const FoldLine& line) { return exact::Rational(line.h) - exact::Rational(line.d); }

}  // namespace

std::vector<ExactPlan::Reached> ExactPlan::faces_reached(const Ray& ray) const {
  const auto& [x, from_Y, up, h, d, painted, short_mm] = ray;
  using Rational = exact::Rational;
  // The line's crossings, and the ends of the bands painted over it, as marks: a crossing points at
  // its rational, a band end keeps its fold line, whose rational h - d is made only when needed.
  // Most comparisons are settled by the nearest doubles (rounding is monotone; for a fold line,
  // the IEEE difference h - d is the nearest double), and painting copies no rational.
  struct Mark {
    const Rational* Y;  // or null: then Y is exactly fold.h - fold.d
    FoldLine fold;
    double Y_near;
    std::int32_t above;
    Rational exact() const { return Y ? *Y : exact_Y(fold); }
  };
  const auto less = [](const Mark& a, const Mark& b) {
    return a.Y_near != b.Y_near ? a.Y_near < b.Y_near : a.exact() < b.exact();
  };
  const auto at_fold = [](const FoldLine& fold, std::int32_t above) {
    return Mark{nullptr, fold, fold.h - fold.d, above};
  };
  std::vector<Mark> line;
  for (const State::Crossing& c : state_->line_at(x)) line.push_back({&c.Y, {}, c.Y_near, c.above});
  // A band covers the line from its lower to its upper fold line: the crossings between go, and
  // the label above its top is what the line held there.
  for (std::size_t k = 0; k < painted.size() && !line.empty(); ++k) {
    Mark lo = at_fold(painted[k].a, kPainted - static_cast<std::int32_t>(k)), hi = at_fold(painted[k].b, kNoLabel);
    if (less(hi, lo)) std::swap(lo.fold, hi.fold), std::swap(lo.Y_near, hi.Y_near);
    // Within the sheet: a run of rows ends on pixel edges, which may lie beyond its outline.
    if (less(lo, line.front())) lo = {line.front().Y, line.front().fold, line.front().Y_near, lo.above};
    if (less(line.back(), hi)) hi = {line.back().Y, line.back().fold, line.back().Y_near, hi.above};
    if (!less(lo, hi)) continue;
    const auto first = std::ranges::partition_point(line, [&](const Mark& m) { return less(m, lo); });
    const auto last = std::partition_point(first, line.end(), [&](const Mark& m) { return !less(hi, m); });
    hi.above = last == line.begin() ? kNoLabel : std::prev(last)->above;
    line.insert(line.erase(first, last), {lo, hi});
  }
  const std::vector<RasterFace>& faces = state_->faces;
  const Mark from = at_fold({from_Y, 0}, kNoLabel);
  // A fold at Y on the piece of the line between crossings i and i + 1, from the ray's start on.
  // The piece holds its near end, not its far one: a fold there lands on the next piece. Ends are
  // taken as the plan takes fold lines, to kFoldLineTolerance_mm: a support's height is the double
  // nearest edge Y + d, so its fold line h - d lies a rounding off the pixel edge it was drawn from.
  // The near end reaches short_mm farther: a fold that short of it lands on the piece.
  auto on = [&](const FoldLine& fold, std::size_t i) {
    const double slack = kFoldLineTolerance_mm + short_mm + 1e-9;  // closer calls go exact
    const Mark &lo = line[i], &hi = line[i + 1];
    const double Y_near = fold.h - fold.d;
    if (Y_near < lo.Y_near - slack || Y_near > hi.Y_near + slack) return false;
    const Rational Y = exact_Y(fold), start(from_Y), tolerance(kFoldLineTolerance_mm);
    const Rational near_reach = tolerance + Rational(short_mm);
    return up ? start <= Y && lo.exact() - near_reach <= Y && Y < hi.exact() - tolerance
              : Y <= start && lo.exact() + tolerance < Y && Y <= hi.exact() + near_reach;
  };
  std::vector<Reached> reached;
  const auto n = static_cast<std::ptrdiff_t>(line.size());
  // Piece i lies between crossings i and i + 1. The first piece walked holds the start: going up,
  // the one beginning at or below it; going down, the one ending at or above it.
  std::ptrdiff_t below = 0;  // crossings under the start (going up: at or under it)
  while (below < n) {
    const Mark& m = line[static_cast<std::size_t>(below)];
    if (up ? less(from, m) : !less(m, from)) break;
    ++below;
  }
  for (std::ptrdiff_t i = below - 1; i >= 0 && i + 1 < n; i += up ? 1 : -1) {
    const auto k = static_cast<std::size_t>(i);
    const std::int32_t g = line[k].above;
    Orientation orientation;
    double depth_mm;
    if (g >= 0) {
      const RasterFace& target = faces[static_cast<std::size_t>(g)];
      if (target.hole) continue;
      orientation = target.orientation, depth_mm = target.depth_mm;
    } else if (g <= kPainted) {
      const PaintedBand& band = painted[static_cast<std::size_t>(kPainted - g)];
      orientation = band.orientation, depth_mm = band.depth_mm;
    } else {
      continue;
    }
    if (!support_folds_onto(orientation, depth_mm, up, h, d)) continue;
    const FoldLine fold = support_fold(orientation, depth_mm, h, d);
    if (on(fold, k)) reached.push_back({std::max(g, kNoLabel), orientation, depth_mm, fold.h - fold.d});
  }
  return reached;
}

}  // namespace origamic
