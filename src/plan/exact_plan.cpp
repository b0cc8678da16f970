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

void add_cut(const Chain& chain, std::size_t from, std::size_t to, const Lattice& lattice, const Junctions& junctions,
             double simplify_mm, Curves& curves, std::array<std::optional<PieceEnd>, 2> ends = {}) {
  if (to <= from) return;
  const Chain piece{chain.left, chain.right, {chain.corners.begin() + from, chain.corners.begin() + to + 1}};
  if (!ends[0]) ends[0] = junctions.moved(piece.corners.front());
  if (!ends[1]) ends[1] = junctions.moved(piece.corners.back());
  const auto near = [](const std::optional<PieceEnd>& end) { return end ? std::optional(end->near) : std::nullopt; };
  const chains::DrawnChain drawn =
      simplified(piece, lattice, lattice.breaks, simplify_mm, std::min(simplify_mm, kSimplifyOnBreaks_mm),
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

// §4.5: where a boundary between V(d) and H(h) runs within `tolerance` of the fold line Y = h - d,
// monotonically along X, that run becomes one exact segment on the line: the faces are extended or
// trimmed to meet on it. Short vertical cuts join its ends to the corners the run had (they name no
// face; the arrangement finds their sides). The rest of the boundary is a cut.
void add_chain(const Chain& chain, Fallback fallback, const std::vector<RasterFace>& faces, const Lattice& lattice,
               const Junctions& junctions, double simplify_mm, double tolerance, Curves& curves) {
  const std::size_t last = chain.corners.size() - 1;
  if (fallback != Fallback::None) simplify_mm = 0;
  const RasterFace &a = faces[static_cast<std::size_t>(chain.left)], &b = faces[static_cast<std::size_t>(chain.right)];
  if (fallback == Fallback::PixelContour || a.orientation == b.orientation || a.hole || b.hole)
    return add_cut(chain, 0, last, lattice, junctions, simplify_mm, curves);
  const double fold_Y = fold_line_Y(a.orientation, a.depth_mm, b.depth_mm);
  if (!(std::abs(fold_Y) < lattice.half_mm)) return add_cut(chain, 0, last, lattice, junctions, simplify_mm, curves);
  const FT exact_Y = fold_line_Y(a.orientation, FT(a.depth_mm), FT(b.depth_mm));
  auto near = [&](std::size_t i) { return std::abs(lattice.Y(chain.corners[i].v) - fold_Y) <= tolerance; };
  std::size_t cut_from = 0, i = 0;
  std::optional<PieceEnd> cut_from_end;  // where the cut from cut_from starts, if not at its corner
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
    // Where the cut before the run (after it) comes in on the model's edge, the fold ends where
    // that edge meets its line, and the cut runs to it: no connector.
    const auto on_edge = [&](std::size_t from, std::size_t to, bool front) -> std::optional<PieceEnd> {
      if (fallback != Fallback::None || to <= from) return std::nullopt;
      const Chain piece{chain.left, chain.right, {chain.corners.begin() + from, chain.corners.begin() + to + 1}};
      const std::optional<double> X = chains::leg_meets_line(piece, front, fold_Y, lattice, lattice.breaks);
      if (!X) return std::nullopt;
      // A move under a micrometre is the corner's own X, in the rays' rounding.
      const LatticePoint corner = chain.corners[front ? from : to];
      if (std::abs(*X - lattice.X(corner.u)) < chains::kLeastMove_mm)
        return PieceEnd{Point(lattice.exact(corner.u, corner.v).x(), exact_Y), {lattice.X(corner.u), fold_Y}};
      return PieceEnd{Point(FT(*X), exact_Y), {*X, fold_Y}};
    };
    std::optional<PieceEnd> start_on_edge = on_edge(cut_from, i, false);
    std::size_t next_cut_to = j + 1;  // the cut after the run ends at the next run or the chain's end
    while (next_cut_to <= last && !near(next_cut_to)) ++next_cut_to;
    std::optional<PieceEnd> end_on_edge = on_edge(j, std::min(next_cut_to, last), true);
    const LatticePoint start = chain.corners[i], end = chain.corners[j];
    const Point s = junctions(start, lattice), e = junctions(end, lattice);
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
    add_cut(chain, cut_from, i, lattice, junctions, simplify_mm, curves, {cut_from_end, start_on_edge});
    const Point s_on = start_on_edge ? start_on_edge->exact : Point(s.x(), exact_Y);
    const Point e_on = end_on_edge ? end_on_edge->exact : Point(e.x(), exact_Y);
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
  add_cut(chain, cut_from, last, lattice, junctions, simplify_mm, curves, {cut_from_end, std::nullopt});
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

// What each chain's ends allow its junctions: a chain drawn on its raster contour (fallen back, or
// nothing simplified) keeps them on the lattice; an end that may snap onto its fold (add_chain)
// moves only along the fold.
std::vector<chains::ChainEnds> chain_ends(const std::vector<Chain>& chains, const std::vector<Fallback>& fallback,
                                          const std::vector<RasterFace>& faces, const Lattice& lattice,
                                          double simplify_mm, double fold_tolerance) {
  std::vector<chains::ChainEnds> ends(chains.size());
  for (std::size_t i = 0; i < chains.size(); ++i) {
    const Chain& chain = chains[i];
    const RasterFace &a = faces[static_cast<std::size_t>(chain.left)],
                     &b = faces[static_cast<std::size_t>(chain.right)];
    if (fallback[i] != Fallback::None || simplify_mm <= 0) {
      ends[i].pinned = true;
    } else if (a.orientation != b.orientation && !a.hole && !b.hole) {
      const double fold_Y = fold_line_Y(a.orientation, a.depth_mm, b.depth_mm);
      if (!(std::abs(fold_Y) < lattice.half_mm)) continue;
      const LatticePoint corners[2] = {chain.corners.front(), chain.corners.back()};
      for (const int end : {0, 1})
        if (std::abs(lattice.Y(corners[end].v) - fold_Y) <= fold_tolerance) ends[i].fold_Y[end] = fold_Y;
    }
  }
  return ends;
}

void build_arrangement(const std::vector<Chain>& chains, const std::vector<Fallback>& fallback,
                       const std::vector<RasterFace>& faces, const Lattice& lattice, const Sheet& sheet,
                       double simplify_mm, double fold_tolerance, Built& built) {
  Curves curves;
  const chains::JunctionMoves moves = junctions_on_breaks(
      chains, lattice, lattice.breaks, chain_ends(chains, fallback, faces, lattice, simplify_mm, fold_tolerance));
  const Junctions junctions(moves.moved, lattice, chains, faces);
  for (std::size_t i = 0; i < chains.size(); ++i) {
    if (moves.collapsed[i]) continue;
    curves.chain = static_cast<std::int32_t>(i);
    add_chain(chains[i], fallback[i], faces, lattice, junctions, simplify_mm, fold_tolerance, curves);
  }
  curves.chain = kNoLabel;
  const FT W(sheet.width_mm), H(sheet.half_height_mm());
  const Point corners[4] = {{0, -H}, {W, -H}, {W, H}, {0, H}};
  for (int i = 0; i < 4; ++i) curves.add(corners[i], corners[(i + 1) % 4], kNoLabel, kNoLabel);
  built.folds_snapped = curves.folds_snapped;
  built.off_model_edges_mm = curves.off_model_edges_mm;
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
  std::vector<std::pair<std::int32_t, double>> votes;  // a face's few labels: a map per face cost more
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
    if (best == kNoLabel || best_votes * 2 <= total) ++built.conflicts;
    f->set_data(best);
  }
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
void ExactPlan::build(State& state, const RasterMaps& maps, const RasterPlan& sliced, const Sheet& sheet,
                      const PlanOptions& options) {
  state.grid = maps.grid;
  // §4.5 in two steps: the raster boundaries move to the pixel row nearest their fold line where
  // they can (align_folds_to_lines; a no-op on plans already aligned), then only those within half a
  // pixel snap onto it. Snapping farther could carry a fold across a neighbouring boundary, which
  // forced the whole chain back to its pixel contour and lost the fold.
  RasterPlan slices;  // the fields a plan is built of (a field it comes to read must be copied here)
  slices.min_strip_mm = sliced.min_strip_mm;
  slices.block_px = sliced.block_px;
  slices.face = sliced.face;
  slices.faces = sliced.faces;
  align_folds_to_lines(slices, maps.grid, fold_snap_tolerance_mm(options, slices, maps.grid));
  const Lattice lattice(maps, sheet);
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
  plan.trimmed_to_card = keep_faces_on_the_card(slices.faces, built);
  const Arrangement& arr = built.arrangement;
  plan.arrangement_valid = arr.is_valid();
  plan.label_conflicts = built.conflicts;
  plan.folds_snapped = built.folds_snapped;
  plan.off_model_edges_mm = built.off_model_edges_mm;

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
      if (p.y() == fold_line_Y(fu.orientation, FT(fu.depth_mm), FT(fl.depth_mm))) {
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
      face_validity(validity_of(graph), pieces, node, piece_area, among_holes, n, slices.min_strip_mm);
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

Plan build_plan(const RasterMaps& maps, const RasterPlan& slices, const Sheet& sheet, const PlanOptions& options) {
  const auto lock = exact_run_lock();
  return ExactPlan(maps, slices, sheet, options).full();
}

}  // namespace origamic
