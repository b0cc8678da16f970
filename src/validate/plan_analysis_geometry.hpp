// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the exact geometry shared by the plan analysis's two translation units (plan_analysis.cpp
// runs the analysis, plan_analysis_geometry.cpp holds this): the plan's lines collected onto the
// sheet, faces as rings, chords narrower than W, and the numbers and points of the messages. Define
// CGAL_HAS_NO_THREADS before including it (see exact_kernel.hpp).
#pragma once

#include <optional>
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

/// A point strictly inside the face the rings bound. \pre rings bound a face of positive area.
exact::Point inside_point(const std::vector<Ring>& rings);

// ---------------------------------------------------------------------------------------------
// Strips narrower than W: chords of a face along one axis through each of its vertices.

struct Chord {
  exact::FT at, lo, hi;  // the chord runs from lo to hi along the measured axis, at `at` on the other
};

/// The shortest chord of the face the rings bound through one of its vertices, along Y or along X,
/// longer than zero and shorter than W, if any; adds the number of such chords to `narrow`. A chord
/// is the face's stretch on the line just before it or just after it, each side on its own (the
/// strip under a notch, whose corners are its only vertices, is one).
std::optional<Chord> narrowest_chord(const std::vector<Ring>& rings, bool along_Y, const exact::FT& W, int& narrow);

}  // namespace origamic::analysis
