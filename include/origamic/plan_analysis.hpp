// SPDX-License-Identifier: GPL-3.0-or-later
// Validating a plan from its lines alone (seed §4.4, "validating raster results", made exact): the
// cuts and folds are put in an exact arrangement, its faces are placed in OA space by walking the
// folds from the back plane and the floor, every fold is checked against the faces it joins, and the
// face graph is validated as the design's own plan is. This header is CGAL-free.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "origamic/plan.hpp"
#include "origamic/plan_dxf_reader.hpp"
#include "origamic/plan_regions.hpp"
#include "origamic/validity.hpp"

namespace origamic {

struct AnalysisOptions {
  // W: report every face narrower than this along X or Y (see PlanProblemKind::NarrowStrip);
  // 0 skips the check.
  double min_strip_mm = 0;
  // A fold and the line Y = h - d of the faces it joins, placed along other paths, agree when they
  // are at most this far apart. The decision is exact; the tolerance only absorbs the rounding of
  // coordinates to doubles in a file (about 1e-14 mm per fold: a plan's h - d is rarely a double).
  // 1e-6 mm is far below any cutter's precision and catches a fold 0.0001 mm off its line.
  double tolerance_mm = kFoldLineTolerance_mm;
  // The lines' unit; converted to mm exactly (25.4 mm per inch as the rational 254/10).
  DrawingUnit unit = DrawingUnit::Millimetre;
};

enum class PlanProblemKind : std::uint8_t {
  // Errors: the plan does not fold as drawn.
  ConflictingLines,   // one stretch drawn as two kinds: cut and fold, or mountain and valley
  SheetNotSplit,      // a face touches both the sheet's top edge (back plane) and bottom edge (floor)
  FoldNotHorizontal,  // a fold not parallel to the main fold Y = 0
  FoldInsideFace,     // a fold with one face on both sides (a loose end or a slit): nothing folds there
  InconsistentFold,   // the faces it joins, placed along other paths, are both V or both H, or fold on
                      // another line Y = h - d (value_mm: how far the fold is off that line)
  WrongFoldKind,      // mountain where the faces make a valley fold, or the reverse
  Floating,           // validity (seed §4.4): no chain of folds to the back plane or the floor
  Dangling,           // all its folds on one line: it swings about it
  Invalid,            // held by neither two disjoint fold paths nor a connective face
  NarrowStrip,        // narrower than W: the shortest chord of a face along X or along Y through one of
                      // its vertices (the face just before the line or just after it), longer than zero
                      // (a corner's tip is no strip) and shorter than W; one per face and direction
                      // (from/to: the chord, value_mm: its length)
  OutsideCard,        // part of a face reaches below the floor or behind the back plane, by more than
                      // the tolerance, when the card is open at 90 degrees (value_mm: how far): paper
                      // through paper, poking out through the hole it leaves
  // Warnings: reported, the verdict does not change.
  CutInsideFace,  // a cut with one face on both sides: a slit or a loose end
  OutsideSheet,   // a line leaving the sheet (the outline), clipped to it
};

std::string_view to_string(PlanProblemKind kind);  // snake_case, as in the JSON report
bool is_error(PlanProblemKind kind);

/// One problem, located on the plan in mm.
struct PlanProblem {
  PlanProblemKind kind = PlanProblemKind::ConflictingLines;
  PlanPoint at;              // the point to look at
  PlanPoint from, to;        // the stretch concerned: a segment, or the corners of a box (from == to: a point)
  std::int32_t region = -1;  // the face concerned (index in PlanAnalysis::regions), -1 for none
  double value_mm = 0;       // the measured amount, for the kinds that say so
  std::string message;       // one line, with the plan coordinates
  // NarrowStrip along Y: how far apart the face's two nearest parallel folds lie, one below it and
  // one above, where that is under W (the strip between them cannot be folded); 0 for none.
  double folds_apart_mm = 0;
  // NarrowStrip: how many of the face's chords through its vertices along that axis are under W
  // (the narrowest is the one described): a face narrow in one place, or along a tip.
  int narrow_chords = 0;
};

/// The sheet, in plan mm: the bounding box of the outline, or of every line when there is none.
struct PlanBox {
  double min_X = 0, min_Y = 0, max_X = 0, max_Y = 0;
};

struct PlanAnalysis {
  PlanBox sheet;           // in plan coordinates, as everything here: Y up from the main fold
  double main_fold_Y = 0;  // where the drawing has the main fold: 0, or half the sheet's height when
                           // it is drawn from its lower-left corner; a drawing's Y is plan Y + this
  // Every face of the plan: rings in plan mm (outer counter-clockwise first, holes clockwise), its
  // place in OA space when folds reach it, and its validity status. Faces touching the sheet's top
  // edge are the back plane V(0), those touching its bottom edge the floor H(0).
  std::vector<PlanRegion> regions;
  std::vector<double> area_mm2;       // per region
  std::vector<std::int32_t> node;     // per region: its face in `graph` (0 back plane, 1 floor, 2.. the others)
  FaceGraph graph;                    // one fold per fold edge between two nodes; lines by Y within the tolerance
  Validity validity;                  // validity_of(graph)
  std::vector<PlanProblem> problems;  // errors and warnings, errors first, each group in plan order
  int faces = 0;                      // nodes other than the back plane and the floor
  int errors = 0, warnings = 0;
  int narrow_between_folds = 0;                       // NarrowStrip problems with folds_apart_mm > 0
  double cut_mm = 0, mountain_mm = 0, valley_mm = 0;  // lengths inside the sheet
  bool arrangement_valid = false;                     // CGAL's is_valid on the exact arrangement

