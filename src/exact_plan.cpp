// SPDX-License-Identifier: GPL-3.0-or-later
// The one translation unit that builds the exact arrangement (CGAL is heavy to compile: keep it here).

// Exact numbers here are never shared between threads (see exact_kernel.hpp).
#define CGAL_HAS_NO_THREADS 1

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>
#include <numeric>
#include <utility>

#include "bands.hpp"
#include "exact_kernel.hpp"
#include "origamic/plan.hpp"

namespace origamic {
namespace {

using exact::approx_x;
using exact::approx_y;
using exact::FT;
using exact::Kernel;
using exact::nearest_double;
using exact::Point;
// Each inserted segment carries the index of its side labels.
using exact::Arrangement;
using exact::Traits;

constexpr std::int32_t kNoLabel = -1;

/// The faces on either side of a segment inserted from its lexicographically smaller end.
struct Sides {
  std::int32_t left = kNoLabel;
  std::int32_t right = kNoLabel;
  std::int32_t chain = kNoLabel;  // the raster boundary it comes from; none for the sheet outline
  bool fold = false;              // a fold snapped onto its line
};

// Plan points on the pixel lattice in half-pixel units: u = 2 col, v = 2 row for pixel corners, odd
// for edge midpoints. Exact coordinates clamp to the sheet, whose edge the last pixels may overhang.
// They are made once per lattice line and shared by the points on it (fewer lazy numbers to make
// and free).
struct Lattice {
  std::vector<FT> exact_X, exact_Y;  // by u, by v
  int rows_above_fold;
  double px_mm, half_mm;

  Lattice(const PixelGrid& grid, const Sheet& sheet)
      : rows_above_fold(grid.rows_above_fold), px_mm(1 / grid.px_per_mm), half_mm(sheet.half_height_mm()) {
    const FT two_ppm = FT(2) * FT(grid.px_per_mm), width(sheet.width_mm), half(sheet.half_height_mm());
    for (int u = 0; u <= 2 * grid.cols; ++u) exact_X.push_back(CGAL::min(FT(u) / two_ppm, width));
    for (int v = 0; v <= 2 * grid.rows; ++v)
      exact_Y.push_back(CGAL::max(CGAL::min(FT(2 * rows_above_fold - v) / two_ppm, half), -half));
  }

