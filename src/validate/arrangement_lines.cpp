// SPDX-License-Identifier: GPL-3.0-or-later
// The lines of an analysed plan's arrangement after faces were relabelled (arrangement_lines,
// plan_analysis_geometry.hpp): the tips' rounds (tip_repair.cpp) draw their plans with it.
#define CGAL_HAS_NO_THREADS 1

#include <algorithm>
#include <cstddef>
#include <functional>
#include <optional>
#include <set>
#include <unordered_map>
#include <utility>
#include <vector>

#include "exact_kernel.hpp"
#include "plan_analysis_geometry.hpp"

namespace origamic::analysis {

using exact::nearest_double;
using exact::Point;

std::vector<PlanPolyline> arrangement_lines(const Analyzer& a, const std::set<Face>& changed, std::int32_t first_new) {
  struct Segment {
    PlanPoint p, q;
    LineKind kind;
  };
  std::vector<Segment> segments;
  const auto point = [&](const Point& p) {
    return PlanPoint{nearest_double(p.x()), nearest_double(p.y() + a.result.main_fold_Y)};
  };
  const auto same = [](PlanPoint p, PlanPoint q) { return p.X == q.X && p.Y == q.Y; };
  for (auto e = a.arr.edges_begin(); e != a.arr.edges_end(); ++e) {
    Halfedge he = e;
    if (he->direction() != CGAL::ARR_LEFT_TO_RIGHT) he = he->twin();
    const Face up = he->face(), down = he->twin()->face();
    bool fresh = changed.contains(up) || changed.contains(down);
    for (const std::int32_t d : he->curve().data()) fresh = fresh || d >= first_new;
    const PlanPoint p = point(he->source()->point()), q = point(he->target()->point());
    if (!fresh || up->is_unbounded() || down->is_unbounded()) {
      // Each kind once: the sheet's outline is there twice (the plan's and the one collect adds).
      std::set<LineKind> kinds;
      for (const std::int32_t d : he->curve().data())
        if (d < first_new) kinds.insert(a.kind[static_cast<std::size_t>(d)]);
      if (!same(p, q))
        for (const LineKind k : kinds) segments.push_back({p, q, k});
      continue;
    }
    if (up->data() == down->data()) continue;
    const Place &above = a.place[static_cast<std::size_t>(up->data())],
                &below = a.place[static_cast<std::size_t>(down->data())];
    LineKind k = a.cut_out[static_cast<std::size_t>(up->data())] || a.cut_out[static_cast<std::size_t>(down->data())]
                     ? LineKind::CutOut
                     : LineKind::Cut;
    if (k == LineKind::Cut && above.placed && below.placed && above.orientation != below.orientation &&
        he->source()->point().y() == he->target()->point().y() &&
        CGAL::abs(he->source()->point().y() - fold_line_Y(below.orientation, below.depth, above.depth)) <= a.tolerance)
      k = below.orientation == Orientation::V ? LineKind::Mountain : LineKind::Valley;
    if (!same(p, q)) segments.push_back({p, q, k});
  }
  // Segments of one kind joined end to end where no other of that kind meets them.
  // The segments ending at each point, in order (only looked up: a hash map keeps the result).
  struct PointHash {
    std::size_t operator()(const std::pair<double, double>& p) const {
      return std::hash<double>{}(p.first) * 0x9E3779B97F4A7C15ull ^ std::hash<double>{}(p.second);
    }
  };
  std::unordered_map<std::pair<double, double>, std::vector<std::size_t>, PointHash> at;
  const auto key = [](PlanPoint p) { return std::pair{p.X, p.Y}; };
  at.reserve(2 * segments.size());
  for (std::size_t i = 0; i < segments.size(); ++i)
    at[key(segments[i].p)].push_back(i), at[key(segments[i].q)].push_back(i);
  std::vector<bool> used(segments.size(), false);
  std::vector<PlanPolyline> lines;
  // Whether exactly two segments of kind k end at p.
  const auto through = [&](PlanPoint p, LineKind k) {
    const std::vector<std::size_t>& here = at.at(key(p));
    return std::ranges::count_if(here, [&](std::size_t j) { return segments[j].kind == k; }) == 2;
  };
  const auto extend = [&](PlanPolyline& line) {
    for (;;) {
      const PlanPoint end = line.points.back();
      if (!through(end, line.kind)) return;
      std::optional<std::size_t> next;
      for (const std::size_t j : at.at(key(end)))
        if (!used[j] && segments[j].kind == line.kind) next = j;
      if (!next) return;
      used[*next] = true;
      const Segment& s = segments[*next];
      line.points.push_back(key(s.p) == key(end) ? s.q : s.p);
    }
  };
  for (const bool loops : {false, true})
    for (std::size_t i = 0; i < segments.size(); ++i) {
      if (used[i]) continue;
      const Segment& s = segments[i];
      if (!loops && through(s.p, s.kind) && through(s.q, s.kind)) continue;  // inside a chain: start at its end
      used[i] = true;
      PlanPolyline line{s.kind, {s.p, s.q}};
      if (!loops && through(s.p, s.kind)) std::swap(line.points[0], line.points[1]);
      extend(line);
      lines.push_back(std::move(line));
    }
  return lines;
}

}  // namespace origamic::analysis
