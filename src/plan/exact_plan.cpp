// SPDX-License-Identifier: GPL-3.0-or-later
// The exact plan built: the raster plan's boundaries in an exact arrangement (its folds snapped onto
// their lines), and the verdict read off its pieces of paper. CGAL is heavy to compile: it stays in
// this file and the three that share exact_plan_state.hpp.

// Exact numbers here are never shared between threads (see exact_kernel.hpp).
#define CGAL_HAS_NO_THREADS 1

#include <CGAL/Arr_observer.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>
#include <utility>

#include "boundary_chains.hpp"
#include "chain_points.hpp"
#include "exact_plan_state.hpp"
#include "exact_runs.hpp"
#include "origamic/plan.hpp"
#include "raster_plan_edits.hpp"

namespace origamic {
namespace {

using chains::Chain;
using chains::ChainPoint;
using chains::junctions_on_breaks;
using chains::labels_inside_sheet;
using chains::LatticePoint;
using chains::simplified;
using chains::trace_chains;
using exact::approx_x;
using exact::approx_y;
using exact::Arrangement;
using exact::Built;
using exact::face_validity;
using exact::FT;
using exact::Kernel;
using exact::kNoLabel;
using exact::length_of;
using exact::negligible;
using exact::Pieces;
using exact::pieces_of;
using exact::PieceVerdict;
using exact::Point;
using exact::Sides;
// Each inserted segment carries the index of its side labels.
using exact::Traits;

// The lattice's points (boundary_chains.hpp), exactly. Exact coordinates clamp to the sheet, whose
// edge the last pixels may overhang.
// They are made once per lattice line and shared by the points on it (fewer lazy numbers to make
// and free).
struct Lattice : chains::LatticeScale {
  std::vector<FT> X_of_u, Y_of_v;
  double half_mm;
  chains::PictureBreaks breaks;

  Lattice(const RasterMaps& maps, const Sheet& sheet)
      : LatticeScale{maps.grid.rows_above_fold, 1 / maps.grid.px_per_mm},
        half_mm(sheet.half_height_mm()),
        breaks{maps.break_right, maps.break_below} {
    const PixelGrid& grid = maps.grid;
    const FT two_ppm = FT(2) * FT(grid.px_per_mm), width(sheet.width_mm), half(sheet.half_height_mm());
    for (int u = 0; u <= 2 * grid.cols; ++u) X_of_u.push_back(CGAL::min(FT(u) / two_ppm, width));
    for (int v = 0; v <= 2 * grid.rows; ++v)
      Y_of_v.push_back(CGAL::max(CGAL::min(FT(2 * rows_above_fold - v) / two_ppm, half), -half));
  }