  Point exact(int u, int v) const {
    return {exact_X[static_cast<std::size_t>(u)], exact_Y[static_cast<std::size_t>(v)]};
  }
  double X(int u) const { return u * px_mm / 2; }
  double Y(int v) const { return (2 * rows_above_fold - v) * px_mm / 2; }
};

struct LatticePoint {
  int u, v;
};

// One boundary between two faces of the raster plan, traced corner to corner with `left` on its
// left; it ends at junctions (three or more faces meet, or the sheet edge) or closes on itself.
struct Chain {
  std::int32_t left, right;
  std::vector<LatticePoint> corners;
};

// The face map, with pixels whose centre fell outside the sheet (the partial last row or column)
// given the face of the nearest pixel inside, so the arrangement covers the sheet to its edge.
Grid<std::int32_t> labels_inside_sheet(Grid<std::int32_t> labels) {
  std::vector<std::pair<int, int>> ring, next;
  // Only a pixel whose row and column lie next to (or on) ones with outside pixels can border one.
  std::vector<std::uint8_t> row_out(static_cast<std::size_t>(labels.rows), 0),
      col_out(static_cast<std::size_t>(labels.cols), 0);
  for (int row = 0; row < labels.rows; ++row)
    for (int col = 0; col < labels.cols; ++col)
      if (labels(col, row) < 0) row_out[static_cast<std::size_t>(row)] = col_out[static_cast<std::size_t>(col)] = 1;
  auto near = [](const std::vector<std::uint8_t>& out, int i) {
    return out[static_cast<std::size_t>(i)] || (i > 0 && out[static_cast<std::size_t>(i) - 1]) ||
           (static_cast<std::size_t>(i) + 1 < out.size() && out[static_cast<std::size_t>(i) + 1]);
  };
  for (int row = 0; row < labels.rows; ++row)
    for (int col = 0; col < labels.cols; ++col) {
      if (!near(row_out, row) || !near(col_out, col) || labels(col, row) < 0) continue;
      const bool borders_outside = (col > 0 && labels(col - 1, row) < 0) || (col + 1 < labels.cols && labels(col + 1, row) < 0) ||
                                   (row > 0 && labels(col, row - 1) < 0) || (row + 1 < labels.rows && labels(col, row + 1) < 0);
      if (borders_outside) ring.emplace_back(col, row);
    }
  while (!ring.empty()) {
    next.clear();
    for (const auto& [col, row] : ring)
      for (const auto& [c, r] : {std::pair{col - 1, row}, {col + 1, row}, {col, row - 1}, {col, row + 1}})
        if (labels.contains(c, r) && labels(c, r) < 0) {
          labels(c, r) = labels(col, row);
          next.emplace_back(c, r);
        }
    ring.swap(next);
  }
  return labels;
}

std::vector<Chain> trace_chains(const Grid<std::int32_t>& labels) {
  const int cols = labels.cols, rows = labels.rows, corner_cols = cols + 1;
  if (cols == 0 || rows == 0) return {};
  auto corner = [&](int c, int r) { return static_cast<std::size_t>(r) * corner_cols + c; };
  struct Edge {
    std::size_t from, to;
    std::int32_t left, right;
  };
  std::vector<Edge> edges;
  // Directed so that the smaller label lies on the left: then each chain runs one way throughout.
  auto directed = [](std::size_t a, std::size_t b, std::int32_t left, std::int32_t right) {
    return left < right ? Edge{a, b, left, right} : Edge{b, a, right, left};
  };
  // The scans run in bands of rows in parallel; each band's edges keep their place in the order.
  // Between pixel rows r - 1 (above) and r, walking +X, above on the left: row by row.
  std::array<std::vector<Edge>, kBands> band_edges;
  for_bands(rows - 1, [&](int band, int begin, int end) {
    for (int r = begin + 1; r < end + 1; ++r)
      for (int c = 0; c < cols; ++c)
        if (labels(c, r - 1) != labels(c, r))
          band_edges[static_cast<std::size_t>(band)].push_back(
              directed(corner(c, r), corner(c + 1, r), labels(c, r - 1), labels(c, r)));
  });
  for (const std::vector<Edge>& band : band_edges) edges.insert(edges.end(), band.begin(), band.end());
  // Between pixel columns c - 1 and c, walking +Y (up), c - 1 on the left: column by column, as the
  // tracing order depends on it, but found row by row (columns are far apart in memory): each band
  // counts its edges per column, and then writes them where its rows fall in each column.
  std::array<std::vector<std::size_t>, kBands> band_next;  // per band and column: where its next edge goes
  for_bands(rows, [&](int band, int begin, int end) {
    std::vector<std::size_t>& count = band_next[static_cast<std::size_t>(band)];
    count.assign(static_cast<std::size_t>(cols), 0);
    for (int r = begin; r < end; ++r)
      for (int c = 1; c < cols; ++c) count[static_cast<std::size_t>(c)] += labels(c - 1, r) != labels(c, r);
  });
  std::size_t total = edges.size();
  for (std::size_t c = 1; c < static_cast<std::size_t>(cols); ++c)
    for (std::vector<std::size_t>& next : band_next) total += std::exchange(next[c], total);
  edges.resize(total);
  for_bands(rows, [&](int band, int begin, int end) {
    std::vector<std::size_t>& next = band_next[static_cast<std::size_t>(band)];
    for (int r = begin; r < end; ++r)
      for (int c = 1; c < cols; ++c)
        if (labels(c - 1, r) != labels(c, r))
          edges[next[static_cast<std::size_t>(c)]++] =
              directed(corner(c, r + 1), corner(c, r), labels(c - 1, r), labels(c, r));
  });

  const std::size_t corners = static_cast<std::size_t>(corner_cols) * (rows + 1);
  std::vector<std::uint8_t> degree(corners, 0);
  std::vector<std::uint32_t> first_out(corners + 1, 0);
  for (const Edge& e : edges) ++degree[e.from], ++degree[e.to], ++first_out[e.from + 1];
  for (std::size_t i = 0; i < corners; ++i) first_out[i + 1] += first_out[i];
  std::vector<std::uint32_t> out(edges.size());
  {
    std::vector<std::uint32_t> fill(first_out.begin(), first_out.end() - 1);
    for (std::uint32_t i = 0; i < edges.size(); ++i) out[fill[edges[i].from]++] = i;
  }
  auto is_junction = [&](std::size_t k) {
    const int c = static_cast<int>(k % corner_cols), r = static_cast<int>(k / corner_cols);
    return degree[k] != 2 || c == 0 || c == cols || r == 0 || r == rows;
  };
  auto lattice = [&](std::size_t k) {
    return LatticePoint{2 * static_cast<int>(k % corner_cols), 2 * static_cast<int>(k / corner_cols)};
  };

  std::vector<bool> used(edges.size(), false);
  std::vector<Chain> chains;
  auto follow = [&](std::uint32_t first) {
    Chain chain{edges[first].left, edges[first].right, {lattice(edges[first].from)}};
    std::uint32_t e = first;
    for (;;) {
      used[e] = true;
      const std::size_t at = edges[e].to;
      chain.corners.push_back(lattice(at));
      if (is_junction(at)) break;
      std::uint32_t next = UINT32_MAX;
      for (std::uint32_t i = first_out[at]; i < first_out[at + 1]; ++i)
        if (!used[out[i]]) next = out[i];
      if (next == UINT32_MAX) break;  // a closed loop is back at its start
      e = next;
    }
    chains.push_back(std::move(chain));
  };
  for (std::size_t k = 0; k < corners; ++k)
    if (degree[k] > 0 && is_junction(k))
      for (std::uint32_t i = first_out[k]; i < first_out[k + 1]; ++i)
        if (!used[out[i]]) follow(out[i]);
  for (std::uint32_t i = 0; i < edges.size(); ++i)
    if (!used[i]) follow(i);
  return chains;
}

// Douglas-Peucker over the chain's edge midpoints between its two fixed end corners.
std::vector<LatticePoint> simplified(const Chain& chain, const Lattice& lattice, double tolerance_mm) {
  if (tolerance_mm <= 0) return chain.corners;
  std::vector<LatticePoint> points = {chain.corners.front()};
  for (std::size_t i = 1; i < chain.corners.size(); ++i) {
    const LatticePoint a = chain.corners[i - 1], b = chain.corners[i];
    points.push_back({(a.u + b.u) / 2, (a.v + b.v) / 2});
  }
  points.push_back(chain.corners.back());
  std::vector<bool> keep(points.size(), false);
  keep.front() = keep.back() = true;
  std::vector<std::pair<std::size_t, std::size_t>> stack = {{0, points.size() - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j <= i + 1) continue;
    const double ax = lattice.X(points[i].u), ay = lattice.Y(points[i].v);
    const double bx = lattice.X(points[j].u), by = lattice.Y(points[j].v);
    const double dx = bx - ax, dy = by - ay, length = std::hypot(dx, dy);
    double worst = -1;
    std::size_t worst_k = i;
    for (std::size_t k = i + 1; k < j; ++k) {
      const double px = lattice.X(points[k].u) - ax, py = lattice.Y(points[k].v) - ay;
      const double distance = length > 0 ? std::abs(dx * py - dy * px) / length : std::hypot(px, py);
      if (distance > worst) worst = distance, worst_k = k;
    }
    if (worst > tolerance_mm) {
      keep[worst_k] = true;
      stack.emplace_back(i, worst_k);
      stack.emplace_back(worst_k, j);
    }
  }
  std::vector<LatticePoint> result;
  for (std::size_t k = 0; k < points.size(); ++k)
    if (keep[k]) result.push_back(points[k]);
  return result;
}

struct Curves {
  std::vector<Traits::Curve_2> curves;
  std::vector<Sides> sides;
  std::vector<std::array<Point, 2>> ends;  // per data index: the segment as inserted
  std::vector<Point> fold_ends;            // where snapped folds end: T-contacts meant to be
  std::int32_t chain = kNoLabel;           // the chain whose segments are being added
  int folds_snapped = 0;

