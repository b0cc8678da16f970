// SPDX-License-Identifier: GPL-3.0-or-later
// Fabrication styles (seed §4.6, the plan as made): how a plan's mountain and valley folds are
// drawn — scored, perforated or printed dashed — as the lines every exporter writes. Plan mm.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "origamic/plan.hpp"

namespace origamic {

enum class FoldStyle : std::uint8_t {
  Score,       // each fold one solid line on MOUNTAIN / VALLEY, for a low-power laser or blade pass
  Perforated,  // each fold as short real cuts on PERF_MOUNTAIN / PERF_VALLEY, clear of every cut
  Dashed,      // the printed convention for cutting by hand: mountain dash-dot, valley dashed
};

struct FoldStyleOptions {
  FoldStyle style = FoldStyle::Score;
  // Perforation cut and gap lengths, mm. 1 mm cut / 1 mm bridge (the 1:1 ratio of printers' perf
  // rules): on 200-300 g/m2 card (0.25-0.4 mm thick) a 1 mm bridge is three or more thicknesses
  // wide, so it bends instead of tearing, while cutting half the line makes it fold exactly there.
  // Chosen from that reasoning, not measured on card here; both are options.
  double perf_cut_mm = 1.0;
  double perf_gap_mm = 1.0;
  // Perforations keep this far (mm) from every cut and the sheet edge, measured to each cut
  // segment, so the card does not tear at corners (LASER.md: 0.5 mm in an open-source card maker).
  double inset_mm = 0.5;
};

/// The layers of a drawn plan, in the order a laser should run them: score and perforate first,
/// then the inner cuts, the sheet outline last.
enum class Layer : std::uint8_t { Mountain, Valley, PerfMountain, PerfValley, CutOut, Cut, Outline };
// Scores first, then the pieces that fall out (inner cuts before the ones that free a face), the
// outline last.
inline constexpr Layer kLayerOrder[] = {Layer::Mountain,   Layer::Valley, Layer::PerfMountain, Layer::PerfValley,
                                        Layer::CutOut,     Layer::Cut,    Layer::Outline};

/// A line to draw: a polyline (closed ones repeat their first point), solid or dashed.
struct DrawnLine {
  Layer layer = Layer::Cut;
  std::vector<PlanPoint> points;
  // Empty: solid. Otherwise one period of on/off lengths in mm, starting with on, repeated from the
  // polyline's start; laid out so that the line starts and ends with a whole first dash.
  std::vector<double> dash_mm;
};

struct DrawnPlan {
  FoldStyle style = FoldStyle::Score;
  std::vector<DrawnLine> lines;  // in plan order; writers group them by kLayerOrder
  double fold_mm = 0;            // length of every fold polyline
  double inset_removed_mm = 0;   // perforated: fold length within the inset of a cut (perforated only
                                 // where a stretch between two of the fold's points is in it whole)
  double perforated_mm = 0;      // perforated: total length of the perforation cuts
  int perforations = 0;          // perforated: number of perforation cuts
  int perforated_runs = 0;       // perforated: stretches of fold between insets, each laid out alone,
                                 // and stretches in the insets whole, each given its middle third
};

/// The printed pattern of a fold kind in mm, on/off from a dash: valley dashed {2, 1} (period
/// 3 mm), mountain dash-dot {2, 0.75, 0.5, 0.75} (period 4 mm).
std::span<const double> fold_dash_pattern(LineKind fold);

/// One fold polyline drawn in a style. Score: the polyline, solid. Dashed: the polyline with its
/// kind's pattern, the gaps stretched evenly so that it starts and ends with a whole dash (a
/// polyline shorter than one period plus a dash gets the pattern scaled down to one period plus a
/// dash). Perforated: the parts of the polyline within `inset_mm` of a segment of `cuts` are
/// dropped; each remaining run of length L gets n = floor((L + gap) / (cut + gap)) cuts of exactly
/// perf_cut_mm, the gaps stretched evenly (never below perf_gap_mm), the first and last cut at the
/// run's ends; a run shorter than one cut is cut whole. \pre fold.kind is Mountain or Valley;
/// options pass check_fold_style.
std::vector<DrawnLine> draw_fold(const PlanPolyline& fold, std::span<const PlanPolyline> cuts,
                                 const FoldStyleOptions& options);

/// Every line of the plan drawn in a style: folds by draw_fold against every cut and the sheet
/// outline, cuts and the outline solid. \throws InputError if the options fail check_fold_style.
DrawnPlan draw_plan(const Plan& plan, const FoldStyleOptions& options);

/// The dashes of a line as separate polylines along it (the line itself when it is solid).
std::vector<std::vector<PlanPoint>> dash_pieces(const DrawnLine& line);

/// \throws InputError naming FoldStyleOptions::perf_cut_mm/perf_gap_mm or ::inset_mm when a length
/// is not finite, the perforation
/// cut or gap is outside 0.1-50 mm, or the inset outside 0-50 mm.
void check_fold_style(const FoldStyleOptions& options);

/// "score", "perforated" or "dashed".
const char* fold_style_name(FoldStyle style);

/// One line for captions and metadata, such as "fold style perforated (cut 1 mm, gap 1 mm, inset 0.5 mm)".
std::string fold_style_summary(const FoldStyleOptions& options);

}  // namespace origamic