  /// No error: every face placed consistently and held (valid or indirect), every fold where it folds.
  bool valid() const { return errors == 0; }
};

/// Builds the exact arrangement of the lines (doubles taken exactly, scaled to mm exactly), clipped
/// to the sheet, and analyses it. The main fold is Y = 0 where the sheet reaches both sides of it,
/// else halfway up the sheet (a drawing from the sheet's lower-left corner): see main_fold_Y.
/// Deterministic. Calls from several threads take turns with each other and with build_plan (one
/// exact run at a time per process).
/// \throws InputError if there is no cut or fold line, a coordinate is not finite, an option is
/// absurd, or the sheet has no area.
PlanAnalysis analyze_plan(const std::vector<PlanPolyline>& lines, const AnalysisOptions& options);

/// Issue 23: the tips of faces narrower than W parted off, on the exact arrangement of the lines.
/// Where a face is narrower than W through one of its vertices (PlanProblemKind::NarrowStrip; its
/// chords along Y are tried, the narrowest first, then those along X, until one parts a tip: one tip
/// a face a round) and, across that chord, narrows to its end on one side within `max_tip_mm` and
/// widens to W plus `margin_mm` on the other, a cut across it there (along the chord's axis) parts
/// the tip off (where it forks on the way, a branch that ends within `max_tip_mm` of the chord, under
/// W all along, is parted where it forks), and the tip joins the neighbour beside it whose plane lies
/// nearest the face's own there (the 45-degree key h + d at a point of the tip). A tip stays if its
/// sides hold all of its face's folds with some neighbour. Lines beside a changed face are drawn
/// again (a fold where a V and an H face meet on their line Y = h - d, a cut-out cut beside a hole,
/// else a cut); the others come back as they were, one polyline per stretch between junctions.
/// Round after round, each round kept only if the plan still has no error but narrow strips, has
/// fewer of those, no two of its points become one in a file (its Y rounded from the sheet's lower
/// edge), and `keep` (if given) accepts its lines. A round kept is tried once more (whatever
/// `retries`) without the tips from or to the faces that then have more places than before, and
/// kept so if that passes the same checks with fewer places still. Rounds stop after one that took
/// less than `min_round_gain` (a share) of the places narrower than W off.
struct TipRepairOptions {
  double min_strip_mm = 0;  // W
  double margin_mm = 0.01;  // the new end is this much wider than W
  double max_tip_mm = 12;   // tips narrower than W along more of their length stay
  int rounds = 4;  // at most (the design asks for DesignOptions::tip_rounds)
  // A round refused (no fewer places, or the check given refuses it) is tried this many times more,
  // each time without the tips from or to the faces that have more places than before (a round
  // kept is tried once more so whatever this is). Most tips leave their face narrow elsewhere, and
  // a few make places where they go: when it was chosen (on the 37 models at W = 3 mm, 3 rounds, no
  // round kept tried again), places 4,674 -> 4,504 with 1 retry, the same with 2; tips parted
  // 836 -> 2,462, mean p95 1.774 -> 1.782 W; the tips' time over the 37, 4.5 -> 7.5 s.
  int retries = 1;
  // A round with fewer places that the check given refuses (the design's: the picture) is tried
  // this many times more, each time without the costliest quarter of its tips (their area times how
  // far their plane moves). Over the 37 models at W = 2 / 3 / 5 mm places 6,273 / 3,824 / 2,186 ->
  // 6,235 / 3,766 / 2,157, the mean p95 the same to 0.001 W (res_dragon_full 1.80 -> 1.81 W, 419 ->
  // 390 places; res_dragon_full's tips 340 -> 600 ms, their rounds now kept and more of them); 2,
  // 3 or 4 times, the same 3,766 at 3 mm; without the costlier half, at most twice, 3,803.
  int picture_retries = 1;
  // Rounds go on while the last one kept took at least this share of the places narrower than W
  // off: each round analyses the whole plan again (again each time it is tried without some of its
  // tips), and after one that gained little the next mostly gains nothing. res_dragon_full at
  // W = 3 mm kept a first round (426 -> 415 places, 2.6 %), then tried a second and its retry, both
  // refused: its tips took 420 ms against 220 ms with the rounds stopped after the first. Over the
  // 37 models places 3,802 at 1 %, 3,808 at 2 %, 3,834 at 3 %; their tips and final analysis 4.6,
  // 4.7 and 4.1 s in all (two designs at a time; 3.5 s before rounds kept were tried again).
  double min_round_gain = 0.03;
};
struct TipRepair {
  std::vector<PlanPolyline> lines;  // of the last round kept (the lines given, if none)
  PlanAnalysis analysis;            // of those lines, with W
  // Per region of `analysis`: a point inside the region of the lines given that it comes from (the
  // same face, less a tip or with one more).
  std::vector<PlanPoint> origin;
  int tips = 0;                     // tips parted off in the rounds kept
  int rounds = 0;                   // rounds kept
};
using TipRoundCheck = std::function<bool(const std::vector<PlanPolyline>& lines, const PlanAnalysis& analysis)>;
TipRepair blunt_narrow_tips(const std::vector<PlanPolyline>& lines, const TipRepairOptions& options,
                            const TipRoundCheck& keep = {});

/// "plan VALID: N faces" or "plan INVALID: N faces; k floating, ..." (errors counted by kind).
std::string analysis_summary_line(const PlanAnalysis& analysis);

/// The analysis as JSON text: verdict, summary line, sheet, counts, problems (kind, severity, at,
/// from, to, face, value, message), faces (node, role, placed, orientation, depth, status, inside
/// point, area, holes) and line lengths, all in plan mm.
std::string analysis_json(const PlanAnalysis& analysis, const std::string& file_name);

}  // namespace origamic