  // A segment with `left` on its left walking p -> q; stored from its lexicographically smaller end.
  void add(const Point& p, const Point& q, std::int32_t left, std::int32_t right) {
    const CGAL::Comparison_result order = CGAL::compare_xy(p, q);
    if (order == CGAL::EQUAL) return;
    const auto data = static_cast<std::int32_t>(sides.size());
    const bool forward = order == CGAL::SMALLER;
    sides.push_back(forward ? Sides{left, right, chain} : Sides{right, left, chain});
    ends.push_back(forward ? std::array{p, q} : std::array{q, p});
    curves.emplace_back(forward ? Kernel::Segment_2(p, q) : Kernel::Segment_2(q, p), data);
  }
};

// How much of the vectorization a chain keeps: a chain that crossed another is first left
// unsimplified, then also unsnapped (its pixel contour, which crosses nothing).
enum class Fallback : std::uint8_t { None, Unsimplified, PixelContour };

void add_cut(const Chain& chain, std::size_t from, std::size_t to, const Lattice& lattice, double simplify_mm,
             Curves& curves) {
  if (to <= from) return;
  const Chain piece{chain.left, chain.right, {chain.corners.begin() + from, chain.corners.begin() + to + 1}};
  const std::vector<LatticePoint> points = simplified(piece, lattice, simplify_mm);
  Point from_point = lattice.exact(points[0].u, points[0].v);
  for (std::size_t k = 1; k < points.size(); ++k) {
    Point to_point = lattice.exact(points[k].u, points[k].v);
    curves.add(from_point, to_point, chain.left, chain.right);
    from_point = std::move(to_point);
  }
}

// §4.5: where a boundary between V(d) and H(h) runs within `tolerance` of the fold line Y = h - d,
// monotonically along X, that run becomes one exact segment on the line: the faces are extended or
// trimmed to meet on it. Short vertical cuts join its ends to the corners the run had (they name no
// face; the arrangement finds their sides). The rest of the boundary is a cut.
void add_chain(const Chain& chain, Fallback fallback, const std::vector<RasterFace>& faces, const Lattice& lattice,
               double simplify_mm, double tolerance, Curves& curves) {
  const std::size_t last = chain.corners.size() - 1;
  if (fallback != Fallback::None) simplify_mm = 0;
  const RasterFace &a = faces[static_cast<std::size_t>(chain.left)], &b = faces[static_cast<std::size_t>(chain.right)];
  if (fallback == Fallback::PixelContour || a.orientation == b.orientation || a.hole || b.hole)
    return add_cut(chain, 0, last, lattice, simplify_mm, curves);
  const RasterFace& v = a.orientation == Orientation::V ? a : b;
  const RasterFace& h = a.orientation == Orientation::H ? a : b;
  const double fold_Y = h.depth_mm - v.depth_mm;
  if (!(std::abs(fold_Y) < lattice.half_mm)) return add_cut(chain, 0, last, lattice, simplify_mm, curves);
  const FT exact_Y = FT(h.depth_mm) - FT(v.depth_mm);
  auto near = [&](std::size_t i) { return std::abs(lattice.Y(chain.corners[i].v) - fold_Y) <= tolerance; };
  std::size_t cut_from = 0, i = 0;
  while (i <= last) {
    if (!near(i)) {
      ++i;
      continue;
    }
    // The longest X-monotone run of near corners from i.
    std::size_t j = i;
    int direction = 0;
    while (j < last && near(j + 1)) {
      const int du = chain.corners[j + 1].u - chain.corners[j].u;
      if (du * direction < 0) break;
      if (du != 0) direction = du > 0 ? 1 : -1;
      ++j;
    }
    if (chain.corners[i].u == chain.corners[j].u) {
      i = j + 1;
      continue;
    }
    add_cut(chain, cut_from, i, lattice, simplify_mm, curves);
    const LatticePoint start = chain.corners[i], end = chain.corners[j];
    const Point s = lattice.exact(start.u, start.v), e = lattice.exact(end.u, end.v);
    const Point s_on(s.x(), exact_Y), e_on(e.x(), exact_Y);
    curves.add(s_on, e_on, chain.left, chain.right);
    curves.sides.back().fold = true;
    const std::int32_t owner = std::exchange(curves.chain, kNoLabel);  // connectors lie along other cuts
    curves.add(s, s_on, kNoLabel, kNoLabel);
    curves.add(e, e_on, kNoLabel, kNoLabel);
    curves.chain = owner;
    curves.fold_ends.push_back(s_on);
    curves.fold_ends.push_back(e_on);
    ++curves.folds_snapped;
    cut_from = j;
    i = j + 1;
  }
  add_cut(chain, cut_from, last, lattice, simplify_mm, curves);
}

// Signed area of a boundary cycle from its vertices' nearest doubles: areas are reported, never
// compared to decide anything.
double ccb_area(Arrangement::Ccb_halfedge_const_circulator first) {
  double twice = 0;
  auto he = first;
  do {
    const Point &p = he->source()->point(), &q = he->target()->point();
    twice += approx_x(p) * approx_y(q) - approx_x(q) * approx_y(p);
  } while (++he != first);
  return twice / 2;
}

struct Built {
  Arrangement arrangement;
  std::vector<Sides> sides;
  std::vector<bool> crossed;  // per chain: one of its segments runs through a vertex it does not end at
  int conflicts = 0;
  int folds_snapped = 0;
};

double length_of(Arrangement::Halfedge_const_handle he) {
  const Point &p = he->source()->point(), &q = he->target()->point();
  return std::hypot(approx_x(p) - approx_x(q), approx_y(p) - approx_y(q));
}

void build_arrangement(const std::vector<Chain>& chains, const std::vector<Fallback>& fallback,
                       const std::vector<RasterFace>& faces, const Lattice& lattice, const Sheet& sheet,
                       double simplify_mm, double fold_tolerance, Built& built) {
  Curves curves;
  for (std::size_t i = 0; i < chains.size(); ++i) {
    curves.chain = static_cast<std::int32_t>(i);
    add_chain(chains[i], fallback[i], faces, lattice, simplify_mm, fold_tolerance, curves);
  }
  curves.chain = kNoLabel;
  const FT W(sheet.width_mm), H(sheet.half_height_mm());
  const Point corners[4] = {{0, -H}, {W, -H}, {W, H}, {0, H}};
  for (int i = 0; i < 4; ++i) curves.add(corners[i], corners[(i + 1) % 4], kNoLabel, kNoLabel);
  built.folds_snapped = curves.folds_snapped;
  built.sides = std::move(curves.sides);
  CGAL::insert(built.arrangement, curves.curves.begin(), curves.curves.end());

  // Topology check, exact: a segment that runs through a vertex it does not end at crosses or
  // touches another boundary there, unless that vertex is the end of a snapped fold (a fold meets a
  // cut in a T by design), or a snapped fold crosses there a boundary that shares one of its
  // junctions: a slanted cut leaving the fold's corner, which the fold's move trims or extends.
  auto lexicographic = [](const Point& a, const Point& b) { return CGAL::compare_xy(a, b) == CGAL::SMALLER; };
  std::sort(curves.fold_ends.begin(), curves.fold_ends.end(), lexicographic);
  auto neighbours = [&](std::int32_t a, std::int32_t b) {
    const Chain &x = chains[static_cast<std::size_t>(a)], &y = chains[static_cast<std::size_t>(b)];
    auto same = [](LatticePoint p, LatticePoint q) { return p.u == q.u && p.v == q.v; };
    return same(x.corners.front(), y.corners.front()) || same(x.corners.front(), y.corners.back()) ||
           same(x.corners.back(), y.corners.front()) || same(x.corners.back(), y.corners.back());
  };
  built.crossed.assign(chains.size(), false);
  std::vector<std::int32_t> through, folds_through;
  for (auto v = built.arrangement.vertices_begin(); v != built.arrangement.vertices_end(); ++v) {
    if (v->is_isolated() ||
        std::binary_search(curves.fold_ends.begin(), curves.fold_ends.end(), v->point(), lexicographic))
      continue;
    through.clear();
    folds_through.clear();
    auto he = v->incident_halfedges(), first = he;
    do {
      for (const std::int32_t d : he->curve().data()) {
        const auto i = static_cast<std::size_t>(d);
        const std::int32_t chain = built.sides[i].chain;
        if (chain < 0 || v->point() == curves.ends[i][0] || v->point() == curves.ends[i][1]) continue;
        through.push_back(chain);
        if (built.sides[i].fold) folds_through.push_back(chain);
      }
    } while (++he != first);
    if (!folds_through.empty() && std::ranges::count(folds_through, folds_through[0]) == std::ssize(folds_through)) {  // one fold
      const std::int32_t fold = folds_through[0];
      if (std::ranges::all_of(through, [&](std::int32_t c) { return c == fold || neighbours(c, fold); })) continue;
    }
    // A cut that touches a snapped fold yields first (unsimplified, then its pixel contour), so
    // that the fold keeps its line; a fold yields only to another fold or to a cut that cannot.
    auto is_fold = [&](std::int32_t c) { return std::ranges::find(folds_through, c) != folds_through.end(); };
    const bool cuts_yield = std::ranges::any_of(through, [&](std::int32_t c) {
      return !is_fold(c) && fallback[static_cast<std::size_t>(c)] != Fallback::PixelContour;
    });
    for (const std::int32_t chain : through)
      if (!(cuts_yield && is_fold(chain))) built.crossed[static_cast<std::size_t>(chain)] = true;
  }

  // Each face takes the label that most of its boundary length names. Sides moved by a snapped fold
  // still name the face that was there before: a short minority, outvoted.
  built.conflicts = 0;
  std::map<std::int32_t, double> votes;
  for (auto f = built.arrangement.faces_begin(); f != built.arrangement.faces_end(); ++f) {
    f->set_data(kNoLabel);
    if (f->is_unbounded()) continue;
    votes.clear();
    double total = 0;
    auto vote = [&](Arrangement::Ccb_halfedge_circulator first) {
      auto he = first;
      do {
        const double length = length_of(he);
        for (const std::int32_t d : he->curve().data()) {
          const Sides& s = built.sides[static_cast<std::size_t>(d)];
          const std::int32_t label = he->direction() == CGAL::ARR_LEFT_TO_RIGHT ? s.left : s.right;
          if (label >= 0) votes[label] += length, total += length;
        }
      } while (++he != first);
    };
    for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) vote(*ccb);
    for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) vote(*ccb);
    std::int32_t best = kNoLabel;
    double best_votes = 0;
    for (const auto& [label, weight] : votes)
      if (weight > best_votes) best = label, best_votes = weight;
    if (best == kNoLabel || best_votes * 2 <= total) ++built.conflicts;
    f->set_data(best);
  }
}

