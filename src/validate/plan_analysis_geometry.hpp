// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the exact geometry shared by the plan analysis's translation units (plan_analysis.cpp
// runs the analysis, tip_repair.cpp parts tips off and runs it again, plan_analysis_geometry.cpp
// and plan_analysis_chords.cpp hold this): the plan's lines collected onto the sheet, faces as
// rings, chords narrower than W, the numbers and points of the messages, and the analysis's state
// (Analyzer). Define CGAL_HAS_NO_THREADS before including it (see exact_kernel.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "exact_kernel.hpp"
#include "origamic/plan_analysis.hpp"

namespace origamic::analysis {

using Ring = std::vector<exact::Point>;

/// A number for a message: plan mm to 1e-6, small amounts with three significant digits.
std::string num(double value);

/// A point for a message: "(X, Y)".
std::string point_text(PlanPoint p);

/// The doubles nearest an exact point.
PlanPoint plan_point(const exact::Point& p);

// ---------------------------------------------------------------------------------------------
// The arrangement of every line, clipped to the sheet.

struct Input {
  std::vector<exact::Traits::Curve_2> curves;
  std::vector<LineKind> kind;  // per data index
  exact::FT min_X, min_Y, max_X, max_Y;  // the sheet, in plan coordinates
  exact::FT main_fold_Y = 0;             // where the drawing has the main fold: subtracted from every Y
  std::vector<PlanProblem> warnings;
};

/// The plan's lines in exact plan mm as curves for the arrangement: the sheet's outline (the
/// bounding box of the OUTLINE lines if any, else of every line) and every line clipped to it, with
/// an OutsideSheet warning per line that leaves it; horizontal folds drawn in pieces joined.
/// A sheet that straddles Y = 0 has its main fold there; any other is drawn from its lower-left
/// corner (or elsewhere), and its main fold is halfway up it: every Y is moved by that, exactly.
/// \throws InputError if a coordinate is not finite, there is no cut or fold line, or the sheet
///         has no area.
Input collect(const std::vector<PlanPolyline>& lines, const AnalysisOptions& options);

// ---------------------------------------------------------------------------------------------
// Faces as rings.

/// The rings bounding a bounded face, without its slits and loose ends: the outer rings
/// (counter-clockwise) first, the largest first, then the holes (clockwise).
std::vector<Ring> rings_of(exact::Arrangement::Face_const_handle f);

/// The signed area of a ring in mm², in doubles: positive counter-clockwise.
double ring_area(const Ring& ring);

/// Where the segment from (u0, v0) to (u1, v1) crosses the line at u (\pre u0 != u1): its v there,
/// on exact numbers or on intervals (where an interval comparison is uncertain, it throws). A
/// segment square to the line (most are) crosses it at its own v, taken as it is: no number built.
template <typename Number>
Number crossing_v(const Number& u0, const Number& v0, const Number& u1, const Number& v1, const Number& u) {
  return v0 == v1 ? v0 : v0 + (v1 - v0) * (u - u0) / (u1 - u0);
}

/// A point strictly inside the face the rings bound. \pre rings bound a face of positive area.
exact::Point inside_point(const std::vector<Ring>& rings);

// ---------------------------------------------------------------------------------------------
// Strips narrower than W: chords of a face along one axis through each of its vertices.

struct Chord {
  exact::FT at, lo, hi;  // the chord runs from lo to hi along the measured axis, at `at` on the other
};

/// Where a chord of a face lies: the vertex on its line and the face's edges its ends lie on, each
/// by its ends (u0 first); the exact chord is made from them (chord_of). It points into the rings
/// searched, and holds while they do, unchanged.
struct ChordPlace {
  const exact::Point* vertex;
  std::array<const exact::Point*, 2> lo, hi;
  double length;  // about: the order in which the tip repair tries a face's chords
};

/// The exact chord at `place`, along Y or along X.
Chord chord_of(const ChordPlace& place, bool along_Y);

/// A face's shortest chords through one of its vertices, along Y ([0]) and along X ([1]), longer
/// than zero and shorter than W, if any, and how many such chords it has each way. A chord is the
/// face's stretch on the line just before it or just after it, each side on its own (the strip
/// under a notch, whose corners are its only vertices, is one).
struct FaceChords {
  std::array<std::optional<Chord>, 2> narrowest;
  std::array<int, 2> narrow = {0, 0};
  std::array<std::vector<ChordPlace>, 2> others;  // the other chords narrower than W, about narrowest first
};

/// The chords of each face the rings bound (rings[f]), none sought where skip[f] is set.
std::vector<FaceChords> narrowest_chords(const std::vector<std::vector<Ring>>& rings,
                                         const std::vector<std::uint8_t>& skip, const exact::FT& W);

// ---------------------------------------------------------------------------------------------
// The analysis (plan_analysis.cpp), which the tip repair (tip_repair.cpp) runs round after round.

using Face = exact::Arrangement::Face_const_handle;
using Halfedge = exact::Arrangement::Halfedge_const_handle;

// A face's plane, once the folds from the back plane and the floor reach it.
struct Place {
  bool placed = false;
  Orientation orientation = Orientation::V;
  exact::FT depth = 0;
};

/// "V(d)" or "H(h)", "unplaced" for a face no fold reaches.
std::string face_text(const Place& place);

// A fold edge between two regions (lower and upper), on its line Y, from X_lo to X_hi.
struct FoldEdge {
  std::int32_t lower, upper;
  exact::FT Y, X_lo, X_hi;
  LineKind kind;
};

// The arrangement of a plan's lines and its analysis, step by step (run).
struct Analyzer {
  const AnalysisOptions& options;
  exact::FT tolerance, W;
  exact::Arrangement arr;  // each segment's data: its index in `kind`
  std::vector<LineKind> kind;
  std::vector<Face> faces;
  std::vector<std::vector<Ring>> rings;
  std::vector<Place> place;
  std::vector<std::uint8_t> cut_out;  // per region: every side on the CUTOUT layer
  std::vector<FoldEdge> folds;
  std::vector<std::vector<std::size_t>> folds_of;
  std::vector<std::array<std::optional<Chord>, 2>> narrowest;  // per region, along Y and along X (check_strips)
  std::vector<std::array<std::vector<ChordPlace>, 2>> other_chords;  // the others narrower than W (check_strips)
  PlanAnalysis result;

