// SPDX-License-Identifier: GPL-3.0-or-later
// The exact arrangement drawn from the raster plan's traced boundary chains (exact_plan_chains.hpp).

// Exact numbers here are never shared between threads (see exact_kernel.hpp).
#define CGAL_HAS_NO_THREADS 1

#include "exact_plan_chains.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

namespace origamic::exact {
namespace {

using chains::Chain;
using chains::ChainPoint;
using chains::LatticePoint;
using chains::moved_junctions;
using chains::simplified;

// Where a cut piece's end is drawn when not at its corner: a junction moved onto the model's edge,
// or a fold's end where the model's edge meets it.
struct PieceEnd {
  Point exact;
  std::array<double, 2> near;  // its nearest doubles
};
using PieceEnds = std::array<std::optional<PieceEnd>, 2>;  // a piece's front and back

// Junctions moved onto the model's edges or their folds' lines (chains::moved_junctions), exactly,
// by their corner.
class Junctions {
 public:
  Junctions(const std::vector<chains::MovedJunction>& moved, const Lattice& lattice, const std::vector<Chain>& chains,
            const std::vector<RasterFace>& faces) {
    for (const chains::MovedJunction& m : moved) {
      Point at = lattice.exact(m.X, m.Y, m.u_on_lattice, m.v_on_lattice);
      if (m.on_fold_of >= 0) {
        const Chain& chain = chains[static_cast<std::size_t>(m.on_fold_of)];
        const RasterFace &a = faces[static_cast<std::size_t>(chain.left)],
                         &b = faces[static_cast<std::size_t>(chain.right)];
        at = Point(at.x(), fold_line_Y(a.orientation, FT(a.depth_mm), FT(b.depth_mm)));
      }
      at_.emplace(std::pair{m.corner.u, m.corner.v}, PieceEnd{at, {CGAL::to_double(at.x()), CGAL::to_double(at.y())}});
    }
  }
  // Where a corner is drawn if its junction moved.
  std::optional<PieceEnd> moved(LatticePoint corner) const {
    const auto moved = at_.find({corner.u, corner.v});
    return moved != at_.end() ? std::optional(moved->second) : std::nullopt;
  }
  // The point a corner is drawn at.
  Point operator()(LatticePoint corner, const Lattice& lattice) const {
    const std::optional<PieceEnd> end = moved(corner);
    return end ? end->exact : lattice.exact(corner.u, corner.v);
  }

 private:
  std::map<std::pair<int, int>, PieceEnd> at_;
};

struct Curves {
  std::vector<Traits::Curve_2> curves;
  std::vector<Sides> sides;
  std::vector<std::array<Point, 2>> ends;  // per data index: the segment as inserted
  std::vector<Point> fold_ends;            // where snapped folds end: T-contacts meant to be
  std::int32_t chain = kNoLabel;           // the chain whose segments are being added
  int folds_snapped = 0;
  double off_model_edges_mm = 0;  // the farthest a cut passes from the model's edge it follows