  Point exact(int u, int v) const { return {X_of_u[static_cast<std::size_t>(u)], Y_of_v[static_cast<std::size_t>(v)]}; }
  // A point off the lattice, from its doubles, but on a lattice line exactly where u (v) is >= 0.
  Point exact(double X, double Y, int u, int v) const {
    return {u >= 0 ? X_of_u[static_cast<std::size_t>(u)] : FT(X), v >= 0 ? Y_of_v[static_cast<std::size_t>(v)] : FT(Y)};
  }
};

// Where a cut piece's end is drawn when not at its corner: a junction moved onto the model's edge,
// or a fold's end where the model's edge meets it.
struct PieceEnd {
  Point exact;
  std::array<double, 2> near;  // its nearest doubles
};

// Junctions moved onto the model's edges (chains::junctions_on_breaks), exactly, by their corner.
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

// How much of the vectorization a chain keeps: a chain that crossed another is first left
// unsimplified, then also unsnapped (its pixel contour, which crosses nothing).
enum class Fallback : std::uint8_t { None, Unsimplified, PixelContour };

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

void add_cut(const Chain& chain, CornerSpan span, const ChainDrawing& drawing, Curves& curves,
             std::array<std::optional<PieceEnd>, 2> ends = {}) {
  if (span.to <= span.from) return;
  const Chain piece = piece_of(chain, span);
  const Lattice& lattice = drawing.lattice;
  if (!ends[0]) ends[0] = drawing.junctions.moved(piece.corners.front());
  if (!ends[1]) ends[1] = drawing.junctions.moved(piece.corners.back());
  const auto near = [](const std::optional<PieceEnd>& end) { return end ? std::optional(end->near) : std::nullopt; };
  const chains::DrawnChain drawn = simplified(
      piece, lattice, lattice.breaks, {drawing.simplify_mm, std::min(drawing.simplify_mm, kSimplifyOnBreaks_mm)},
      {near(ends[0]), near(ends[1])});
  const std::vector<ChainPoint>& points = drawn.points;
  curves.off_model_edges_mm = std::max(curves.off_model_edges_mm, drawn.off_edge_mm);
  const auto exact = [&](std::size_t k) {
    if (k == 0 && ends[0]) return ends[0]->exact;
    if (k + 1 == points.size() && ends[1]) return ends[1]->exact;
    const ChainPoint& p = points[k];
    return p.on_break ? lattice.exact(p.X, p.Y, p.on_lattice_u, p.on_lattice_v)
                      : lattice.exact(p.lattice.u, p.lattice.v);
  };
  Point from_point = exact(0);
  for (std::size_t k = 1; k < points.size(); ++k) {
    Point to_point = exact(k);
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
    std::optional<PieceEnd> start_on_edge = on_edge({cut_from, i}, false);
    std::size_t next_cut_to = j + 1;  // the cut after the run ends at the next run or the chain's end
    while (next_cut_to <= last && !near[next_cut_to]) ++next_cut_to;
    std::optional<PieceEnd> end_on_edge = on_edge({j, std::min(next_cut_to, last)}, true);
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

// What the arrangement is built of: the traced chains, the faces on their sides, the lattice, the
// sheet and the tolerances.
struct ArrangementInput {
  const std::vector<Chain>& chains;
  const std::vector<RasterFace>& faces;
  const Lattice& lattice;
  const Sheet& sheet;
  double simplify_mm;
  double fold_tolerance;
};

// What each chain's ends allow its junctions: a chain drawn on its raster contour (fallen back, or
// nothing simplified) keeps them on the lattice; an end that may snap onto its fold (add_chain)
// moves only along the fold.
std::vector<chains::ChainEnds> chain_ends(const ArrangementInput& in, const std::vector<Fallback>& fallback) {
  std::vector<chains::ChainEnds> ends(in.chains.size());
  for (std::size_t i = 0; i < in.chains.size(); ++i) {
    const Chain& chain = in.chains[i];
    const RasterFace &a = in.faces[static_cast<std::size_t>(chain.left)],
                     &b = in.faces[static_cast<std::size_t>(chain.right)];
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

// Every chain's segments, their junctions moved onto the model's edges, and the sheet's outline.
Curves chain_curves(const ArrangementInput& in, const std::vector<Fallback>& fallback) {
  Curves curves;
  const chains::JunctionMoves moves =
      junctions_on_breaks(in.chains, in.lattice, in.lattice.breaks, chain_ends(in, fallback));
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
// has a majority of.
int label_faces(Arrangement& arrangement, const std::vector<Sides>& sides) {
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
    if (best == kNoLabel || best_votes * 2 <= total) ++conflicts;
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
  built.conflicts = label_faces(built.arrangement, built.sides);
}

// Paper stays on the card: an H(h) face holds plan points up to Y = h (depth h - Y >= 0), a V(d)
// face down to Y = -d (height Y + d >= 0). A face may reach past that line where a fold snapped
// onto it and a slanted cut still leaves the pixel row the fold moved from (capitol: 0.08 mm
// behind the back plane). Each such face is cut along its line across its width, and the part
// beyond goes to the back plane (behind an H face) or the floor (below a V face): the face that
// folds with it on exactly that line. Other faces the cut line crosses keep their label on both
// sides (no line of the plan). Returns how many faces were trimmed.
int keep_faces_on_the_card(const std::vector<RasterFace>& faces, Built& built) {
  Arrangement& arr = built.arrangement;
  auto limit_of = [](const RasterFace& face) {  // its fold line with the back plane (H) or the floor (V)
    return fold_line_Y(face.orientation, FT(face.depth_mm), FT(0));
  };
  auto beyond = [](const RasterFace& face, const Point& p, const FT& limit) {
    return face.orientation == Orientation::H ? p.y() > limit : p.y() < limit;
  };
  auto each_vertex = [](Arrangement::Face_const_handle f, auto&& visit) {
    for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) {
      auto he = *ccb, first = he;
      do visit(he->source()->point());
      while (++he != first);
    }
    for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) {
      auto he = *ccb, first = he;
      do visit(he->source()->point());
      while (++he != first);
    }
  };
  std::vector<Kernel::Segment_2> cuts;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded() || f->data() < 0) continue;
    const RasterFace& face = faces[static_cast<std::size_t>(f->data())];
    if (face.hole) continue;
    const FT limit = limit_of(face);
    bool past = false, first = true;
    FT x_lo, x_hi;
    each_vertex(f, [&](const Point& p) {
      past = past || beyond(face, p, limit);
      if (first || p.x() < x_lo) x_lo = p.x();
      if (first || p.x() > x_hi) x_hi = p.x();
      first = false;
    });
    if (past) cuts.emplace_back(Point(x_lo, limit), Point(x_hi, limit));
  }
  if (cuts.empty()) return 0;

  struct KeepLabels : CGAL::Arr_observer<Arrangement> {
    using CGAL::Arr_observer<Arrangement>::Arr_observer;
    void after_split_face(Face_handle f, Face_handle new_f, bool) override { new_f->set_data(f->data()); }
  } keep_labels(arr);
  const auto first_cut = static_cast<std::int32_t>(built.sides.size());
  for (const Kernel::Segment_2& cut : cuts) {
    const auto data = static_cast<std::int32_t>(built.sides.size());
    built.sides.push_back(Sides{});  // names no face: its sides are read off the faces
    CGAL::insert(arr, Traits::Curve_2(cut, data));
  }
  int trimmed = 0;
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded() || f->data() < 0) continue;
    const RasterFace& face = faces[static_cast<std::size_t>(f->data())];
    if (face.hole) continue;
    const FT limit = limit_of(face);
    bool past = false;
    each_vertex(f, [&](const Point& p) { past = past || beyond(face, p, limit); });
    if (!past) continue;
    f->set_data(face.orientation == Orientation::H ? 0 : 1);  // the back plane V(0), the floor H(0)
    ++trimmed;
  }
  // The cut lines' stretches with one label on both sides part nothing: they go, and the faces they
  // crossed are whole again (a stretch under the fold tolerance would otherwise part a crumb off).
  std::vector<Arrangement::Halfedge_handle> parting_nothing;
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const auto& data = e->curve().data();
    if (e->face()->data() == e->twin()->face()->data() &&
        std::ranges::all_of(data, [&](std::int32_t d) { return d >= first_cut; }))
      parting_nothing.push_back(e);
  }
  for (const Arrangement::Halfedge_handle e : parting_nothing) arr.remove_edge(e);
  return trimmed;
}

}  // namespace

