// SPDX-License-Identifier: GPL-3.0-or-later
// The translation unit that validates a plan from its lines on an exact arrangement (CGAL is heavy
// to compile: keep it here, in plan_analysis_geometry.cpp, which holds the geometry it works on, and
// in plan_analysis_chords.cpp, its strip widths and their check).
// One exact run at a time: see exact_runs.hpp.
#define CGAL_HAS_NO_THREADS 1

#include "origamic/plan_analysis.hpp"

#include <CGAL/Arr_batched_point_location.h>
#include <CGAL/Arr_observer.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <map>
#include <optional>
#include <tuple>
#include <unordered_map>
#include <utility>

#include "exact_kernel.hpp"
#include "exact_runs.hpp"
#include "origamic/error.hpp"
#include "plan_analysis_geometry.hpp"

namespace origamic::analysis {
namespace {

using exact::FT;
using exact::nearest_double;
using exact::Point;

constexpr std::int32_t kOutside = -1;

}  // namespace

void Analyzer::run(const std::vector<PlanPolyline>& lines) {
  Input in = collect(lines, options);
  result.sheet = {nearest_double(in.min_X), nearest_double(in.min_Y), nearest_double(in.max_X),
                  nearest_double(in.max_Y)};
  result.main_fold_Y = nearest_double(in.main_fold_Y);
  result.problems = std::move(in.warnings);
  kind = std::move(in.kind);
  CGAL::insert(arr, in.curves.begin(), in.curves.end());
  result.arrangement_valid = arr.is_valid();
  make_regions(in);
  classify_edges();
  place_faces();
  check_folds();
  check_card();
  validate_graph();
  if (options.min_strip_mm > 0) check_strips();
  finish();
}

void Analyzer::make_regions(const Input& in) {
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded()) {
      f->set_data(kOutside);
      continue;
    }
    f->set_data(static_cast<std::int32_t>(faces.size()));
    faces.push_back(f);
  }
  const std::size_t n = faces.size();
  rings.resize(n);
  place.assign(n, {});
  folds_of.assign(n, {});
  result.regions.resize(n);
  result.area_mm2.assign(n, 0.0);
  std::vector<bool> top(n, false), bottom(n, false);
  for (auto he = arr.halfedges_begin(); he != arr.halfedges_end(); ++he) {
    if (he->face()->is_unbounded() || !he->twin()->face()->is_unbounded()) continue;
    const Point &p = he->source()->point(), &q = he->target()->point();
    const auto r = static_cast<std::size_t>(he->face()->data());
    if (p.y() == in.max_Y && q.y() == in.max_Y) top[r] = true;
    if (p.y() == in.min_Y && q.y() == in.min_Y) bottom[r] = true;
  }
  result.node.assign(n, 0);
  std::int32_t next_node = 2;
  for (std::size_t r = 0; r < n; ++r) {
    rings[r] = rings_of(faces[r]);
    PlanRegion& region = result.regions[r];
    for (const Ring& ring : rings[r]) {
      std::vector<PlanPoint>& out = region.rings.emplace_back();
      for (const Point& p : ring) out.push_back(plan_point(p));
      result.area_mm2[r] += ring_area(ring);
    }
    region.inside = plan_point(inside_point(rings[r]));
    if (top[r] || bottom[r]) place[r] = {true, top[r] ? Orientation::V : Orientation::H, FT(0)};
    result.node[r] = top[r] ? 0 : bottom[r] ? 1 : next_node++;
    if (top[r] && bottom[r])
      add({PlanProblemKind::SheetNotSplit, region.inside, region.inside, region.inside, static_cast<std::int32_t>(r), 0,
           "the face at " + point_text(region.inside) +
               " touches both the sheet's top edge (back plane) and its bottom edge (floor): no main fold "
               "separates them"});
  }
  result.faces = next_node - 2;
}