  // A segment with `left` on its left walking p -> q; stored from its lexicographically smaller end.
  // False for a point: nothing is added.
  bool add(const Point& p, const Point& q, std::int32_t left, std::int32_t right) {
    const CGAL::Comparison_result order = CGAL::compare_xy(p, q);
    if (order == CGAL::EQUAL) return false;
    const auto data = static_cast<std::int32_t>(sides.size());
    const bool forward = order == CGAL::SMALLER;
    sides.push_back(forward ? Sides{left, right, chain} : Sides{right, left, chain});
    ends.push_back(forward ? std::array{p, q} : std::array{q, p});
    curves.emplace_back(forward ? Kernel::Segment_2(p, q) : Kernel::Segment_2(q, p), data);
    return true;
  }
};

// Cuts moved onto the model's own edges (where the picture breaks) are kept this close to them: a
// 96-sided drum's rim, 35 mm across, bulges 0.019 mm from its chords.
constexpr double kSimplifyOnBreaks_mm = 0.02;

// What drawing a chain reads besides the chain: the faces on its sides, the lattice with the
// picture's breaks, where junctions moved, and the two tolerances.
struct ChainDrawing {
  const std::vector<RasterFace>& faces;
  const Lattice& lattice;
  const Junctions& junctions;
  double simplify_mm;     // drawn within this of its pixel contour; 0: on it
  double fold_tolerance;  // a V/H boundary this near its fold line snaps onto it
};

// A chain's corners [from, to].
struct CornerSpan {
  std::size_t from = 0, to = 0;
};

Chain piece_of(const Chain& chain, CornerSpan span) {
  return {chain.left, chain.right, {chain.corners.begin() + span.from, chain.corners.begin() + span.to + 1}};
}

// Whether a support lies on either side of the chain.
bool bounds_support(const Chain& chain, const std::vector<RasterFace>& faces) {
  const auto support = [&](std::int32_t f) { return f >= 0 && faces[static_cast<std::size_t>(f)].support; };
  return support(chain.left) || support(chain.right);
}

// Per drawn point of a support's edge, the Y it goes to: the straight run along the lattice row from
// an end whose junction moved off that row (onto its fold's line, or the model's edge) goes along,
// up to the corner where the edge turns. One straight line, where the fold onto the support's
// target ends at the target's slanted edge inside its width, with no notch a pixel's fraction deep
// beside a third face (res_armadillo: 0.19 mm, a place 1.25 mm wide at (146, 80.5)). With the
// junctions moved so (junction_moves.cpp), places narrower than W over the 37 models at W = 2 / 3
// / 5 mm 7,043 / 4,138 / 2,300 -> 6,670 / 3,924 / 2,221, the mean p95 the same to 0.003 W. Every
// chain's run so moved, not only supports', res_bunny_low's supports at W = 2 mm ran to the round
// bound (p95 1.11 -> 6.82 W).
std::vector<std::optional<FT>> rows_following_ends(const Chain& piece, const std::vector<ChainPoint>& points,
                                                   const PieceEnds& ends, const Lattice& lattice) {
  std::vector<std::optional<FT>> run_Y(points.size());
  for (const bool front : {true, false}) {
    const std::optional<PieceEnd>& end = ends[front ? 0 : 1];
    const LatticePoint corner = front ? piece.corners.front() : piece.corners.back();
    if (!end || end->exact.y() == lattice.exact(corner.u, corner.v).y()) continue;
    for (std::size_t m = 1; m + 1 < points.size(); ++m) {
      const std::size_t k = front ? m : points.size() - 1 - m;
      if (points[k].on_break || points[k].lattice.v != corner.v || run_Y[k]) break;
      run_Y[k] = end->exact.y();
    }
  }
  return run_Y;
}

// Where a cut piece's ends are drawn: where given, else where their junctions moved (none: on their
// corners).
PieceEnds piece_ends(const Chain& piece, const ChainDrawing& drawing, PieceEnds ends) {
  if (!ends[0]) ends[0] = drawing.junctions.moved(piece.corners.front());
  if (!ends[1]) ends[1] = drawing.junctions.moved(piece.corners.back());
  return ends;
}

// A cut piece of a chain as simplified draws it, its ends at `ends` (piece_ends).
chains::DrawnChain drawn_piece(const Chain& piece, const ChainDrawing& drawing, const PieceEnds& ends) {
  const auto near = [](const std::optional<PieceEnd>& end) { return end ? std::optional(end->near) : std::nullopt; };
  // A support is W wide on the pixel lattice. Simplified through its pixel edges' midpoints, a side
  // meeting a staircase lost half a pixel at the corner (the sphere's supports 2.875 mm wide at W =
  // 3). Drawn on their own corners: places narrower than W over the 37 models 5,223 -> 4,646, and
  // the same likeness on each.
  const double lattice_mm = bounds_support(piece, drawing.faces) ? 0.0 : drawing.simplify_mm;
  return simplified(piece, drawing.lattice, drawing.lattice.breaks,
                    {lattice_mm, std::min(drawing.simplify_mm, kSimplifyOnBreaks_mm)}, {near(ends[0]), near(ends[1])});
}

void add_cut(const Chain& chain, CornerSpan span, const ChainDrawing& drawing, Curves& curves,
             const PieceEnds& given = {}) {
  if (span.to <= span.from) return;
  const Chain piece = piece_of(chain, span);
  const Lattice& lattice = drawing.lattice;
  const bool support_edge = bounds_support(chain, drawing.faces);
  const PieceEnds ends = piece_ends(piece, drawing, given);
  const chains::DrawnChain drawn = drawn_piece(piece, drawing, ends);
  const std::vector<ChainPoint>& points = drawn.points;
  curves.off_model_edges_mm = std::max(curves.off_model_edges_mm, drawn.off_edge_mm);
  const auto exact = [&](std::size_t k) {
    if (k == 0 && ends[0]) return ends[0]->exact;
    if (k + 1 == points.size() && ends[1]) return ends[1]->exact;
    const ChainPoint& p = points[k];
    return p.on_break ? lattice.exact(p.X, p.Y, p.on_lattice_u, p.on_lattice_v)
                      : lattice.exact(p.lattice.u, p.lattice.v);
  };
  const std::vector<std::optional<FT>> run_Y =
      support_edge ? rows_following_ends(piece, points, ends, lattice) : std::vector<std::optional<FT>>(points.size());
  const auto drawn_at = [&](std::size_t k) {
    return run_Y[k] ? Point(lattice.exact(points[k].lattice.u, points[k].lattice.v).x(), *run_Y[k]) : exact(k);
  };
  Point from_point = drawn_at(0);
  for (std::size_t k = 1; k < points.size(); ++k) {
    Point to_point = drawn_at(k);
    curves.add(from_point, to_point, chain.left, chain.right);
    from_point = std::move(to_point);
  }
}

// A fold line, as a double and exactly.
struct FoldAt {
  double Y;
  FT exact_Y;
};

// Where the cut piece `span` of a chain comes in on the model's edge at its front end (front) or
// its back end, the fold ends where that edge meets its line, and the cut runs to it: no connector.
std::optional<PieceEnd> fold_end_on_edge(const Chain& chain, CornerSpan span, bool front, const FoldAt& fold,
                                         const Lattice& lattice) {
  if (span.to <= span.from) return std::nullopt;
  const std::optional<double> X = chains::leg_meets_line(piece_of(chain, span), front, fold.Y, lattice, lattice.breaks);
  if (!X) return std::nullopt;
  // A move under a micrometre is the corner's own X, in the rays' rounding.
  const LatticePoint corner = chain.corners[front ? span.from : span.to];
  if (std::abs(*X - lattice.X(corner.u)) < chains::kLeastMove_mm)
    return PieceEnd{Point(lattice.exact(corner.u, corner.v).x(), fold.exact_Y), {lattice.X(corner.u), fold.Y}};
  return PieceEnd{Point(FT(*X), fold.exact_Y), {*X, fold.Y}};
}

// A fold's end slides along its line at most this far to where the cut piece leaving it, as drawn,
// meets the line. Slides of at most 0.5, 1 and 2 px left the 37 models' sliced plans at W = 3 mm the
// same to 3 of their 61,000 chords under W.
constexpr double kFoldEndSlide_px = 1.0;

// A cut leaning back over the fold it leaves by at most this (its run across over its run along,
// under 2 degrees) meets it at a corner of 88 degrees or more, no tip: the fold ends on the cut's
// line, as where it leans forward. A support's side below a wall's edge leans so, from the edge to
// its corner on the lattice; refused, the fold ended a connector's length off (the demo house: a
// notch 0.185 mm deep at two of its stilts' feet). Over the 37 models at W = 3 mm, places
// narrower than W 3,945 -> 3,917, no plan with more; leaning back by up to 0.05 / 0.1 / 0.25 /
// 0.5, 3,911 / 3,911 / 3,932 / 3,924, some plans with more (the fold's end slid along a connector
// from the model's edge to the lattice, a notch 1.4 mm long on arch_stepped_tower at 0.1).
constexpr double kFoldEndLeanBack = 0.03;

// Where the cut piece `span` of a chain, leaving a fold run at its front end (front) or its back
// end, meets the fold's line as it is drawn: its first segment from that end, on from the corner or
// back short of it. The fold then ends there, and no connector along the lattice column joins the
// corner to the line (a cut arriving slanted at the corner met the connector in a notch). Not where
// the cut turns back over the fold (the run goes `forward`, +1 or -1 along X, towards the piece's
// front end or from its back end) by more than kFoldEndLeanBack: the two would meet at an acute
// corner, a tip of the face there.
// Only at a run's ends inside the chain (a junction's moves are junction_moves.cpp's). With this
// and loops closed on their breaks (chain_points.cpp), the 37 models' sliced plans (no supports)
// at W = 3 mm: places narrower than W 4,540 -> 4,515, the chords under W across them 63,772 ->
// 60,913; as finished, 3,909 -> 3,921 and 49,500 -> 46,673, the likeness the same (without the
// tips parted, 4,141 -> 4,143 places): most faces that lose a notch stay narrow elsewhere.
std::optional<PieceEnd> fold_end_along_cut(const Chain& chain, CornerSpan span, bool front, int forward,
                                           const FoldAt& fold, const ChainDrawing& drawing,
                                           std::optional<PieceEnd> far_end) {
  if (span.to <= span.from) return std::nullopt;
  const Chain piece = piece_of(chain, span);
  const Lattice& lattice = drawing.lattice;
  PieceEnds given;
  given[front ? 1 : 0] = std::move(far_end);
  const PieceEnds ends = piece_ends(piece, drawing, given);
  const std::vector<ChainPoint> points = drawn_piece(piece, drawing, ends).points;
  if (points.size() < 2) return std::nullopt;
  const auto at = [&](std::size_t k) {
    if (k == 0 && ends[0]) return ends[0]->near;
    if (k + 1 == points.size() && ends[1]) return ends[1]->near;
    const ChainPoint& p = points[k];
    return p.on_break ? std::array{p.X, p.Y} : std::array{lattice.X(p.lattice.u), lattice.Y(p.lattice.v)};
  };
  const std::array<double, 2> q = at(front ? 0 : points.size() - 1), p = at(front ? 1 : points.size() - 2);
  const double dy = q[1] - p[1];
  if (dy == 0 || (front ? p[0] - q[0] : q[0] - p[0]) * forward < -kFoldEndLeanBack * std::abs(dy)) return std::nullopt;
  const double back = (fold.Y - q[1]) / dy;  // how far back along the segment, in its lengths
  const double X = q[0] + back * (q[0] - p[0]);
  if (!(back > -1) || !(std::abs(X - q[0]) <= kFoldEndSlide_px * lattice.px_mm)) return std::nullopt;
  // A slide under a micrometre (a cut square to the fold) keeps the corner's own X, exactly.
  const LatticePoint corner = front ? piece.corners.front() : piece.corners.back();
  if (std::abs(X - lattice.X(corner.u)) < chains::kLeastMove_mm)
    return PieceEnd{Point(lattice.exact(corner.u, corner.v).x(), fold.exact_Y), {lattice.X(corner.u), fold.Y}};
  return PieceEnd{Point(FT(X), fold.exact_Y), {X, fold.Y}};
}

// The last corner of the longest X-monotone run of corners near the fold line from corner i.
std::size_t monotone_run_end(const Chain& chain, const std::vector<bool>& near, std::size_t i) {
  std::size_t j = i;
  int direction = 0;
  while (j + 1 < chain.corners.size() && near[j + 1]) {
    const int du = chain.corners[j + 1].u - chain.corners[j].u;
    if (du * direction < 0) break;
    if (du != 0) direction = du > 0 ? 1 : -1;
    ++j;
  }
  return j;
}

// §4.5: where a boundary between V(d) and H(h) runs within `tolerance` of the fold line Y = h - d,
// monotonically along X, that run becomes one exact segment on the line: the faces are extended or
// trimmed to meet on it. Short vertical cuts join its ends to the corners the run had (they name no
// face; the arrangement finds their sides). The rest of the boundary is a cut.
void add_chain(const Chain& chain, Fallback fallback, ChainDrawing drawing, Curves& curves) {
  const std::size_t last = chain.corners.size() - 1;
  if (fallback != Fallback::None) drawing.simplify_mm = 0;
  const Lattice& lattice = drawing.lattice;
  const RasterFace &a = drawing.faces[static_cast<std::size_t>(chain.left)],
                   &b = drawing.faces[static_cast<std::size_t>(chain.right)];
  if (fallback == Fallback::PixelContour || a.orientation == b.orientation || a.hole || b.hole)
    return add_cut(chain, {0, last}, drawing, curves);
  const FoldAt fold{fold_line_Y(a.orientation, a.depth_mm, b.depth_mm),
                    fold_line_Y(a.orientation, FT(a.depth_mm), FT(b.depth_mm))};
  if (!(std::abs(fold.Y) < lattice.half_mm)) return add_cut(chain, {0, last}, drawing, curves);
  std::vector<bool> near(chain.corners.size());
  for (std::size_t i = 0; i <= last; ++i)
    near[i] = std::abs(lattice.Y(chain.corners[i].v) - fold.Y) <= drawing.fold_tolerance;
  const auto on_edge = [&](CornerSpan span, bool front) -> std::optional<PieceEnd> {
    if (fallback != Fallback::None) return std::nullopt;
    return fold_end_on_edge(chain, span, front, fold, lattice);
  };
  std::size_t cut_from = 0, i = 0;
  std::optional<PieceEnd> cut_from_end;  // where the cut from cut_from starts, if not at its corner
  while (i <= last) {
    if (!near[i]) {
      ++i;
      continue;
    }
    const std::size_t j = monotone_run_end(chain, near, i);
    if (chain.corners[i].u == chain.corners[j].u) {
      i = j + 1;
      continue;
    }
    const int forward = chain.corners[j].u > chain.corners[i].u ? 1 : -1;
    std::optional<PieceEnd> start_on_edge = on_edge({cut_from, i}, false);
    if (!start_on_edge && i > 0 && fallback == Fallback::None)
      start_on_edge = fold_end_along_cut(chain, {cut_from, i}, false, forward, fold, drawing, cut_from_end);
    std::size_t next_cut_to = j + 1;  // the cut after the run ends at the next run or the chain's end
    while (next_cut_to <= last && !near[next_cut_to]) ++next_cut_to;
    std::optional<PieceEnd> end_on_edge = on_edge({j, std::min(next_cut_to, last)}, true);
    if (!end_on_edge && j < last && fallback == Fallback::None)
      end_on_edge =
          fold_end_along_cut(chain, {j, std::min(next_cut_to, last)}, true, forward, fold, drawing, std::nullopt);
    const LatticePoint start = chain.corners[i], end = chain.corners[j];
    const Point s = drawing.junctions(start, lattice), e = drawing.junctions(end, lattice);
    // Ends moved onto the model's edge must leave the fold running the way the run did: on a run a
    // pixel or two long they could meet or cross. Then the fold keeps its corners' X, and if moved
    // junctions still turn it round, the run stays a cut.
    const auto keeps_its_way = [&](const Point& from, const Point& to) {
      return CGAL::compare_x(from, to) == (end.u > start.u ? CGAL::SMALLER : CGAL::LARGER);
    };
    if (!keeps_its_way(start_on_edge ? start_on_edge->exact : s, end_on_edge ? end_on_edge->exact : e))
      start_on_edge.reset(), end_on_edge.reset();
    if (!keeps_its_way(s, e)) {
      i = j + 1;
      continue;
    }
    add_cut(chain, {cut_from, i}, drawing, curves, {cut_from_end, start_on_edge});
    const Point s_on = start_on_edge ? start_on_edge->exact : Point(s.x(), fold.exact_Y);
    const Point e_on = end_on_edge ? end_on_edge->exact : Point(e.x(), fold.exact_Y);
    if (curves.add(s_on, e_on, chain.left, chain.right)) curves.sides.back().fold = true;
    const std::int32_t owner = std::exchange(curves.chain, kNoLabel);  // connectors lie along other cuts
    if (!start_on_edge) curves.add(s, s_on, kNoLabel, kNoLabel);
    if (!end_on_edge) curves.add(e, e_on, kNoLabel, kNoLabel);
    curves.chain = owner;
    curves.fold_ends.push_back(s_on);
    curves.fold_ends.push_back(e_on);
    ++curves.folds_snapped;
    cut_from = j;
    cut_from_end = end_on_edge;
    i = j + 1;
  }
  add_cut(chain, {cut_from, last}, drawing, curves, {cut_from_end, std::nullopt});
}

// What each chain's ends allow its junctions: a chain drawn on its raster contour (fallen back, or
// nothing simplified) keeps them on the lattice; an end that may snap onto its fold (add_chain)
// moves only along the fold.
std::vector<chains::ChainEnds> chain_ends(const ArrangementInput& in, const std::vector<Fallback>& fallback) {
  std::vector<chains::ChainEnds> ends(in.chains.size());
  for (std::size_t i = 0; i < in.chains.size(); ++i) {
    const Chain& chain = in.chains[i];
    const RasterFace &a = in.faces[static_cast<std::size_t>(chain.left)],
                     &b = in.faces[static_cast<std::size_t>(chain.right)];
    ends[i].beside_support = bounds_support(chain, in.faces);
    if (fallback[i] != Fallback::None || in.simplify_mm <= 0) {
      ends[i].pinned = true;
    } else if (a.orientation != b.orientation && !a.hole && !b.hole) {
      const double fold_Y = fold_line_Y(a.orientation, a.depth_mm, b.depth_mm);
      if (!(std::abs(fold_Y) < in.lattice.half_mm)) continue;
      const LatticePoint corners[2] = {chain.corners.front(), chain.corners.back()};
      for (const int end : {0, 1})
        if (std::abs(in.lattice.Y(corners[end].v) - fold_Y) <= in.fold_tolerance) ends[i].fold_Y[end] = fold_Y;
    }
  }
  return ends;
}

// Every chain's segments, their junctions moved onto the model's edges or fold lines, and the sheet's
// outline.
Curves chain_curves(const ArrangementInput& in, const std::vector<Fallback>& fallback) {
  Curves curves;
  const chains::JunctionMoves moves =
      moved_junctions(in.chains, in.lattice, in.lattice.breaks, chain_ends(in, fallback));
  const Junctions junctions(moves.moved, in.lattice, in.chains, in.faces);
  const ChainDrawing drawing{in.faces, in.lattice, junctions, in.simplify_mm, in.fold_tolerance};
  for (std::size_t i = 0; i < in.chains.size(); ++i) {
    if (moves.collapsed[i]) continue;
    curves.chain = static_cast<std::int32_t>(i);
    add_chain(in.chains[i], fallback[i], drawing, curves);
  }
  curves.chain = kNoLabel;
  const FT W(in.sheet.width_mm), H(in.sheet.half_height_mm());
  const Point corners[4] = {{0, -H}, {W, -H}, {W, H}, {0, H}};
  for (int i = 0; i < 4; ++i) curves.add(corners[i], corners[(i + 1) % 4], kNoLabel, kNoLabel);
  return curves;
}

// Topology check, exact: per chain, whether a segment of it runs through a vertex it does not end
// at. It crosses or touches another boundary there, unless that vertex is the end of a snapped fold
// (a fold meets a cut in a T by design), or a snapped fold crosses there a boundary that shares one
// of its junctions: a slanted cut leaving the fold's corner, which the fold's move trims or extends.
std::vector<bool> crossed_chains(const Arrangement& arrangement, const std::vector<Sides>& sides, Curves& curves,
                                 const std::vector<Chain>& chains, const std::vector<Fallback>& fallback) {
  auto lexicographic = [](const Point& a, const Point& b) { return CGAL::compare_xy(a, b) == CGAL::SMALLER; };
  std::sort(curves.fold_ends.begin(), curves.fold_ends.end(), lexicographic);
  auto neighbours = [&](std::int32_t a, std::int32_t b) {
    const Chain &x = chains[static_cast<std::size_t>(a)], &y = chains[static_cast<std::size_t>(b)];
    auto same = [](LatticePoint p, LatticePoint q) { return p.u == q.u && p.v == q.v; };
    return same(x.corners.front(), y.corners.front()) || same(x.corners.front(), y.corners.back()) ||
           same(x.corners.back(), y.corners.front()) || same(x.corners.back(), y.corners.back());
  };
  std::vector<bool> crossed(chains.size(), false);
  std::vector<std::int32_t> through, folds_through;
  for (auto v = arrangement.vertices_begin(); v != arrangement.vertices_end(); ++v) {
    if (v->is_isolated() ||
        std::binary_search(curves.fold_ends.begin(), curves.fold_ends.end(), v->point(), lexicographic))
      continue;
    through.clear();
    folds_through.clear();
    auto he = v->incident_halfedges(), first = he;
    do {
      for (const std::int32_t d : he->curve().data()) {
        const auto i = static_cast<std::size_t>(d);
        const std::int32_t chain = sides[i].chain;
        if (chain < 0 || v->point() == curves.ends[i][0] || v->point() == curves.ends[i][1]) continue;
        through.push_back(chain);
        if (sides[i].fold) folds_through.push_back(chain);
      }
    } while (++he != first);
    if (!folds_through.empty() &&
        std::ranges::count(folds_through, folds_through[0]) == std::ssize(folds_through)) {  // one fold
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
      if (!(cuts_yield && is_fold(chain))) crossed[static_cast<std::size_t>(chain)] = true;
  }
  return crossed;
}

// Each face takes the label that most of its boundary length names. Sides moved by a snapped fold
// still name the face that was there before: a short minority, outvoted. Returns the faces no label
// has a majority of; the chains round such a face are marked in `disputed`.
int label_faces(Arrangement& arrangement, const std::vector<Sides>& sides, std::vector<bool>& disputed) {
  int conflicts = 0;
  std::vector<std::pair<std::int32_t, double>> votes;  // a face's few labels: a map per face cost more
  for (auto f = arrangement.faces_begin(); f != arrangement.faces_end(); ++f) {
    f->set_data(kNoLabel);
    if (f->is_unbounded()) continue;
    votes.clear();
    double total = 0;
    auto vote = [&](Arrangement::Ccb_halfedge_circulator first) {
      auto he = first;
      do {
        const double length = length_of(he);
        for (const std::int32_t d : he->curve().data()) {
          const Sides& s = sides[static_cast<std::size_t>(d)];
          const std::int32_t label = he->direction() == CGAL::ARR_LEFT_TO_RIGHT ? s.left : s.right;
          if (label < 0) continue;
          const auto known = std::ranges::find(votes, label, &std::pair<std::int32_t, double>::first);
          (known != votes.end() ? known->second : votes.emplace_back(label, 0.0).second) += length;
          total += length;
        }
      } while (++he != first);
    };
    for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) vote(*ccb);
    for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) vote(*ccb);
    std::int32_t best = kNoLabel;
    double best_votes = 0;
    for (const auto& [label, weight] : votes)  // ties to the smallest label
      if (weight > best_votes || (weight == best_votes && best != kNoLabel && label < best))
        best = label, best_votes = weight;
    if (best == kNoLabel || best_votes * 2 <= total) {
      ++conflicts;
      const auto mark = [&](Arrangement::Ccb_halfedge_circulator first) {
        auto he = first;
        do
          for (const std::int32_t d : he->curve().data())
            if (const std::int32_t chain = sides[static_cast<std::size_t>(d)].chain; chain >= 0)
              disputed[static_cast<std::size_t>(chain)] = true;
        while (++he != first);
      };
      for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) mark(*ccb);
      for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) mark(*ccb);
    }
    f->set_data(best);
  }
  return conflicts;
}