ExactPlan::ExactPlan(const RasterMaps& maps, const RasterPlan& sliced, const Sheet& sheet, const PlanOptions& options) {
  const auto lock = exact_run_lock();  // held until the exact numbers are made, or freed on an error
  state_ = std::make_unique<State>();
  try {
    build(*state_, maps, sliced, sheet, options);
  } catch (...) {
    state_.reset();
    throw;
  }
}

// Built in place: the handles read off the arrangement stay valid.
namespace {

// The faces the plan is built from, their V/H boundaries moved to the pixel row nearest their fold
// line where they can (§4.5's first step; a no-op on a plan already aligned).
RasterPlan aligned_faces(const RasterPlan& sliced, const PixelGrid& grid, const PlanOptions& options) {
  RasterPlan faces;  // the fields a plan is built of (a field it comes to read must be copied here)
  faces.min_strip_mm = sliced.min_strip_mm;
  faces.block_px = sliced.block_px;
  faces.face = sliced.face;
  faces.faces = sliced.faces;
  const double tolerance = fold_snap_tolerance_mm(options, faces, grid);
  return align_folds_to_lines(std::move(faces), grid, tolerance);
}

// Simplification or snapping that makes two boundaries cross would change the plan's topology:
// the chains involved fall back a step (unsimplified, then their pixel contour) until none does.
// Returns how far each chain fell back; `unresolved` counts chains that cross on their contour.
std::vector<Fallback> arrangement_without_crossings(const ArrangementInput& in, Built& built, int& unresolved) {
  std::vector<Fallback> fallback(in.chains.size(), Fallback::None);
  for (;;) {
    built = Built{};
    build_arrangement(in, fallback, built);
    bool again = false;
    unresolved = 0;
    for (std::size_t i = 0; i < fallback.size(); ++i) {
      if (!built.crossed[i]) continue;
      if (fallback[i] == Fallback::PixelContour) {
        ++unresolved;
        continue;
      }
      fallback[i] = fallback[i] == Fallback::None ? Fallback::Unsimplified : Fallback::PixelContour;
      again = true;
    }
    if (!again) return fallback;
  }
}

// Areas from the arrangement's faces: per raster face's label, per piece of paper, in all.
struct Areas {
  std::vector<double> of_label, of_piece;
  double total = 0;
  int arrangement_faces = 0;  // bounded ones, labelled or not
};

Areas areas_of(const Arrangement& arr, const Pieces& pieces, std::size_t labels) {
  Areas areas{std::vector<double>(labels, 0.0), std::vector<double>(pieces.label.size(), 0.0)};
  for (auto f = arr.faces_begin(); f != arr.faces_end(); ++f) {
    if (f->is_unbounded()) continue;
    ++areas.arrangement_faces;
    double a = 0;
    for (auto ccb = f->outer_ccbs_begin(); ccb != f->outer_ccbs_end(); ++ccb) a += ccb_area(*ccb);
    // Holes run clockwise: their areas are negative.
    for (auto ccb = f->inner_ccbs_begin(); ccb != f->inner_ccbs_end(); ++ccb) a += ccb_area(*ccb);
    if (f->data() < 0) continue;  // an unlabelled face leaves a hole in the tiling
    areas.total += a;
    areas.of_label[static_cast<std::size_t>(f->data())] += a;
    areas.of_piece[static_cast<std::size_t>(pieces.of.at(f))] += a;
  }
  return areas;
}

// The face graph's nodes: validity is decided on pieces of paper, and the back plane and the floor
// are their largest pieces (nodes 0 and 1); every other piece is a node of its own.
struct PieceNodes {
  std::vector<std::int32_t> of_piece;
  std::int32_t count = 2;
};

PieceNodes piece_nodes(const Pieces& pieces, const std::vector<double>& piece_area) {
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
  return {std::move(node), nodes};
}

// What the plan's edges are: each inner edge's line kind, the folds between nodes, and which
// raster faces have a fold on their top or bottom side.
struct EdgeReading {
  std::vector<std::pair<Arrangement::Halfedge_const_handle, LineKind>> edges;  // upper face first
  std::vector<Fold> folds;
  std::vector<bool> fold_on_top, fold_on_bottom;
};

// Edges vanish inside a face, are folds on their exact line and cuts elsewhere.
EdgeReading read_edges(const Arrangement& arr, const std::vector<RasterFace>& faces, const Pieces& pieces,
                       const std::vector<std::int32_t>& node) {
  EdgeReading reading{{}, {}, std::vector<bool>(faces.size(), false), std::vector<bool>(faces.size(), false)};
  std::map<FT, std::int32_t> fold_line_ids;
  auto node_of = [&](Arrangement::Face_const_handle f) { return node[static_cast<std::size_t>(pieces.of.at(f))]; };
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    Arrangement::Halfedge_const_handle he = e;
    if (he->direction() != CGAL::ARR_LEFT_TO_RIGHT) he = he->twin();  // he->face() is above or left
    if (he->face()->is_unbounded() || he->twin()->face()->is_unbounded()) continue;
    const std::int32_t upper = he->face()->data(), lower = he->twin()->face()->data();
    if (upper == lower || upper < 0 || lower < 0) continue;
    const Point &p = he->source()->point(), &q = he->target()->point();
    const RasterFace &fu = faces[static_cast<std::size_t>(upper)], &fl = faces[static_cast<std::size_t>(lower)];
    LineKind kind = LineKind::Cut;
    if (CGAL::compare_y(p, q) == CGAL::EQUAL && fu.orientation != fl.orientation && !fu.hole && !fl.hole &&
        !negligible(he)) {
      if (p.y() == fold_line_Y(fu.orientation, FT(fu.depth_mm), FT(fl.depth_mm))) {
        // Going up the plan: V then H is a mountain fold, H then V a valley fold.
        kind = fu.orientation == Orientation::H ? LineKind::Mountain : LineKind::Valley;
        const auto [it, fresh] = fold_line_ids.try_emplace(p.y(), static_cast<std::int32_t>(fold_line_ids.size()));
        reading.folds.push_back({node_of(he->face()), node_of(he->twin()->face()), it->second});
        reading.fold_on_top[static_cast<std::size_t>(lower)] = true;
        reading.fold_on_bottom[static_cast<std::size_t>(upper)] = true;
      }
    }
    if (fu.hole || fl.hole) kind = LineKind::CutOut;
    reading.edges.push_back({he, kind});
  }
  // Folds under kFoldLineTolerance_mm apart are one line, as validate reads them: the face between
  // them swings about it. (Depths reached along different paths can differ in a double's last bits.)
  std::vector<std::int32_t> line_of(fold_line_ids.size());
  std::int32_t line = -1;
  const FT* previous = nullptr;
  for (const auto& [Y, id] : fold_line_ids) {
    if (!previous || Y - *previous > FT(kFoldLineTolerance_mm)) ++line;
    line_of[static_cast<std::size_t>(id)] = line;
    previous = &Y;
  }
  for (Fold& fold : reading.folds) fold.line = line_of[static_cast<std::size_t>(fold.line)];
  return reading;
}