  explicit Analyzer(const AnalysisOptions& o) : options(o), tolerance(o.tolerance_mm), W(o.min_strip_mm) {}

  void add(PlanProblem problem) { result.problems.push_back(std::move(problem)); }

  void run(const std::vector<PlanPolyline>& lines);

  void make_regions(const Input& in);

  // Each edge inside the sheet: a cut, a fold between two faces, or a problem.
  void classify_edges();

  // Edges with one face on both sides, grouped into connected pieces; each piece is one problem.
  void report_inside(const std::vector<Halfedge>& edges, PlanProblemKind k);

  // BFS over the folds from the back plane V(0) and the floor H(0): crossing a fold on Y from V(d)
  // gives H(Y + d), from H(h) gives V(h - Y).
  void place_faces();

  // Every fold against the faces it joins: one V and one H face, on their line Y = h - d, mountain
  // when the V face is below it. Consecutive edges with the same problem are reported together.
  void check_folds();

  // A V(d) face holds plan points Y at height Y + d >= 0, an H(h) face at depth h - Y >= 0.
  void check_card();

  void validate_graph();

  // Two folds of region r, one below it and one above, less than W apart where they overlap along
  // X with nothing of the region's boundary between them: the strip of paper between them can be
  // neither cut nor folded (issue 23). The nearest such pair, at a place where the region spans
  // from one to the other: the middle of their overlap, else of a stretch of it between the
  // region's vertices.
  struct FoldPair {
    exact::FT X, lo, hi;
  };
  std::optional<FoldPair> nearest_fold_pair(std::size_t r) const;
  // An X in (X_lo, X_hi) where no side of region r meets the open vertical segment from Y lo to Y
  // hi: the middle of the interval, or of a stretch of it between the region's vertices there.
  std::optional<exact::FT> open_between(std::size_t r, const exact::FT& X_lo, const exact::FT& X_hi,
                                        const exact::FT& lo, const exact::FT& hi) const;
  // Whether a side of region r meets the open vertical segment at X from Y lo to Y hi.
  bool crosses_between(std::size_t r, const exact::FT& X, const exact::FT& lo, const exact::FT& hi) const;

  void check_strips();

  void finish();
};

/// The lines of an analysed plan's arrangement after faces were relabelled (the tips,
/// tip_repair.cpp): edges beside no face of `changed` and of lines before `first_new` as they were
/// drawn; the rest by the faces either side (a cut, a cut-out's cut, or a fold where two placed
/// faces meet on their fold line). Segments of one kind are joined end to end where no other of
/// that kind meets them.
std::vector<PlanPolyline> arrangement_lines(const Analyzer& a, const std::set<Face>& changed, std::int32_t first_new);

}  // namespace origamic::analysis