void Analyzer::classify_edges() {
  std::vector<Halfedge> cut_inside, fold_inside;
  cut_out.assign(faces.size(), 1);
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    Halfedge he = e;
    if (he->direction() != CGAL::ARR_LEFT_TO_RIGHT) he = he->twin();  // he->face() is above or left
    if (he->face()->is_unbounded() || he->twin()->face()->is_unbounded()) continue;
    bool cut = false, mountain = false, valley = false, only_cut_out = true;
    for (const std::int32_t d : he->curve().data()) {
      const LineKind k = kind[static_cast<std::size_t>(d)];
      (k == LineKind::Mountain ? mountain : k == LineKind::Valley ? valley : cut) = true;
      only_cut_out &= k == LineKind::CutOut;
    }
    // A face whose every side is on the CUTOUT layer is declared cut out: it falls out.
    if (!only_cut_out)
      for (const Face f : {he->face(), he->twin()->face()}) cut_out[static_cast<std::size_t>(f->data())] = 0;
    const Point &p = he->source()->point(), &q = he->target()->point();
    const double length = std::hypot(CGAL::to_double(q.x() - p.x()), CGAL::to_double(q.y() - p.y()));
    const std::int32_t upper = he->face()->data(), lower = he->twin()->face()->data();
    if (int(cut) + int(mountain) + int(valley) > 1) {
      const PlanPoint a = plan_point(p), b = plan_point(q);
      std::string drawn;
      for (const auto& [on, name] : {std::pair{cut, "a cut"}, {mountain, "a mountain fold"}, {valley, "a valley fold"}})
        if (on) drawn += (drawn.empty() ? "" : " and ") + std::string(name);
      add({PlanProblemKind::ConflictingLines, a, a, b, -1, 0,
           "the stretch from " + point_text(a) + " to " + point_text(b) + " is drawn as " + drawn +
               ": it is taken as a cut"});
      mountain = valley = false, cut = true;
    }
    if (cut) {
      result.cut_mm += length;
      if (upper == lower) cut_inside.push_back(he);
      continue;
    }
    (mountain ? result.mountain_mm : result.valley_mm) += length;
    if (upper == lower) {
      fold_inside.push_back(he);
      continue;
    }
    if (p.y() != q.y()) {
      const PlanPoint a = plan_point(p), b = plan_point(q);
      add({PlanProblemKind::FoldNotHorizontal, a, a, b, -1, 0,
           std::string(mountain ? "mountain" : "valley") + " fold from " + point_text(a) + " to " + point_text(b) +
               " is not parallel to the main fold: folds run along X"});
      continue;
    }
    folds.push_back({lower, upper, p.y(), p.x(), q.x(), mountain ? LineKind::Mountain : LineKind::Valley});
    folds_of[static_cast<std::size_t>(lower)].push_back(folds.size() - 1);
    folds_of[static_cast<std::size_t>(upper)].push_back(folds.size() - 1);
  }
  report_inside(fold_inside, PlanProblemKind::FoldInsideFace);
  report_inside(cut_inside, PlanProblemKind::CutInsideFace);
}

void Analyzer::report_inside(const std::vector<Halfedge>& edges, PlanProblemKind k) {
  std::unordered_map<const void*, std::size_t> index;
  for (std::size_t i = 0; i < edges.size(); ++i) index[&*edges[i]] = index[&*edges[i]->twin()] = i;
  std::vector<bool> seen(edges.size(), false);
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (seen[i]) continue;
    std::vector<std::size_t> stack = {i};
    seen[i] = true;
    FT lo_x = edges[i]->source()->point().x(), hi_x = lo_x, lo_y = edges[i]->source()->point().y(), hi_y = lo_y;
    std::optional<Point> loose;
    while (!stack.empty()) {
      const Halfedge he = edges[stack.back()];
      stack.pop_back();
      for (const auto& v : {he->source(), he->target()}) {
        const Point& p = v->point();
        lo_x = CGAL::min(lo_x, p.x()), hi_x = CGAL::max(hi_x, p.x());
        lo_y = CGAL::min(lo_y, p.y()), hi_y = CGAL::max(hi_y, p.y());
        if (v->degree() == 1 && (!loose || CGAL::compare_xy(p, *loose) == CGAL::SMALLER)) loose = p;
        auto around = v->incident_halfedges(), first = around;
        do {
          const auto it = index.find(&*around);
          if (it != index.end() && !seen[it->second]) seen[it->second] = true, stack.push_back(it->second);
        } while (++around != first);
      }
    }
    const PlanPoint from = plan_point(Point(lo_x, lo_y)), to = plan_point(Point(hi_x, hi_y));
    const PlanPoint at = loose ? plan_point(*loose) : from;
    const std::int32_t region = edges[i]->face()->data();
    const bool fold = k == PlanProblemKind::FoldInsideFace;
    add({k, at, from, to, region, 0,
         std::string(fold ? "a fold" : "a cut") + " between " + point_text(from) + " and " + point_text(to) +
             " has the same face on both sides" +
             (loose ? ", with a loose end at " + point_text(at) : std::string(" (a slit)")) +
             (fold ? ": nothing folds there" : "")});
  }
}

