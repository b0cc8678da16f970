// SPDX-License-Identifier: GPL-3.0-or-later
// The exact plan drawn in full (ExactPlan::full): its lines chained and measured, its faces as
// regions with a point inside each, and the raster faces it lost.

// Exact numbers here are never shared between threads (see exact_kernel.hpp).
#define CGAL_HAS_NO_THREADS 1

#include <algorithm>
#include <cstddef>
#include <functional>
#include <iterator>
#include <map>
#include <utility>
#include <vector>

#include "exact_plan_state.hpp"
#include "exact_runs.hpp"

namespace origamic {
namespace {

using exact::Arrangement;
using exact::length_of;
using exact::nearest_coordinate;

// Joins segments of one kind that meet end to end (at vertices where exactly two of them meet).
std::vector<PlanPolyline> chain_segments(LineKind kind,
                                         const std::vector<std::pair<std::size_t, std::size_t>>& segments,
                                         const std::vector<PlanPoint>& vertex_points) {
  std::map<std::size_t, std::vector<std::size_t>> incident;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    incident[segments[i].first].push_back(i);
    incident[segments[i].second].push_back(i);
  }
  std::vector<bool> used(segments.size(), false);
  std::vector<PlanPolyline> lines;
  auto walk = [&](std::size_t start_vertex, std::size_t first) {
    PlanPolyline line{kind, {vertex_points[start_vertex]}};
    std::size_t at = start_vertex, s = first;
    for (;;) {
      used[s] = true;
      at = segments[s].first == at ? segments[s].second : segments[s].first;
      // Distinct exact points can share their nearest double: no zero-length segment in the files.
      if (line.points.back().X != vertex_points[at].X || line.points.back().Y != vertex_points[at].Y)
        line.points.push_back(vertex_points[at]);
      const auto& next = incident[at];
      if (next.size() != 2) break;
      const std::size_t n = next[0] == s ? next[1] : next[0];
      if (used[n]) break;
      s = n;
    }
    if (line.points.size() >= 2) lines.push_back(std::move(line));
  };
  for (const auto& [vertex, list] : incident)
    if (list.size() != 2)
      for (const std::size_t s : list)
        if (!used[s]) walk(vertex, s);
  for (std::size_t s = 0; s < segments.size(); ++s)
    if (!used[s]) walk(segments[s].first, s);
  return lines;
}

// The plan's faces as regions for folding (plan_regions.hpp). A plan face may span several
// arrangement faces, split by edges with its label on both sides (the connectors of snapped folds,
// among others); those edges are no lines of the plan, so the faces they split are joined here: one
// region per set of same-label faces connected through such edges. Its rings are the cycles of
// halfedges with the region on their left and another label on their right: the outer one
// counter-clockwise, holes clockwise, at the nearest doubles of their vertices (a vertex repeating
// the previous one's doubles is dropped). A piece cut out (a crumb, ExactPlan's verdict) is a region
// of its own, removed, as the DXF draws it (a hole) and its reader finds it: the pop-up is the fold
// of the plan.
std::vector<PlanRegion> regions_of(const Arrangement& arr, const std::vector<PlanFace>& faces,
                                   const std::function<bool(Arrangement::Face_const_handle)>& cut_out) {
  using Face = Arrangement::Face_const_handle;
  using Halfedge = Arrangement::Halfedge_const_handle;
  auto each_halfedge = [](Face f, auto&& visit) {
    for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) {
      auto he = *ccb, first = he;
      do visit(Halfedge(he));
      while (++he != first);
    }
    for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) {
      auto he = *ccb, first = he;
      do visit(Halfedge(he));
      while (++he != first);
    }
  };
  std::map<Face, bool> joined;
  std::map<Halfedge, bool> walked;
  std::vector<PlanRegion> regions;
  for (auto start = arr.faces_begin(); start != arr.faces_end(); ++start) {
    const std::int32_t label = start->data();
    if (start->is_unbounded() || label < 0 || joined[start]) continue;
    const bool cut = cut_out(start);
    // The connected set of faces with this label, and the halfedges that bound it.
    std::vector<Face> stack = {start};
    std::vector<Halfedge> boundary;
    joined[start] = true;
    while (!stack.empty()) {
      const Face f = stack.back();
      stack.pop_back();
      each_halfedge(f, [&](Halfedge he) {
        const Face other = he->twin()->face();
        if (other->data() != label || cut_out(other) != cut)
          boundary.push_back(he);
        else if (!joined[other])
          joined[other] = true, stack.push_back(other);
      });
    }
    // Around each boundary vertex, turn through faces of the set to the next boundary halfedge.
    auto next_on_boundary = [&](Halfedge he) {
      Halfedge next = he->next();
      while (next->twin()->face()->data() == label && cut_out(next->twin()->face()) == cut) next = next->twin()->next();
      return next;
    };
    std::vector<std::vector<PlanPoint>> rings;
    for (const Halfedge first : boundary) {
      if (walked[first]) continue;
      std::vector<PlanPoint> ring;
      Halfedge he = first;
      do {
        walked[he] = true;
        const PlanPoint p{nearest_coordinate(he->source()->point(), 0), nearest_coordinate(he->source()->point(), 1)};
        if (ring.empty() || ring.back().X != p.X || ring.back().Y != p.Y) ring.push_back(p);
        he = next_on_boundary(he);
      } while (he != first);
      if (ring.size() > 1 && ring.back().X == ring.front().X && ring.back().Y == ring.front().Y) ring.pop_back();
      if (ring.size() >= 3) rings.push_back(std::move(ring));
    }
    if (rings.empty()) continue;
    // The outer ring first: the one of largest signed area (holes are negative).
    auto twice_area = [](const std::vector<PlanPoint>& ring) {
      double twice = 0;
      for (std::size_t i = 0; i < ring.size(); ++i) {
        const PlanPoint &p = ring[i], &q = ring[(i + 1) % ring.size()];
        twice += p.X * q.Y - q.X * p.Y;
      }
      return twice;
    };
    std::ranges::stable_sort(rings, std::greater<>(), twice_area);
    const PlanFace& face = faces[static_cast<std::size_t>(label)];
    regions.push_back({.rings = std::move(rings),
                       .orientation = face.orientation,
                       .depth_mm = face.depth_mm,
                       .placed = true,
                       .status = cut ? FaceStatus::Removed : face.status,
                       .inside = face.inside,
                       .face = label});
  }
  return regions;
}