// Joins segments of one kind that meet end to end (at vertices where exactly two of them meet).
std::vector<PlanPolyline> chain_segments(LineKind kind, const std::vector<std::pair<std::size_t, std::size_t>>& segments,
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
// the previous one's doubles is dropped).
std::vector<PlanRegion> regions_of(const Arrangement& arr, const std::vector<PlanFace>& faces) {
  using Face = Arrangement::Face_const_handle;
  using Halfedge = Arrangement::Halfedge_const_handle;
  auto each_halfedge = [](Face f, auto&& visit) {
    for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) {
      auto he = *ccb, first = he;
      do visit(Halfedge(he)); while (++he != first);
    }
    for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) {
      auto he = *ccb, first = he;
      do visit(Halfedge(he)); while (++he != first);
    }
  };
  std::map<Face, bool> joined;
  std::map<Halfedge, bool> walked;
  std::vector<PlanRegion> regions;
  for (auto start = arr.faces_begin(); start != arr.faces_end(); ++start) {
    const std::int32_t label = start->data();
    if (start->is_unbounded() || label < 0 || joined[start]) continue;
    // The connected set of faces with this label, and the halfedges that bound it.
    std::vector<Face> stack = {start};
    std::vector<Halfedge> boundary;
    joined[start] = true;
    while (!stack.empty()) {
      const Face f = stack.back();
      stack.pop_back();
      each_halfedge(f, [&](Halfedge he) {
        const Face other = he->twin()->face();
        if (other->data() != label) boundary.push_back(he);
        else if (!joined[other]) joined[other] = true, stack.push_back(other);
      });
    }
    // Around each boundary vertex, turn through faces of the set to the next boundary halfedge.
    auto next_on_boundary = [&](Halfedge he) {
      Halfedge next = he->next();
      while (next->twin()->face()->data() == label) next = next->twin()->next();
      return next;
    };
    std::vector<std::vector<PlanPoint>> rings;
    for (const Halfedge first : boundary) {
      if (walked[first]) continue;
      std::vector<PlanPoint> ring;
      Halfedge he = first;
      do {
        walked[he] = true;
        const PlanPoint p{nearest_double(he->source()->point().x()), nearest_double(he->source()->point().y())};
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
    regions.push_back({.rings = std::move(rings), .orientation = face.orientation, .depth_mm = face.depth_mm,
                       .placed = true, .status = face.status, .inside = face.inside, .face = label});
  }
  return regions;
}

// The pieces of paper: sets of arrangement faces of one label joined across edges with that label on
// both sides (those edges are no lines of the plan).
struct Pieces {
  std::map<Arrangement::Face_const_handle, std::int32_t> of;  // bounded labelled face -> piece
  std::vector<std::int32_t> label;                            // per piece
};

// An edge under kFoldLineTolerance_mm joins nothing: paper does not hang by it, and the plan's
// files may not even keep it apart from its end points.
bool negligible(Arrangement::Halfedge_const_handle he) {
  const FT tolerance(kFoldLineTolerance_mm);
  return CGAL::compare_squared_distance(he->source()->point(), he->target()->point(), tolerance * tolerance) == CGAL::SMALLER;
}

Pieces pieces_of(const Arrangement& arr) {
  std::vector<Arrangement::Face_const_handle> faces;
  std::map<Arrangement::Face_const_handle, std::int32_t> index;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f)
    if (!f->is_unbounded() && f->data() >= 0) index[f] = static_cast<std::int32_t>(faces.size()), faces.push_back(f);
  std::vector<std::int32_t> parent(faces.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](std::int32_t i) {
    while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
    return i;
  };
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const auto a = e->face(), b = e->twin()->face();
    if (a == b || a->is_unbounded() || b->is_unbounded() || a->data() < 0 || a->data() != b->data() || negligible(e)) continue;
    const std::int32_t ra = root(index.at(a)), rb = root(index.at(b));
    parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
  }
  Pieces pieces;
  std::map<std::int32_t, std::int32_t> piece_of_root;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const auto [it, fresh] = piece_of_root.try_emplace(root(static_cast<std::int32_t>(i)), static_cast<std::int32_t>(pieces.label.size()));
    if (fresh) pieces.label.push_back(faces[i]->data());
    pieces.of[faces[i]] = it->second;
  }
  return pieces;
}