void build_arrangement(const ArrangementInput& in, const std::vector<Fallback>& fallback, Built& built) {
  Curves curves = chain_curves(in, fallback);
  built.folds_snapped = curves.folds_snapped;
  built.off_model_edges_mm = curves.off_model_edges_mm;
  built.sides = std::move(curves.sides);
  CGAL::insert(built.arrangement, curves.curves.begin(), curves.curves.end());
  built.crossed = crossed_chains(built.arrangement, built.sides, curves, in.chains, fallback);
  built.disputed.assign(in.chains.size(), false);
  built.conflicts = label_faces(built.arrangement, built.sides, built.disputed);
}

// A chain by its corners and the planes of the faces on its sides (their ids change from plan to
// plan), hashed (FNV-1a): the same chain in the run's next plan, whose ids are new. A chain that shares
// another's hash would start unsimplified, as a stale one does (ChainFallbacks). The floor and the
// back plane are told apart by label: their planes are both 0.
std::uint64_t chain_fallback_key(const Chain& chain, const std::vector<RasterFace>& faces) {
  std::uint64_t hash = 14695981039346656037ULL;
  const auto mix = [&](std::uint64_t x) {
    for (int byte = 0; byte < 8; ++byte, x >>= 8) hash = (hash ^ (x & 0xff)) * 1099511628211ULL;
  };
  for (const std::int32_t label : {chain.left, chain.right}) {
    const RasterFace& face = faces[static_cast<std::size_t>(label)];
    mix(std::bit_cast<std::uint64_t>(face.depth_mm));
    mix(static_cast<std::uint64_t>(face.orientation) | std::uint64_t{face.hole} << 8 |
        std::uint64_t{face.support} << 16 | std::uint64_t{label <= kFloorFace} << 24);
  }
  for (const LatticePoint& corner : chain.corners)
    mix(std::uint64_t{static_cast<std::uint32_t>(corner.u)} << 32 | static_cast<std::uint32_t>(corner.v));
  return hash;
}

}  // namespace

