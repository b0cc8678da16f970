// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: what the translation units of the exact plan share. exact_plan_chains.cpp builds the
// arrangement from the traced chains; exact_plan.cpp decides the verdict on the pieces of paper
// exact_plan_pieces.cpp finds in it; exact_plan_drawing.cpp draws the plan in full, and
// exact_plan_rays.cpp shoots rays on it.
// Include after defining CGAL_HAS_NO_THREADS (see exact_kernel.hpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <map>
#include <mutex>
#include <shared_mutex>
#include <type_traits>
#include <utility>
#include <vector>

#include "exact_kernel.hpp"
#include "exact_plan.hpp"
#include "origamic/plan.hpp"
#include "origamic/validity.hpp"

namespace origamic {
namespace exact {

// Threads read copies of the lines' rationals at once (ExactPlan::State): gmpxx copies are deep,
// where CGAL's own Gmpq would share a reference count that CGAL_HAS_NO_THREADS leaves unguarded.
static_assert(std::is_same_v<Rational, mpq_class>, "exact rationals must be gmpxx's mpq_class");

constexpr std::int32_t kNoLabel = -1;

/// The faces on either side of a segment inserted from its lexicographically smaller end.
struct Sides {
  std::int32_t left = kNoLabel;
  std::int32_t right = kNoLabel;
  std::int32_t chain = kNoLabel;  // the raster boundary it comes from; none for the sheet outline
  bool fold = false;              // a fold snapped onto its line
};

/// The arrangement of a plan's boundaries, and what its building found.
struct Built {
  Arrangement arrangement;
  std::vector<Sides> sides;
  std::vector<bool> crossed;  // per chain: one of its segments runs through a vertex it does not end at
  std::vector<bool> disputed;  // per chain: it bounds a face no label has a majority of
  int conflicts = 0;
  int folds_snapped = 0;
  double off_model_edges_mm = 0;  // the farthest a cut passes from the model's edge it follows
  int builds = 0;                 // of the arrangement: once, and once more per step chains fell back
};

/// The pieces of paper: sets of arrangement faces of one label joined across edges with that label on
/// both sides (those edges are no lines of the plan).
struct Pieces {
  std::map<Arrangement::Face_const_handle, std::int32_t> of;  // bounded labelled face -> piece
  std::vector<std::int32_t> label;                            // per piece
};

/// Every bounded labelled face's piece of paper (Pieces).
Pieces pieces_of(const Arrangement& arr);

/// An edge under kFoldLineTolerance_mm joins nothing: paper does not hang by it, and the plan's
/// files may not even keep it apart from its end points.
bool negligible(Arrangement::Halfedge_const_handle he);

/// Whether a piece of the back plane or the floor (not the card's halves themselves) falls out of the
/// card: a crumb (under W x W / 8) that hangs by one fold line, a flap too small to fold (what a face
/// trimmed to the card leaves where the card's own piece is not beside it), or a sliver (twice its
/// area over its perimeter, a strip's width, under W / 4), however long, that floats or hangs so.
/// Card, not a face of the model: its hole takes from the likeness only the model pixels the card
/// showed on it (parts of faces beyond the card become back plane or floor), a sliver's worth.
bool card_piece_falls_out(FaceStatus status, double area_mm2, double perimeter_mm, double min_strip_mm);

/// The verdict per raster face from the verdict per piece: a face stands when every piece of it does.
/// A floating crumb (a piece under W x W / 8, cut off where a snapped fold met a slanted cut) falls
/// out when the card is cut and is no part of the likeness: it is cut out (a hole) and does not count.
/// So does a floating piece with holes all round it: it falls out with them, a crumb of the back
/// plane or the floor that falls out (card_piece_falls_out): `by_node` must judge the faces without
/// the folds of such pieces.
/// Pieces of the back plane and the floor that came loose count as faces of their own.
struct PieceVerdict {
  Validity validity;                  // per raster face
  int loose_card_pieces = 0;          // pieces of the back plane or the floor no fold holds
  std::vector<std::uint8_t> cut_out;  // per piece: a crumb or a sliver, cut out
};
/// What face_validity reads of each piece besides its label: its node in the face graph, its area,
/// its perimeter, and whether it borders only holes.
struct PieceFacts {
  const Pieces& pieces;
  const std::vector<std::int32_t>& node;
  const std::vector<double>& area;
  const std::vector<double>& perimeter;
  const std::vector<std::uint8_t>& among_holes;
};
PieceVerdict face_validity(const Validity& by_node, const PieceFacts& piece, std::size_t faces, double min_strip_mm);

/// An edge's length from its vertices' doubles, for the label vote and the reported line lengths.
inline double length_of(Arrangement::Halfedge_const_handle he) {
  const Point &p = he->source()->point(), &q = he->target()->point();
  return std::hypot(approx_x(p) - approx_x(q), approx_y(p) - approx_y(q));
}

}  // namespace exact

// What a verdict leaves for drawing the plan in full: the arrangement and what was read off it.
struct ExactPlan::State {
  PixelGrid grid;
  std::vector<RasterFace> faces;
  Grid<std::int32_t> labels;
  exact::Built built;
  exact::Pieces pieces;
  std::vector<double> area;                                                           // per raster face
  std::vector<std::pair<exact::Arrangement::Halfedge_const_handle, LineKind>> edges;  // inner edges, upper face first
  std::vector<std::uint8_t> cut_out;                                                  // per piece: cut out
  Plan plan;                                                                          // the verdict

  // Vertical ray shooting (faces_reached). The exact numbers are read under the lock held alone,
  // while a line is made; lines made are looked up under it shared. They keep their crossings as
  // plain rationals, which threads may read at once (MPFR, which to_interval calls on them, is
  // built thread-safe in Debian).
  struct Crossing {
    exact::Rational Y;
    double Y_near;       // nearest double: a smaller one means a smaller Y, an equal one decides nothing
    std::int32_t above;  // the label between this crossing and the next one up
  };
  struct EdgeSpan {
    double x_lo, x_hi;                             // the edge's x-extent, widened by its doubles' rounding
    exact::Arrangement::Halfedge_const_handle he;  // directed left to right: its face lies above it
  };
  std::shared_mutex mutex;
  // The edges by the pixel columns their x-extents meet, so that a line looks at its column's only.
  std::vector<std::vector<EdgeSpan>> spans_by_column;
  std::map<double, std::vector<Crossing>> lines;  // by x: a map's elements stay where they are
  const std::vector<Crossing>& line_at(double x);
};

}  // namespace origamic