// How badly a status falls short, for the worst piece of a face.
int shortfall(FaceStatus s) {
  switch (s) {
    case FaceStatus::Valid: return 0;
    case FaceStatus::Indirect: return 1;
    case FaceStatus::Removed: return 2;
    case FaceStatus::Dangling: return 3;
    case FaceStatus::Invalid: return 4;
    case FaceStatus::Floating: return 5;
  }
  return 5;
}

// The verdict per raster face from the verdict per piece: a face stands when every piece of it does.
// A floating crumb (a piece under W x W / 8, cut off where a snapped fold met a slanted cut) falls
// out when the card is cut and is no part of the likeness: it is cut out (a hole) and does not count.
// So does a floating piece with holes all round it: it falls out with them.
// Pieces of the back plane and the floor that came loose count as faces of their own.
struct PieceVerdict {
  Validity validity;                   // per raster face
  int loose_card_pieces = 0;           // pieces of the back plane or the floor no fold holds
  std::vector<std::uint8_t> cut_out;   // per piece: a floating crumb, cut out
};

PieceVerdict face_validity(const Validity& by_node, const Pieces& pieces, const std::vector<std::int32_t>& node,
                           const std::vector<double>& piece_area, const std::vector<std::uint8_t>& among_holes,
                           std::size_t faces, double min_strip_mm) {
  const double crumb = min_strip_mm * min_strip_mm / 8;
  PieceVerdict verdict;
  verdict.cut_out.assign(pieces.label.size(), 0);
  Validity& v = verdict.validity;
  v.status.assign(faces, FaceStatus::Valid);
  v.in_X.assign(faces, true);
  v.in_Y.assign(faces, true);
  v.fold_lines.assign(faces, 2);
  std::vector<int> worst(faces, -1);
  std::vector<std::uint8_t> kept(faces, 0);  // some piece of the face stays in the sheet
  for (std::size_t p = 0; p < pieces.label.size(); ++p) {
    const auto f = static_cast<std::size_t>(pieces.label[p]), k = static_cast<std::size_t>(node[p]);
    if (k < 2) continue;  // the card's halves themselves
    if ((piece_area[p] < crumb || among_holes[p]) && by_node.status[k] == FaceStatus::Floating) {
      verdict.cut_out[p] = 1;
      continue;
    }
    kept[f] = 1;
    if (f < 2) {  // a loose piece of the back plane or the floor
      if (by_node.status[k] == FaceStatus::Valid || by_node.status[k] == FaceStatus::Indirect) continue;
      ++verdict.loose_card_pieces;
      v.floating += by_node.status[k] == FaceStatus::Floating, v.dangling += by_node.status[k] == FaceStatus::Dangling;
      v.invalid += by_node.status[k] == FaceStatus::Invalid;
      continue;
    }
    if (shortfall(by_node.status[k]) <= worst[f]) continue;
    worst[f] = shortfall(by_node.status[k]);
    v.status[f] = by_node.status[k];
    v.in_X[f] = by_node.in_X[k], v.in_Y[f] = by_node.in_Y[k], v.fold_lines[f] = by_node.fold_lines[k];
  }
  // A face all of whose pieces fell out is a hole.
  for (std::size_t p = 0; p < pieces.label.size(); ++p)
    if (const auto f = static_cast<std::size_t>(pieces.label[p]); f >= 2 && verdict.cut_out[p] && !kept[f])
      v.status[f] = FaceStatus::Removed;
  count_statuses(v);
  return verdict;
}

