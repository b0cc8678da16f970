// SPDX-License-Identifier: GPL-3.0-or-later
// Supports (seed §4.4, second half): strips added to the raster plan until the exact plan has no
// floating, dangling or other invalid face, chosen for the likeness of the finished card. Each round
// proposes, from both edges of every invalid face, supports to the first few faces behind/above or
// in front/below, each costing the error it adds to the 45-degree picture (likeness.hpp); chooses
// them as ears of the face graph, the face hardest to hold first (support_ears.hpp); and widens
// them. A face whose holding costs the picture more than its hole is cut out. The exact plan,
// rebuilt from scratch, judges pieces of paper: a face it finds in pieces becomes one face per piece.
#pragma once

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic {

struct SupportOptions {
  bool enabled = true;
  std::uint32_t seed = 1;       // the orders tried break ties between equally costly ears (--seed)
  bool allow_dangling = false;  // leave dangling faces (windows, balconies) as they are
  // c(s) = picture + length + corner + split (seed §4.4, with the error a support adds to the
  // picture): cutting a face not yet held in two costs this much more (as much as 100 mm of a
  // W-wide support 1 W off the model), cutting a standing one ten times as much.
  double split_cost_mm = 100;
  // A support shorter than W (its folds lie the depth difference of the faces it joins apart) is a
  // strip narrower than W between two parallel folds (issue 23): its ears cost this much more, as
  // much as 8 mm more of its length, so a longer support or another way to hold its face wins where
  // it costs about as little. Over the 37 models, places between two parallel folds at W = 2, 3 and
  // 5 mm 595 / 281 / 115 -> 505 / 249 / 109, all places narrower than W 7,633 / 4,303 / 2,292 ->
  // 7,346 / 4,383 / 2,257, mean p95 2.25 / 2.03 / 1.99 -> 2.22 / 2.02 / 2.00 W, all standing.
  double short_support_cost_mm = 2;
  // A support whose fold leaves the face it holds or the face it reaches a strip under W before
  // that face's next fold beyond (a tread or riser between two parallel folds, issue 23: two
  // supports stacked on a slice from rounds apart left it 0.13 mm on prim_cone) costs this much
  // more. Over the 37 models at W = 2 / 3 / 5 mm: faces between two folds under W apart 1,188 / 631
  // / 331 -> 919 / 508 / 282, those under 0.5 mm 254 / 117 / 48 -> 135 / 54 / 28; all places under
  // W 7,968 / 4,726 / 2,437 -> 7,867 / 4,731 / 2,426; mean p95 2.20 / 1.96 / 1.99 -> 2.21 / 1.95 /
  // 2.04 W. At 4 mm: 915 / 495 / 261 such faces, but seedlike/sphere's supports took 26 rounds
  // instead of 11 (15 at 1 mm), its design 1.0 -> 1.45 s.
  double thin_strip_cost_mm = 1;
  // And one whose strip is under W / 6 (0.5 mm at W = 3 mm), a face no one can fold, this much more
  // again. With slices of touching levels kept W apart (slice.cpp), supports stacked onto them left
  // more such slivers. Over the 37 models at W = 2 / 3 / 5 mm, faces between two folds under 0.5
  // mm apart 118 / 80 / 31 -> 104 / 48 / 26, all such faces 659 / 348 / 205 -> 631 / 339 / 205;
  // mean p95 2.05 / 1.79 / 1.90 -> 2.08 / 1.77 / 1.89 W, all standing.
  double sliver_strip_cost_mm = 8;
  // A support whose block column reaches past the end of the face it holds, over the back plane or
  // the floor, is drawn only as far as the face's side, narrower than W (seedlike/wedge: 22 of its
  // 23 places under W): it costs this much more. Over the 37 models at W = 3 mm, places under W
  // 4,504 -> 4,393, mean p95 1.782 -> 1.778 W (4 mm: 4,400, 1.775 W; 12 mm: 4,399, 1.787 W; 30 mm:
  // 4,413, 1.812 W; never taken where a block fits inside the face: 4,266, 1.892 W).
  double past_end_cost_mm = 8;
  // A face no support holds goes to a neighbour (or has its supports bounded by what that would
  // cost) only where the neighbour's plane adds at most this many W of error per pixel of the face,
  // on average; past it the face is held where that costs the picture no more than its hole, else
  // cut out. Unbounded by default: design() bounds it in a third try where the first two gave
  // faces far away (design.cpp, supported_plan).
  double join_error_cap_W = std::numeric_limits<double>::infinity();
  // When supports run out, cut the faces they could not hold out of the sheet (holes, reported as
  // "removed") so that what is left stands; off, such faces stay in the plan, reported invalid.
  bool cut_out_unsupported = true;
  // Cutting out is the last resort (issue 22: at most 3 % of any model cut out): a face whose
  // holding costs the picture more than its hole is cut out only while the faces cut out take no
  // more than this share of the model; a larger one is held whatever that costs, or given to a
  // neighbour (SupportReport::spared_faces). Stairs or a ramp falling away from the viewer, whose
  // treads no fold can hold, had 6.6 % and 11 % cut out, now none (p95 5.8 -> 11.1 W and 9.1 ->
  // 8.5 W: their supports cross the treads). The 37 models' plans at W = 2, 3 and 5 mm are the
  // same; at 1 %, res_teapot at 2 mm went from 1.63 to 2.49 W for 0.49 -> 0.26 % cut out.
  double holes_model_share = 0.03;
  // Face orders tried, one after another from the seed's random sequence, until one makes the
  // plan stand with under 15% of the model cut out; the best of them is kept (fewest faces left
  // unheld, then least cut out).
  int orders = 8;
};

/// A face or support whose whole extent along the main fold is under W: the place to look.
struct NarrowStrip {
  std::int32_t face = 0;
  bool support = false;
  double width_mm = 0;  // its extent along X
  PlanPoint at;         // a pixel centre of it (in its middle column where it has one), in plan mm
};

/// A face cut out of the sheet (a hole), and why.
struct CutOutFace {
  PlanPoint at;  // a pixel centre of it when it was cut out, in plan mm
  double area_mm2 = 0;
  // What holding it and cutting it out cost the picture, as supports' costs are counted (mm of a
  // W-wide support showing the model 1 W off): the cheapest ear found (-1: none) and its hole.
  double hold_cost = -1, hole_cost = 0;
  std::string reason;
};

/// A face no support held (or none for less), shared among its neighbours, each pixel to the one
/// whose plane shows the model there best, or given whole to one; either showed it better than a
/// hole would.
struct JoinedFace {
  PlanPoint at;  // a pixel centre of it, in plan mm
  double area_mm2 = 0;
  // What giving it away and cutting it out added to the picture, in CutOutFace's units (negative
  // where the neighbours' planes show the model better than the face did).
  double joined_cost = 0, hole_cost = 0;
};

/// A face given the plane that shows the finished card's model best, once supports held every face
/// (refit_planes, src/design/plane_refit.hpp).
struct RefitPlane {
  PlanPoint at;  // a pixel centre of it, in plan mm
  Orientation orientation = Orientation::V;
  bool support = false;           // a support, not a face of the model
  double from_mm = 0, to_mm = 0;  // its depth d (V) or height h (H) before and after
  bool closed = false;            // spread: into the plane of the face across the strip, now part of it
};

/// Why supports alone did not make every face stand.
enum class SupportStop : std::uint8_t {
  None,          // they did, or nothing needed them
  NoProgress,    // three rounds in a row left as many faces invalid
  RoundBound,    // the loop's bound (SupportReport::round_bound) was reached
  Unreachable,   // no support reaches the faces left invalid
  ExactInvalid,  // the rounds ended, but the exact plan finds faces invalid
};

struct SupportReport {
  int supports = 0;       // support strips added, before widening merged any
  int rounds = 0;         // rounds of supports chosen
  int exact_builds = 0;   // exact plans judged by: the slices' own, then one per pass of rounds
  int passes_undone = 0;  // passes of rounds undone because they left no fewer faces invalid
  // The share of the model's pixels in the faces cut out (pieces of the back plane or the floor
  // aside), counted as they are cut; never over a quarter.
  double cut_out_share = 0;
  int round_bound = 0;  // the loop's bound: one round per W-wide column of the sheet, plus one
  int orders = 0;       // face orders tried (SupportOptions::orders); the rest is of the one kept
  // Chosen on the raster plan's mirror image and mirrored back (add_supports and
  // add_supports_in_other_frame), and the tries made: 2 when the design tried the other frame too,
  // its first choice having cost the likeness over 1 W (design.hpp); 3 when it tried the other frame
  // again with joins capped (design.cpp, supported_plan).
  bool mirror_image = false;
  bool drawn_in_mirror_image = false;  // and its plan kept as drawn there: drawn here, it did not stand
  int frames = 1;
  bool converged = false;
  SupportStop stop = SupportStop::None;  // why supports alone did not make every face stand
  int stop_faces = 0;                    // how many faces were invalid then
  int stop_loose_pieces = 0;             // and loose pieces of the back plane or the floor
  bool stop_at_quota = false;            // cutting the rest out would have removed over a quarter of the model
  int cut_out = 0;                        // faces cut out of the sheet as the last resort
  std::vector<CutOutFace> cut_out_faces;  // each, with its place and why
  // Faces whose holding costs the picture more than their holes, not cut out: their holes would
  // have taken more of the model than the faces cut out for their cost may
  // (SupportOptions::holes_model_share); held from then on, or given to a neighbour (where no
  // support reaches one at all, the last resort may still cut it out). Each with its place, its
  // costs when it was spared and why.
  std::vector<CutOutFace> spared_faces;
  std::vector<JoinedFace> joined_faces;   // faces given to a neighbour instead of cut out
  std::vector<RefitPlane> planes_refit;   // faces moved to a plane that shows the model better
  std::vector<RefitPlane> planes_spread;  // faces moved to W from a plane across a strip between two
                                          // folds, or into it (closed)
  std::vector<NarrowStrip> narrow;        // faces and supports narrower than W, with their place
};

struct SupportedPlan {
  RasterPlan raster_plan;  // the raster plan with the supports painted in (RasterFace::support)
  Plan plan;           // the exact plan of it, validated from scratch
  SupportReport report;
};

/// Adds supports until every face of the exact plan is valid (or, with allow_dangling, valid or
/// dangling), or the bound is reached. Deterministic for a given seed; the mirror image of a raster
/// plan (on a pixel lattice symmetric on the sheet) gets the mirror image of its supports. The maps
/// are mirrored in place while the supports are chosen on the mirror image, and given back as they
/// were (no copy of them held beside them: 25 bytes a pixel); nothing else may read them meanwhile.
/// Calls from several threads take turns (one exact run at a time per process, as for build_plan and
/// design).
SupportedPlan add_supports(RasterMaps& maps, RasterPlan raster_plan, const Sheet& sheet,
                           const PlanOptions& plan_options, const SupportOptions& options);

/// The same, chosen in the other frame: on the mirror image where add_supports chose on the plan,
/// and on the plan where it chose on the mirror image. Its ties fall the other way, and so may its
/// choices. Nothing where there is no other frame (a plan that is its own mirror image, or a pixel
/// lattice not symmetric on the sheet).
std::optional<SupportedPlan> add_supports_in_other_frame(RasterMaps& maps, RasterPlan raster_plan, const Sheet& sheet,
                                                         const PlanOptions& plan_options,
                                                         const SupportOptions& options);

/// The faces the raster plan's own folds (its V/H boundaries on their fold lines) leave floating,
/// invalid or, unless allowed, dangling: the face graph the support rounds run on, in face order.
/// Its verdict costs a few milliseconds where the exact plan's costs 50-700.
std::vector<std::int32_t> faces_unheld_on_raster(const PixelGrid& grid, const RasterPlan& raster_plan,
                                                 bool allow_dangling);

/// Every face (holes aside) whose pixels span fewer than W (block_px) columns, in face order.
std::vector<NarrowStrip> narrow_strips(const RasterPlan& raster_plan, const PixelGrid& grid);

/// Why supports stopped, in words ("" for SupportStop::None): "12 faces still invalid: no progress in
/// 3 rounds; 2 loose pieces of the back plane or the floor", as the report gives it.
std::string stop_reason(const SupportReport& report);

/// Whether a face of this status is not held: floating, invalid, or dangling unless allowed.
bool needs_support(FaceStatus status, bool allow_dangling);

/// The verdict: no floating or invalid face, and no dangling one unless they are allowed.
bool plan_stands(const Validity& validity, bool allow_dangling);

/// Whether a plan stands: its validity as above, and no loose piece of the back plane or the floor.
bool plan_stands(const Plan& plan, bool allow_dangling);

}  // namespace origamic