// The plan's lines from its inner edges (upper face first, with their kind) and the sheet outline,
// with the total length of each kind.
void draw_lines(const std::vector<std::pair<Arrangement::Halfedge_const_handle, LineKind>>& edges, Plan& plan) {
  std::map<Arrangement::Vertex_const_handle, std::size_t> vertex_index;
  std::vector<PlanPoint> vertex_points;
  auto index_of = [&](Arrangement::Vertex_const_handle v) {
    auto [it, fresh] = vertex_index.try_emplace(v, vertex_points.size());
    if (fresh) vertex_points.push_back({nearest_coordinate(v->point(), 0), nearest_coordinate(v->point(), 1)});
    return it->second;
  };
  std::vector<std::pair<std::size_t, std::size_t>> by_kind[5];
  for (const auto& [he, kind] : edges) {
    const double length = length_of(he);
    (kind == LineKind::Cut || kind == LineKind::CutOut ? plan.cut_mm
     : kind == LineKind::Mountain                      ? plan.mountain_mm
                                                       : plan.valley_mm) += length;
    by_kind[static_cast<int>(kind)].emplace_back(index_of(he->source()), index_of(he->target()));
  }
  for (const LineKind kind : {LineKind::Cut, LineKind::Mountain, LineKind::Valley, LineKind::CutOut}) {
    std::vector<PlanPolyline> lines = chain_segments(kind, by_kind[static_cast<int>(kind)], vertex_points);
    plan.lines.insert(plan.lines.end(), std::make_move_iterator(lines.begin()), std::make_move_iterator(lines.end()));
  }
  const Sheet& sheet = plan.sheet;
  plan.lines.push_back({LineKind::Outline,
                        {{0, sheet.min_Y()},
                         {sheet.width_mm, sheet.min_Y()},
                         {sheet.width_mm, sheet.max_Y()},
                         {0, sheet.max_Y()},
                         {0, sheet.min_Y()}}});
}