// The same chains cross in plan after plan of a run of supports (res_dragon_full: the same two in
// each of its 7 plans; res_knot: 66 rebuilds in 45 plans), so each plan starts from those the last
// drew unsimplified (ChainFallbacks); none started so would have been simplified otherwise on the 27
// MANIFEST models at W = 3 mm, the 10 seedlike shapes, res_knot and res_dragon_full at W = 2 mm:
// their DXFs are byte for byte the plans built fresh. A plan built again after planes refit or
// fold pairs spread starts from its supported plan's: built fresh, the chains of res_dragon_res4's
// at W = 2 mm crossed in another order, one fell back to its pixel contour, its fold was lost and
// two faces dangled.
// Simplification or snapping that makes two boundaries cross would change the plan's topology:
// the chains involved fall back a step (unsimplified, then their pixel contour) until none does. So
// do the chains round a face no label has a majority of (most often one of no length in doubles,
// where lines nearly meet): on the Menger slice at W = 2 mm, a simplified cut passing a hair beside a
// fold's end left one, and the lines read back with a fold inside a face.
ArrangementFallbacks arrangement_without_crossings(const ArrangementInput& in, const ChainFallbacks& known,
                                                   Built& built) {
  ArrangementFallbacks result;
  std::vector<Fallback>& fallback = result.fallback;
  fallback.assign(in.chains.size(), Fallback::None);
  std::vector<std::uint64_t> keys(in.chains.size());
  for (std::size_t i = 0; i < in.chains.size(); ++i) {
    keys[i] = chain_fallback_key(in.chains[i], in.faces);
    if (known.unsimplified.contains(keys[i])) fallback[i] = Fallback::Unsimplified;
  }
  for (int builds = 1;; ++builds) {
    built = Built{};
    built.builds = builds;
    build_arrangement(in, fallback, built);
    bool again = false;
    result.unresolved = 0;
    for (std::size_t i = 0; i < fallback.size(); ++i) {
      if (!built.crossed[i] && !built.disputed[i]) continue;
      if (fallback[i] == Fallback::PixelContour) {
        result.unresolved += built.crossed[i];
        continue;
      }
      fallback[i] = fallback[i] == Fallback::None ? Fallback::Unsimplified : Fallback::PixelContour;
      again = true;
    }
    if (!again) break;
  }
  for (std::size_t i = 0; i < fallback.size(); ++i)
    if (fallback[i] == Fallback::Unsimplified) result.passed_on.unsimplified.insert(keys[i]);
  return result;
}

}  // namespace origamic::exact