// The plan's lines from its inner edges (upper face first, with their kind) and the sheet outline,
// with the total length of each kind.
void draw_lines(const std::vector<std::pair<Arrangement::Halfedge_const_handle, LineKind>>& edges, Plan& plan) {
  std::map<Arrangement::Vertex_const_handle, std::size_t> vertex_index;
  std::vector<PlanPoint> vertex_points;
  auto index_of = [&](Arrangement::Vertex_const_handle v) {
    auto [it, fresh] = vertex_index.try_emplace(v, vertex_points.size());
    if (fresh) vertex_points.push_back({nearest_double(v->point().x()), nearest_double(v->point().y())});
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
  std::vector<double> best(n, 1e300);
  for (int row = 0; row < labels.rows; ++row)
    for (int col = 0; col < labels.cols; ++col) {
      const auto f = static_cast<std::size_t>(labels(col, row));
      const double dc = col - sum_col[f] / count[f], dr = row - sum_row[f] / count[f], d2 = dc * dc + dr * dr;
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

// What a verdict leaves for drawing the plan in full: the arrangement and what was read off it.
struct PlanBuild::State {
  PixelGrid grid;
  std::vector<RasterFace> faces;
  Grid<std::int32_t> labels;
  Built built;
  Pieces pieces;
  std::vector<double> area;                                                    // per raster face
  std::vector<std::pair<Arrangement::Halfedge_const_handle, LineKind>> edges;  // inner edges, upper face first
  std::vector<std::uint8_t> cut_out;                                           // per piece: a crumb, cut out
  Plan plan;                                                                   // the verdict

  // Vertical ray shooting (faces_reached). The exact numbers are read under the lock only; the
  // lines keep their crossings as plain rationals, which threads may read at once (MPFR, which
  // to_interval calls on them, is built thread-safe in Debian).
  struct Crossing {
    exact::Rational Y;
    double Y_near;       // nearest double: a smaller one means a smaller Y, an equal one decides nothing
    std::int32_t above;  // the label between this crossing and the next one up
  };
  struct EdgeSpan {
    double x_lo, x_hi;                      // the edge's x-extent, widened by its doubles' rounding
    Arrangement::Halfedge_const_handle he;  // directed left to right: its face lies above it
  };
  std::mutex mutex;
  // The edges by the pixel columns their x-extents meet, so that a line looks at its column's only.
  std::vector<std::vector<EdgeSpan>> spans_by_column;
  std::map<double, std::vector<Crossing>> lines;  // by x: a map's elements stay where they are
  const std::vector<Crossing>& line_at(double x);
};

// The edges the vertical line X = x crosses, bottom to top. An edge is crossed where x lies in
// [its left end's x, its right end's x): a line through a vertex takes the edges to its right, as a
// line a hair to the right would, and no vertical edge.
const std::vector<PlanBuild::State::Crossing>& PlanBuild::State::line_at(double x) {
  const std::lock_guard lock(mutex);
  if (const auto known = lines.find(x); known != lines.end()) return known->second;
  const Arrangement& arr = built.arrangement;
  const auto columns = static_cast<std::size_t>(std::ceil(plan.sheet.width_mm * grid.px_per_mm)) + 1;
  const auto column_of = [&](double at) {
    return std::min(columns - 1, static_cast<std::size_t>(std::max(0.0, std::floor(at * grid.px_per_mm))));
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

PlanBuild::PlanBuild(const RasterMaps& maps, const SliceResult& sliced, const Sheet& sheet, const PlanOptions& options)
    : state_(std::make_unique<State>()) {
  State& state = *state_;  // built in place: the handles read off the arrangement stay valid
  state.grid = maps.grid;
  // §4.5 in two steps: the raster boundaries move to the pixel row nearest their fold line where
  // they can (align_folds_to_lines; a no-op on plans already aligned), then only those within half a
  // pixel snap onto it. Snapping farther could carry a fold across a neighbouring boundary, which
  // forced the whole chain back to its pixel contour and lost the fold.
  SliceResult slices;  // the fields a plan is built of (a field it comes to read must be copied here)
  slices.min_strip_mm = sliced.min_strip_mm;
  slices.block_px = sliced.block_px;
  slices.face = sliced.face;
  slices.faces = sliced.faces;
  align_folds_to_lines(slices, maps.grid, fold_snap_tolerance_mm(options, slices, maps.grid));
  const Lattice lattice(maps.grid, sheet);
  state.labels = labels_inside_sheet(std::move(slices.face));  // the face map is not read again
  const Grid<std::int32_t>& labels = state.labels;
  const std::vector<Chain> chains = trace_chains(labels);
  const double px_mm = 1 / maps.grid.px_per_mm;
  const double simplify_mm = std::min(options.simplify_mm, px_mm);
  const double fold_tolerance = aligned_fold_tolerance_mm(maps.grid);

  Plan& plan = state.plan;
  plan.sheet = sheet;
  // Simplification or snapping that makes two boundaries cross would change the plan's topology:
  // the chains involved fall back a step (unsimplified, then their pixel contour) until none does.
  std::vector<Fallback> fallback(chains.size(), Fallback::None);
  Built& built = state.built;
  for (;;) {
    built = Built{};
    build_arrangement(chains, fallback, slices.faces, lattice, sheet, simplify_mm, fold_tolerance, built);
    bool again = false;
    plan.unresolved_crossings = 0;
    for (std::size_t i = 0; i < chains.size(); ++i) {
      if (!built.crossed[i]) continue;
      if (fallback[i] == Fallback::PixelContour) {
        ++plan.unresolved_crossings;
        continue;
      }
      fallback[i] = fallback[i] == Fallback::None ? Fallback::Unsimplified : Fallback::PixelContour;
      again = true;
    }
    if (!again) break;
  }
  plan.raw_chains = static_cast<int>(std::ranges::count(fallback, Fallback::Unsimplified));
  plan.unsnapped_chains = static_cast<int>(std::ranges::count(fallback, Fallback::PixelContour));
  plan.simplified = plan.raw_chains + plan.unsnapped_chains == 0;
  const Arrangement& arr = built.arrangement;
  plan.arrangement_valid = arr.is_valid();
  plan.label_conflicts = built.conflicts;
  plan.folds_snapped = built.folds_snapped;

  // Faces: exact areas per label, and the tiling check.
  const std::size_t n = slices.faces.size();
  std::vector<double>& area = state.area;
  area.assign(n, 0.0);
  double total = 0;
  state.pieces = pieces_of(arr);
  const Pieces& pieces = state.pieces;
  std::vector<double> piece_area(pieces.label.size(), 0.0);
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded()) continue;
    ++plan.arrangement_faces;
    double a = 0;
    for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) a += ccb_area(*ccb);
    for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) a += ccb_area(*ccb);  // clockwise: negative
    if (f->data() < 0) continue;  // an unlabelled face leaves a hole in the tiling
    total += a;
    area[static_cast<std::size_t>(f->data())] += a;
    piece_area[static_cast<std::size_t>(pieces.of.at(f))] += a;
  }
  // Validity is decided on pieces of paper: the back plane and the floor are their largest pieces.
  std::vector<std::int32_t> node(pieces.label.size(), -1);
  std::int32_t nodes = 2;
  for (const std::int32_t card : {0, 1}) {
    std::int32_t largest = -1;
    for (std::size_t p = 0; p < pieces.label.size(); ++p)
      if (pieces.label[p] == card && (largest < 0 || piece_area[p] > piece_area[static_cast<std::size_t>(largest)]))
        largest = static_cast<std::int32_t>(p);
    if (largest >= 0) node[static_cast<std::size_t>(largest)] = card;
  }
  for (auto& id : node)
    if (id < 0) id = nodes++;
  // The arrangement is a subdivision by construction; this guards the labelling and the outline.
  const double sheet_area = sheet.width_mm * sheet.height_mm;
  plan.faces_tile_sheet = std::abs(total - sheet_area) <= 1e-9 * sheet_area;

  // Edges: vanish inside a face, folds on their exact line, cuts elsewhere.
  std::map<FT, std::int32_t> fold_line_ids;
  FaceGraph graph;
  graph.faces = nodes;
  graph.holes.assign(static_cast<std::size_t>(nodes), 0);
  for (std::size_t p = 0; p < pieces.label.size(); ++p)
    graph.holes[static_cast<std::size_t>(node[p])] = slices.faces[static_cast<std::size_t>(pieces.label[p])].hole;
  auto node_of = [&](Arrangement::Face_const_handle f) { return node[static_cast<std::size_t>(pieces.of.at(f))]; };
  std::vector<bool> fold_on_top(n, false), fold_on_bottom(n, false);
  auto& edges = state.edges;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    Arrangement::Halfedge_const_handle he = e;
    if (he->direction() != CGAL::ARR_LEFT_TO_RIGHT) he = he->twin();  // he->face() is above or left
    if (he->face()->is_unbounded() || he->twin()->face()->is_unbounded()) continue;
    const std::int32_t upper = he->face()->data(), lower = he->twin()->face()->data();
    if (upper == lower || upper < 0 || lower < 0) continue;
    const Point &p = he->source()->point(), &q = he->target()->point();
    const RasterFace &fu = slices.faces[static_cast<std::size_t>(upper)], &fl = slices.faces[static_cast<std::size_t>(lower)];
    LineKind kind = LineKind::Cut;
    if (CGAL::compare_y(p, q) == CGAL::EQUAL && fu.orientation != fl.orientation && !fu.hole && !fl.hole &&
        !negligible(he)) {
      const RasterFace& v = fu.orientation == Orientation::V ? fu : fl;
      const RasterFace& h = fu.orientation == Orientation::H ? fu : fl;
      if (p.y() == FT(h.depth_mm) - FT(v.depth_mm)) {
        // Going up the plan: V then H is a mountain fold, H then V a valley fold.
        kind = fu.orientation == Orientation::H ? LineKind::Mountain : LineKind::Valley;
        const auto [it, fresh] = fold_line_ids.try_emplace(p.y(), static_cast<std::int32_t>(fold_line_ids.size()));
        graph.folds.push_back({node_of(he->face()), node_of(he->twin()->face()), it->second});
        fold_on_top[static_cast<std::size_t>(lower)] = true;
        fold_on_bottom[static_cast<std::size_t>(upper)] = true;
      }
    }
    if (fu.hole || fl.hole) kind = LineKind::CutOut;
    edges.push_back({he, kind});
  }
  // Folds under kFoldLineTolerance_mm apart are one line, as validate reads them: the face between
  // them swings about it. (Depths reached along different paths can differ in a double's last bits.)
  {
    std::vector<std::int32_t> line_of(fold_line_ids.size());
    std::int32_t line = -1;
    const FT* previous = nullptr;
    for (const auto& [Y, id] : fold_line_ids) {
      if (!previous || Y - *previous > FT(kFoldLineTolerance_mm)) ++line;
      line_of[static_cast<std::size_t>(id)] = line;
      previous = &Y;
    }
    for (Fold& fold : graph.folds) fold.line = line_of[static_cast<std::size_t>(fold.line)];
  }
  std::vector<std::uint8_t> among_holes(pieces.label.size(), 1);
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
    for (const auto& [side, other] : {std::pair{e->face(), e->twin()->face()}, {e->twin()->face(), e->face()}}) {
      if (side->is_unbounded() || side->data() < 0 || side->data() == other->data()) continue;
      if (other->is_unbounded() || other->data() < 0 || !slices.faces[static_cast<std::size_t>(other->data())].hole)
        among_holes[static_cast<std::size_t>(pieces.of.at(side))] = 0;
    }
  const PieceVerdict verdict =
      face_validity(validate(graph), pieces, node, piece_area, among_holes, n, slices.min_strip_mm);
  plan.validity = verdict.validity;
  plan.loose_card_pieces = verdict.loose_card_pieces;
  plan.crumbs_cut_out = static_cast<int>(std::ranges::count(verdict.cut_out, 1));
  plan.pieces = static_cast<int>(pieces.label.size());
  plan.faces.resize(n);
  for (std::size_t f = 0; f < n; ++f) {
    PlanFace& face = plan.faces[f];
    face.orientation = slices.faces[f].orientation;
    face.depth_mm = slices.faces[f].depth_mm;
    face.area_mm2 = area[f];
    face.fold_on_top = fold_on_top[f];
    face.fold_on_bottom = fold_on_bottom[f];
    face.support = slices.faces[f].support;
    face.status = plan.validity.status[f];
  }
  state.cut_out = verdict.cut_out;
  state.faces = std::move(slices.faces);
}

PlanBuild::~PlanBuild() = default;
PlanBuild::PlanBuild(PlanBuild&&) noexcept = default;
PlanBuild& PlanBuild::operator=(PlanBuild&&) noexcept = default;

const Plan& PlanBuild::verdict() const { return state_->plan; }
const Grid<std::int32_t>& PlanBuild::face_map() const { return state_->labels; }
const std::vector<RasterFace>& PlanBuild::faces() const { return state_->faces; }

Plan PlanBuild::full() const {
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
  plan.regions = regions_of(state.built.arrangement, plan.faces);
  return plan;
}

namespace {

// Painted band k crossing a ray is labelled kPainted - k on the line, below every face label.
constexpr std::int32_t kPainted = -2;

exact::Rational exact_Y(const FoldLine& line) { return exact::Rational(line.h) - exact::Rational(line.d); }

}  // namespace

std::vector<PlanBuild::Reached> PlanBuild::faces_reached(const Ray& ray) const {
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

Plan build_plan(const RasterMaps& maps, const SliceResult& slices, const Sheet& sheet, const PlanOptions& options) {
  return PlanBuild(maps, slices, sheet, options).full();
}

}  // namespace origamic