// A point inside each face: its pixel nearest the centroid of its pixels.
void place_inside_points(const Grid<std::int32_t>& labels, const PixelGrid& grid, std::vector<PlanFace>& faces) {
  const std::size_t n = faces.size();
  std::vector<double> sum_col(n, 0), sum_row(n, 0), count(n, 0);
  for (int row = 0; row < labels.rows; ++row)
    for (int col = 0; col < labels.cols; ++col) {
      const auto f = static_cast<std::size_t>(labels(col, row));
      sum_col[f] += col, sum_row[f] += row, count[f] += 1;
    }
  // The means once, not two divisions a pixel (seedlike/torus: 2.5 -> 0.8 % of its samples here).
  std::vector<double> best(n, 1e300), mean_col(n), mean_row(n);
  for (std::size_t f = 0; f < n; ++f) mean_col[f] = sum_col[f] / count[f], mean_row[f] = sum_row[f] / count[f];
  for (int row = 0; row < labels.rows; ++row)
    for (int col = 0; col < labels.cols; ++col) {
      const auto f = static_cast<std::size_t>(labels(col, row));
      const double dc = col - mean_col[f], dr = row - mean_row[f], d2 = dc * dc + dr * dr;
      if (d2 < best[f]) best[f] = d2, faces[f].inside = {grid.X(col), grid.Y(row)};
    }
}

// Raster faces with pixels but no area in the exact plan. One at most two pixels tall in every
// column may vanish when the folds on both its sides snap onto their lines (up to a pixel each):
// collapsed, not lost.
void count_vanished_faces(const Grid<std::int32_t>& labels, const std::vector<RasterFace>& faces,
                          const std::vector<double>& area, Plan& plan) {
  std::vector<int> tallest(faces.size(), 0), run(static_cast<std::size_t>(labels.cols), 0);
  for (int row = 0; row < labels.rows; ++row)
    for (int col = 0; col < labels.cols; ++col) {
      int& r = run[static_cast<std::size_t>(col)];
      r = row > 0 && labels(col, row) == labels(col, row - 1) ? r + 1 : 1;
      auto& t = tallest[static_cast<std::size_t>(labels(col, row))];
      t = std::max(t, r);
    }
  for (std::size_t f = 2; f < faces.size(); ++f)
    if (faces[f].pixels > 0 && !(area[f] > 0)) ++(tallest[f] <= 2 ? plan.collapsed_faces : plan.lost_faces);
}

}  // namespace

Plan ExactPlan::full() const {
  const auto lock = exact_run_lock();
  const State& state = *state_;
  Plan plan = state.plan;
  auto edges = state.edges;
  const auto cut_out = [&](Arrangement::Face_const_handle f) {
    return state.cut_out[static_cast<std::size_t>(state.pieces.of.at(f))];
  };
  for (auto& [he, kind] : edges)
    if (cut_out(he->face()) || cut_out(he->twin()->face())) kind = LineKind::CutOut;
  draw_lines(edges, plan);
  place_inside_points(state.labels, state.grid, plan.faces);
  count_vanished_faces(state.labels, state.faces, state.area, plan);
  plan.regions = regions_of(state.built.arrangement, plan.faces, cut_out);
  return plan;
}

}  // namespace origamic
