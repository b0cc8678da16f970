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
#include <optional>
#include <shared_mutex>
#include <span>
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
  {
    const std::shared_lock reading(mutex);  // most lines are known: threads look them up at once
    if (const auto known = lines.find(x); known != lines.end()) return known->second;
  }
  const std::unique_lock lock(mutex);
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

// The line's crossings, and the ends of the bands painted over it, as marks: a crossing points at
// its rational, a band end keeps its fold line, whose rational h - d is made only when needed.
// Most comparisons are settled by the nearest doubles (rounding is monotone; for a fold line,
// the IEEE difference h - d is the nearest double), and painting copies no rational.
struct Mark {
  const exact::Rational* Y;  // or null: then Y is exactly fold.h - fold.d
  FoldLine fold;
  double Y_near;
  std::int32_t above;
  exact::Rational exact() const { return Y ? *Y : exact_Y(fold); }
};

// Where the nearest doubles tie, the rationals compare as they are: exact() copies one (res_dragon_full:
// 1.9 of the design's 4.2 million GMP allocations were those copies).
bool below(const Mark& a, const Mark& b) {
  if (a.Y_near != b.Y_near) return a.Y_near < b.Y_near;
  if (a.Y && b.Y) return *a.Y < *b.Y;
  if (a.Y) return *a.Y < exact_Y(b.fold);
  if (b.Y) return exact_Y(a.fold) < *b.Y;
  if (a.fold.h == b.fold.h && a.fold.d == b.fold.d) return false;  // one fold line
  return exact_Y(a.fold) < exact_Y(b.fold);
}

Mark at_fold(const FoldLine& fold, std::int32_t above) { return Mark{nullptr, fold, fold.h - fold.d, above}; }

// A band covers the line from its lower to its upper fold line: the crossings between go, and
// the label above its top is what the line held there.
std::vector<Mark> painted_over(std::vector<Mark> line, std::span<const PaintedBand> painted) {
  for (std::size_t k = 0; k < painted.size() && !line.empty(); ++k) {
    Mark lo = at_fold(painted[k].a, kPainted - static_cast<std::int32_t>(k)), hi = at_fold(painted[k].b, kNoLabel);
    if (below(hi, lo)) std::swap(lo.fold, hi.fold), std::swap(lo.Y_near, hi.Y_near);
    // Within the sheet: a run of rows ends on pixel edges, which may lie beyond its outline.
    if (below(lo, line.front())) lo = {line.front().Y, line.front().fold, line.front().Y_near, lo.above};
    if (below(line.back(), hi)) hi = {line.back().Y, line.back().fold, line.back().Y_near, hi.above};
    if (!below(lo, hi)) continue;
    const auto first = std::ranges::partition_point(line, [&](const Mark& m) { return below(m, lo); });
    const auto last = std::partition_point(first, line.end(), [&](const Mark& m) { return !below(hi, m); });
    hi.above = last == line.begin() ? kNoLabel : std::prev(last)->above;
    line.insert(line.erase(first, last), {lo, hi});
  }
  return line;
}

// How many marks lie under the ray's start (going up: at or under it). Piece i lies between marks
// i and i + 1, and the first piece walked holds the start: going up, the one beginning at or below
// it; going down, the one ending at or above it.
std::ptrdiff_t marks_under_start(const std::vector<Mark>& line, const ExactPlan::Ray& ray) {
  const Mark from = at_fold({ray.from_Y, 0}, kNoLabel);
  const auto n = static_cast<std::ptrdiff_t>(line.size());
  std::ptrdiff_t under = 0;
  while (under < n) {
    const Mark& m = line[static_cast<std::size_t>(under)];
    if (ray.up ? below(from, m) : !below(m, from)) break;
    ++under;
  }
  return under;
}

// Whether a <= b (or a < b, as `exactly` asks) for two numbers known by their doubles a and b and
// exactly: settled on the doubles where they lie farther apart than kSettled_mm, else exactly. The
// doubles are each within a few ulps of their numbers (nearest doubles, and sums of two): on a plan
// a few hundred millimetres across, under 1e-12 mm. (seedlike/chapel: the ray shooting 11% -> 6% of
// its samples; folds that land on a crossing's line still go exact.)
constexpr double kSettled_mm = 1e-9;
template <typename Exactly>
bool at_most(double a, double b, Exactly exactly) {
  return b - a > kSettled_mm || (b - a >= -kSettled_mm && exactly());
}