void Analyzer::place_faces() {
  std::deque<std::size_t> queue;
  for (std::size_t r = 0; r < faces.size(); ++r)
    if (place[r].placed) queue.push_back(r);
  while (!queue.empty()) {
    const std::size_t r = queue.front();
    queue.pop_front();
    for (const std::size_t e : folds_of[r]) {
      const FoldEdge& fold = folds[e];
      const auto s = static_cast<std::size_t>(fold.lower == static_cast<std::int32_t>(r) ? fold.upper : fold.lower);
      if (place[s].placed) continue;
      place[s] = place[r].orientation == Orientation::V ? Place{true, Orientation::H, fold.Y + place[r].depth}
                                                        : Place{true, Orientation::V, place[r].depth - fold.Y};
      queue.push_back(s);
    }
  }
}

void Analyzer::check_folds() {
  struct Group {
    FT X_lo, X_hi;
    double value = 0;
    std::string what;
  };
  std::map<std::tuple<int, std::int32_t, std::int32_t, double>, Group> groups;
  auto note = [&](PlanProblemKind k, const FoldEdge& fold, double value, std::string what) {
    const auto key = std::make_tuple(static_cast<int>(k), fold.lower, fold.upper, nearest_double(fold.Y));
    auto [it, fresh] = groups.try_emplace(key, Group{fold.X_lo, fold.X_hi, value, std::move(what)});
    if (!fresh)
      it->second.X_lo = CGAL::min(it->second.X_lo, fold.X_lo), it->second.X_hi = CGAL::max(it->second.X_hi, fold.X_hi);
  };
  for (const FoldEdge& fold : folds) {
    const Place &below = place[static_cast<std::size_t>(fold.lower)],
                &above = place[static_cast<std::size_t>(fold.upper)];
    if (!below.placed || !above.placed) continue;  // a floating group: validity reports it
    const std::string kind_name = fold.kind == LineKind::Mountain ? "mountain" : "valley";
    if (below.orientation == above.orientation) {
      note(PlanProblemKind::InconsistentFold, fold, 0,
           kind_name + " fold joins " + face_text(below) + " below and " + face_text(above) +
               " above (placed along other folds): a fold joins a V and an H face");
      continue;
    }
    const FT line = fold_line_Y(below.orientation, below.depth, above.depth), off = fold.Y - line;
    if (CGAL::abs(off) > tolerance)
      note(PlanProblemKind::InconsistentFold, fold, nearest_double(off),
           kind_name + " fold joins " + face_text(below) + " below and " + face_text(above) +
               " above (placed along other folds), which fold on Y = " + num(nearest_double(line)) + ": it is " +
               num(nearest_double(off)) + " mm off that line");
    const LineKind expected = below.orientation == Orientation::V ? LineKind::Mountain : LineKind::Valley;
    if (fold.kind != expected)
      note(PlanProblemKind::WrongFoldKind, fold, 0,
           kind_name + " fold, but " + face_text(below) + " below and " + face_text(above) + " above make a " +
               (expected == LineKind::Mountain ? "mountain fold (V then H going up)"
                                               : "valley fold (H then V going up)"));
  }
  for (const auto& [key, group] : groups) {
    const auto& [k, lower, upper, Y] = key;
    const PlanPoint from{nearest_double(group.X_lo), Y}, to{nearest_double(group.X_hi), Y};
    const PlanPoint at{nearest_double((group.X_lo + group.X_hi) / 2), Y};
    add({static_cast<PlanProblemKind>(k), at, from, to, lower, group.value,
         "at Y = " + num(Y) + " from X = " + num(from.X) + " to " + num(to.X) + ": " + group.what});
  }
}