// Per piece: whether it borders only holes (and pieces of its own label).
std::vector<std::uint8_t> among_holes(const Arrangement& arr, const Pieces& pieces,
                                      const std::vector<RasterFace>& faces) {
  std::vector<std::uint8_t> among(pieces.label.size(), 1);
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e)
    for (const auto& [side, other] : {std::pair{e->face(), e->twin()->face()}, {e->twin()->face(), e->face()}}) {
      if (side->is_unbounded() || side->data() < 0 || side->data() == other->data()) continue;
      if (other->is_unbounded() || other->data() < 0 || !faces[static_cast<std::size_t>(other->data())].hole)
        among[static_cast<std::size_t>(pieces.of.at(side))] = 0;
    }
  return among;
}

}  // namespace

void ExactPlan::build(State& state, const RasterMaps& maps, const RasterPlan& sliced, const Sheet& sheet,
                      const PlanOptions& options) {
  state.grid = maps.grid;
  // §4.5 in two steps: the raster boundaries move to the pixel row nearest their fold line where
  // they can, then only those within half a pixel snap onto it. Snapping farther could carry a fold
  // across a neighbouring boundary, which forced the whole chain back to its pixel contour and lost
  // the fold.
  RasterPlan aligned = aligned_faces(sliced, maps.grid, options);
  const std::vector<RasterFace>& faces = aligned.faces;
  const Lattice lattice(maps, sheet);
  state.labels = labels_inside_sheet(std::move(aligned.face));  // the face map is not read again
  const std::vector<Chain> chains = trace_chains(state.labels);
  const double simplify_mm = std::min(options.simplify_mm, 1 / maps.grid.px_per_mm);

  Plan& plan = state.plan;
  plan.sheet = sheet;
  Built& built = state.built;
  const std::vector<Fallback> fallback =
      arrangement_without_crossings({chains, faces, lattice, sheet, simplify_mm, aligned_fold_tolerance_mm(maps.grid)},
                                    built, plan.unresolved_crossings);
  plan.raw_chains = static_cast<int>(std::ranges::count(fallback, Fallback::Unsimplified));
  plan.unsnapped_chains = static_cast<int>(std::ranges::count(fallback, Fallback::PixelContour));
  plan.simplified = plan.raw_chains + plan.unsnapped_chains == 0;
  plan.trimmed_to_card = keep_faces_on_the_card(faces, built);
  const Arrangement& arr = built.arrangement;
  plan.arrangement_valid = arr.is_valid();
  plan.label_conflicts = built.conflicts;
  plan.folds_snapped = built.folds_snapped;
  plan.off_model_edges_mm = built.off_model_edges_mm;

  state.pieces = pieces_of(arr);
  const Pieces& pieces = state.pieces;
  const std::size_t n = faces.size();
  Areas areas = areas_of(arr, pieces, n);
  plan.arrangement_faces = areas.arrangement_faces;
  // The arrangement is a subdivision by construction; this guards the labelling and the outline.
  const double sheet_area = sheet.width_mm * sheet.height_mm;
  plan.faces_tile_sheet = std::abs(areas.total - sheet_area) <= 1e-9 * sheet_area;

  const auto [node, nodes] = piece_nodes(pieces, areas.of_piece);
  FaceGraph graph;
  graph.faces = nodes;
  graph.holes.assign(static_cast<std::size_t>(graph.faces), 0);
  for (std::size_t p = 0; p < pieces.label.size(); ++p)
    graph.holes[static_cast<std::size_t>(node[p])] = faces[static_cast<std::size_t>(pieces.label[p])].hole;
  EdgeReading reading = read_edges(arr, faces, pieces, node);
  graph.folds = std::move(reading.folds);
  state.edges = std::move(reading.edges);
  const std::vector<std::uint8_t> bordering_holes = among_holes(arr, pieces, faces);
  const PieceVerdict verdict =
      face_validity(validity_of(graph), {pieces, node, areas.of_piece, bordering_holes}, n, aligned.min_strip_mm);
  plan.validity = verdict.validity;
  plan.loose_card_pieces = verdict.loose_card_pieces;
  plan.crumbs_cut_out = static_cast<int>(std::ranges::count(verdict.cut_out, 1));
  plan.pieces = static_cast<int>(pieces.label.size());
  plan.faces.resize(n);
  for (std::size_t f = 0; f < n; ++f) {
    PlanFace& face = plan.faces[f];
    face.orientation = faces[f].orientation;
    face.depth_mm = faces[f].depth_mm;
    face.area_mm2 = areas.of_label[f];
    face.fold_on_top = reading.fold_on_top[f];
    face.fold_on_bottom = reading.fold_on_bottom[f];
    face.support = faces[f].support;
    face.status = plan.validity.status[f];
  }
  state.area = std::move(areas.of_label);
  state.cut_out = verdict.cut_out;
  state.faces = std::move(aligned.faces);
}

ExactPlan::~ExactPlan() {
  const auto lock = exact_run_lock();  // its exact numbers are freed
  state_.reset();
}
ExactPlan::ExactPlan(ExactPlan&&) noexcept = default;
ExactPlan& ExactPlan::operator=(ExactPlan&& other) noexcept {
  const auto lock = exact_run_lock();
  state_ = std::move(other.state_);
  return *this;
}

const Plan& ExactPlan::verdict() const { return state_->plan; }
const Grid<std::int32_t>& ExactPlan::face_map() const { return state_->labels; }
const std::vector<RasterFace>& ExactPlan::faces() const { return state_->faces; }

Plan build_plan(const RasterMaps& maps, const RasterPlan& raster_plan, const Sheet& sheet, const PlanOptions& options) {
  const auto lock = exact_run_lock();
  return ExactPlan(maps, raster_plan, sheet, options).full();
}

}  // namespace origamic
