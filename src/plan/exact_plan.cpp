// SPDX-License-Identifier: GPL-3.0-or-later
// The exact plan built: the raster plan's boundaries in an exact arrangement (its folds snapped onto
// their lines; exact_plan_chains.cpp), and the verdict read off its pieces of paper. CGAL is heavy
// to compile: it stays in this file and the four that share exact_plan_state.hpp.

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
#include "exact_plan_chains.hpp"
#include "exact_plan_state.hpp"
#include "exact_runs.hpp"
#include "level_contours.hpp"
#include "origamic/plan.hpp"
#include "raster_plan_edits.hpp"

namespace origamic {
namespace {

using chains::Chain;
using chains::labels_inside_sheet;
using chains::trace_chains;
using exact::approx_x;
using exact::approx_y;
using exact::Arrangement;
using exact::arrangement_without_crossings;
using exact::Built;
using exact::face_validity;
using exact::Fallback;
using exact::FT;
using exact::Kernel;
using exact::Lattice;
using exact::negligible;
using exact::Pieces;
using exact::pieces_of;
using exact::PieceVerdict;
using exact::Point;
using exact::Sides;
// Each inserted segment carries the index of its side labels.
using exact::Traits;

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

ExactPlan::ExactPlan(const RasterMaps& maps, const RasterPlan& raster_plan, const Sheet& sheet,
                     const PlanOptions& options, const ChainFallbacks& known) {
  const auto lock = exact_run_lock();  // held until the exact numbers are made, or freed on an error
  state_ = std::make_unique<State>();
  try {
    build(*state_, maps, raster_plan, sheet, options, known);
  } catch (...) {
    state_.reset();
    throw;
  }
}

namespace {

// The faces the plan is built from, their V/H boundaries moved to the pixel row nearest their fold
// line where they can (§4.5's first step; a no-op on a plan already aligned).
RasterPlan aligned_faces(const RasterPlan& raster_plan, const PixelGrid& grid, const PlanOptions& options) {
  RasterPlan copy;  // the fields a plan is built of (a field it comes to read must be copied here)
  copy.min_strip_mm = raster_plan.min_strip_mm;
  copy.block_px = raster_plan.block_px;
  copy.face = raster_plan.face;
  copy.faces = raster_plan.faces;
  const double tolerance = fold_snap_tolerance_mm(options, copy, grid);
  return align_folds_to_lines(std::move(copy), grid, tolerance);
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

// Per piece: the length of its boundary, each edge between it and another piece, a hole or the
// sheet's outside counted once.
std::vector<double> piece_perimeters(const Arrangement& arr, const Pieces& pieces) {
  std::vector<double> perimeter(pieces.label.size(), 0.0);
  const auto piece = [&](Arrangement::Face_const_handle f) -> std::int32_t {
    const auto it = pieces.of.find(f);
    return it == pieces.of.end() ? -1 : it->second;
  };
  for (auto e = arr.edges_begin(); e != arr.edges_end(); ++e) {
    const std::int32_t a = piece(e->face()), b = piece(e->twin()->face());
    if (a == b) continue;
    const double length = exact::length_of(e);
    if (a >= 0) perimeter[static_cast<std::size_t>(a)] += length;
    if (b >= 0) perimeter[static_cast<std::size_t>(b)] += length;
  }
  return perimeter;
}

// The plan's faces: each raster face's plane, exact area, folded sides and verdict.
std::vector<PlanFace> plan_faces(const std::vector<RasterFace>& faces, const std::vector<double>& area,
                                 const EdgeReading& reading, const Validity& validity) {
  std::vector<PlanFace> result(faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    PlanFace& face = result[f];
    face.orientation = faces[f].orientation;
    face.depth_mm = faces[f].depth_mm;
    face.area_mm2 = area[f];
    face.fold_on_top = reading.fold_on_top[f];
    face.fold_on_bottom = reading.fold_on_bottom[f];
    face.support = faces[f].support;
    face.status = validity.status[f];
  }
  return result;
}

}  // namespace

// Built in place: the handles read off the arrangement stay valid.
void ExactPlan::build(State& state, const RasterMaps& maps, const RasterPlan& raster_plan, const Sheet& sheet,
                      const PlanOptions& options, const ChainFallbacks& known) {
  state.grid = maps.grid;
  // §4.5 in two steps: the raster boundaries move to the pixel row nearest their fold line where
  // they can, then only those within half a pixel snap onto it. Snapping farther could carry a fold
  // across a neighbouring boundary, which forced the whole chain back to its pixel contour and lost
  // the fold.
  RasterPlan aligned = aligned_faces(raster_plan, maps.grid, options);
  const std::vector<RasterFace>& faces = aligned.faces;
  const BreaksAndLevels lines = breaks_and_levels(maps, aligned.face, faces);
  const Lattice lattice(maps, sheet, {lines.right, lines.below});
  state.labels = labels_inside_sheet(std::move(aligned.face));  // the face map is not read again
  const std::vector<Chain> chains = trace_chains(state.labels);
  const double simplify_mm = std::min(options.simplify_mm, 1 / maps.grid.px_per_mm);

  Plan& plan = state.plan;
  plan.sheet = sheet;
  Built& built = state.built;
  exact::ArrangementFallbacks fell = arrangement_without_crossings(
      {chains, faces, lattice, sheet, simplify_mm, aligned_fold_tolerance_mm(maps.grid)}, known, built);
  const std::vector<Fallback>& fallback = fell.fallback;
  plan.unresolved_crossings = fell.unresolved;
  plan.fallbacks = std::move(fell.passed_on);
  plan.raw_chains = static_cast<int>(std::ranges::count(fallback, Fallback::Unsimplified));
  plan.unsnapped_chains = static_cast<int>(std::ranges::count(fallback, Fallback::PixelContour));
  plan.arrangement_builds = built.builds;
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
  const std::vector<double> perimeter = piece_perimeters(arr, pieces);
  Validity by_node = validity_of(graph);
  // The faces are judged again without the folds of the card's pieces that fall out: a face folded
  // to one, and held through it, would stand by paper that is not there.
  std::vector<bool> falls_out(static_cast<std::size_t>(nodes), false);
  bool any_falls_out = false;
  for (std::size_t p = 0; p < pieces.label.size(); ++p) {
    const auto k = static_cast<std::size_t>(node[p]);
    if (pieces.label[p] < 2 && k >= 2 &&
        exact::card_piece_falls_out(by_node.status[k], areas.of_piece[p], perimeter[p], aligned.min_strip_mm))
      falls_out[k] = any_falls_out = true;
  }
  if (any_falls_out) {
    std::erase_if(graph.folds, [&](const Fold& fold) {
      return falls_out[static_cast<std::size_t>(fold.a)] || falls_out[static_cast<std::size_t>(fold.b)];
    });
    by_node = validity_of(graph);
  }
  const PieceVerdict verdict =
      face_validity(by_node, {pieces, node, areas.of_piece, perimeter, bordering_holes}, n, aligned.min_strip_mm);
  plan.validity = verdict.validity;
  plan.loose_card_pieces = verdict.loose_card_pieces;
  plan.crumbs_cut_out = static_cast<int>(std::ranges::count(verdict.cut_out, 1));
  plan.pieces = static_cast<int>(pieces.label.size());
  plan.faces = plan_faces(faces, areas.of_label, reading, plan.validity);
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

Plan build_plan(const RasterMaps& maps, const RasterPlan& raster_plan, const Sheet& sheet, const PlanOptions& options,
                const ChainFallbacks& known) {
  const auto lock = exact_run_lock();
  return ExactPlan(maps, raster_plan, sheet, options, known).full();
}

}  // namespace origamic