void Analyzer::check_card() {
  for (std::size_t r = 0; r < faces.size(); ++r) {
    const Place& p = place[r];
    if (!p.placed) continue;
    const bool v = p.orientation == Orientation::V;
    std::optional<Point> worst;
    for (const Ring& ring : rings[r])
      for (const Point& q : ring)
        if (!worst || (v ? q.y() < worst->y() : q.y() > worst->y())) worst = q;
    const FT beyond = v ? -(worst->y() + p.depth) : worst->y() - p.depth;
    if (!(beyond > tolerance)) continue;
    const PlanPoint at = plan_point(*worst);
    add({PlanProblemKind::OutsideCard, at, at, at, static_cast<std::int32_t>(r), nearest_double(beyond),
         "face " + face_text(p) + " at " + point_text(result.regions[r].inside) + " reaches " +
             (v ? "below the floor" : "behind the back plane") + " by " + num(nearest_double(beyond)) + " mm at " +
             point_text(at)});
  }
}

void Analyzer::validate_graph() {
  std::vector<FT> ys;
  for (const FoldEdge& fold : folds) ys.push_back(fold.Y);
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::vector<std::int32_t> line_of(ys.size(), 0);
  for (std::size_t i = 1; i < ys.size(); ++i) line_of[i] = line_of[i - 1] + (ys[i] - ys[i - 1] > tolerance ? 1 : 0);
  result.graph.faces = result.faces + 2;
  result.graph.holes.assign(static_cast<std::size_t>(result.graph.faces), 0);
  for (std::size_t r = 0; r < faces.size(); ++r)
    if (cut_out[r] && result.node[r] >= 2) result.graph.holes[static_cast<std::size_t>(result.node[r])] = 1;
  for (const FoldEdge& fold : folds) {
    const std::int32_t a = result.node[static_cast<std::size_t>(fold.lower)],
                       b = result.node[static_cast<std::size_t>(fold.upper)];
    if (a == b) continue;
    const auto y = static_cast<std::size_t>(std::lower_bound(ys.begin(), ys.end(), fold.Y) - ys.begin());
    result.graph.folds.push_back({a, b, line_of[y]});
  }
  result.validity = validity_of(result.graph);
  for (std::size_t r = 0; r < faces.size(); ++r) {
    PlanRegion& region = result.regions[r];
    region.placed = place[r].placed;
    region.orientation = place[r].orientation;
    region.depth_mm = place[r].placed ? nearest_double(place[r].depth) : 0;
    region.status = result.validity.status[static_cast<std::size_t>(result.node[r])];
    PlanProblemKind k;
    std::string why;
    switch (region.status) {
      case FaceStatus::Floating:
        k = PlanProblemKind::Floating, why = "no chain of folds joins it to the back plane or the floor";
        break;
      case FaceStatus::Dangling:
        k = PlanProblemKind::Dangling, why = "all its folds lie on one line: it swings about it";
        break;
      case FaceStatus::Invalid:
        k = PlanProblemKind::Invalid, why = "no two fold paths to the back plane and the floor hold it";
        break;
      default:
        continue;
    }
    add({k, region.inside, region.inside, region.inside, static_cast<std::int32_t>(r), 0,
         std::string(to_string(region.status)) + " face " + (place[r].placed ? face_text(place[r]) + " " : "") + "at " +
             point_text(region.inside) + ": " + why});
  }
}

void Analyzer::finish() {
  std::stable_sort(result.problems.begin(), result.problems.end(), [](const PlanProblem& a, const PlanProblem& b) {
    if (is_error(a.kind) != is_error(b.kind)) return is_error(a.kind);
    if (a.kind != b.kind) return a.kind < b.kind;
    if (a.at.Y != b.at.Y) return a.at.Y > b.at.Y;
    return a.at.X < b.at.X;
  });
  for (const PlanProblem& p : result.problems) (is_error(p.kind) ? result.errors : result.warnings) += 1;
}

}  // namespace origamic::analysis

namespace origamic {

bool is_error(PlanProblemKind kind) { return kind < PlanProblemKind::CutInsideFace; }

PlanAnalysis analyze_plan(const std::vector<PlanPolyline>& lines, const AnalysisOptions& options) {
  if (!(std::isfinite(options.min_strip_mm) && options.min_strip_mm >= 0))
    throw InputError("AnalysisOptions::min_strip_mm", "W must be zero (no check) or a positive number of mm");
  if (!(std::isfinite(options.tolerance_mm) && options.tolerance_mm >= 0 && options.tolerance_mm <= 0.1))
    throw InputError("AnalysisOptions::tolerance_mm", "must be between 0 and 0.1 mm");
  const auto lock = exact_run_lock();
  analysis::Analyzer analyzer(options);
  analyzer.run(lines);
  return std::move(analyzer.result);
}

}  // namespace origamic