// Whether a fold lands on the piece of the line between marks lo and hi, from the ray's start on.
// The piece holds its near end, not its far one: a fold there lands on the next piece. Ends are
// taken as the plan takes fold lines, to kFoldLineTolerance_mm: a support's height is the double
// nearest edge Y + d, so its fold line h - d lies a rounding off the pixel edge it was drawn from.
// The near end reaches short_mm farther: a fold that short of it lands on the piece.
bool lands_between(const FoldLine& fold, const Mark& lo, const Mark& hi, const ExactPlan::Ray& ray) {
  using exact::Rational;
  const double tolerance = kFoldLineTolerance_mm, reach = tolerance + ray.short_mm;
  const double Y_near = fold.h - fold.d;
  const auto Y = [&] { return exact_Y(fold); };
  const auto near_reach = [&] { return Rational(tolerance) + Rational(ray.short_mm); };
  if (ray.up)
    return at_most(ray.from_Y, Y_near, [&] { return Rational(ray.from_Y) <= Y(); }) &&
           at_most(lo.Y_near - reach, Y_near, [&] { return lo.exact() - near_reach() <= Y(); }) &&
           at_most(Y_near, hi.Y_near - tolerance, [&] { return Y() < hi.exact() - Rational(tolerance); });
  return at_most(Y_near, ray.from_Y, [&] { return Y() <= Rational(ray.from_Y); }) &&
         at_most(lo.Y_near + tolerance, Y_near, [&] { return lo.exact() + Rational(tolerance) < Y(); }) &&
         at_most(Y_near, hi.Y_near + reach, [&] { return Y() <= hi.exact() + near_reach(); });
}

struct Plane {
  Orientation orientation;
  double depth_mm;
};

// The plane of what the line holds above a mark labelled g: a face or a painted band; none for a
// hole or outside the paper.
std::optional<Plane> plane_above(std::int32_t g, const std::vector<RasterFace>& faces,
                                 std::span<const PaintedBand> painted) {
  if (g >= 0) {
    const RasterFace& target = faces[static_cast<std::size_t>(g)];
    if (target.hole) return std::nullopt;
    return Plane{target.orientation, target.depth_mm};
  }
  if (g <= kPainted) {
    const PaintedBand& band = painted[static_cast<std::size_t>(kPainted - g)];
    return Plane{band.orientation, band.depth_mm};
  }
  return std::nullopt;
}

}  // namespace

std::vector<ExactPlan::Reached> ExactPlan::faces_reached(const Ray& ray) const {
  const auto& [x, from_Y, up, h, d, painted, short_mm] = ray;
  const std::vector<State::Crossing>& at_x = state_->line_at(x);
  std::vector<Mark> crossings;
  crossings.reserve(at_x.size() + 2 * painted.size());  // each band may add its two ends
  for (const State::Crossing& c : at_x) crossings.push_back({&c.Y, {}, c.Y_near, c.above});
  const std::vector<Mark> line = painted_over(std::move(crossings), painted);
  std::vector<Reached> reached;
  const auto n = static_cast<std::ptrdiff_t>(line.size());
  for (std::ptrdiff_t i = marks_under_start(line, ray) - 1; i >= 0 && i + 1 < n; i += up ? 1 : -1) {
    const auto k = static_cast<std::size_t>(i);
    const std::int32_t g = line[k].above;
    const std::optional<Plane> plane = plane_above(g, state_->faces, painted);
    if (!plane || !support_folds_onto(plane->orientation, plane->depth_mm, up, h, d)) continue;
    const FoldLine fold = support_fold(plane->orientation, plane->depth_mm, h, d);
    if (lands_between(fold, line[k], line[k + 1], ray))
      reached.push_back({std::max(g, kNoLabel), plane->orientation, plane->depth_mm, fold.h - fold.d});
  }
  return reached;
}

}  // namespace origamic
