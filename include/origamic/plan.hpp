// SPDX-License-Identifier: GPL-3.0-or-later
// The exact core (seed §4.4 validity, §4.5, §4.6): the raster plan's face boundaries become a CGAL
// arrangement over an exact kernel; folds are placed on their exact lines Y = h - d and every edge is
// classified exactly. This header is CGAL-free: it hands out the result in plan millimetres.
#pragma once

#include <cstdint>
#include <unordered_set>
#include <vector>

#include "origamic/oa.hpp"
#include "origamic/plan_regions.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"
#include "origamic/validity.hpp"

namespace origamic {

enum class LineKind : std::uint8_t {
  Cut,
  Mountain,
  Valley,
  Outline,
  CutOut,  // a cut around a piece cut out of the sheet (a hole): it falls out, nothing holds it
};

/// Cut, cut-out and outline lines are all cut through the card.
inline bool is_cut(LineKind kind) {
  return kind == LineKind::Cut || kind == LineKind::CutOut || kind == LineKind::Outline;
}

/// A chain of plan segments of one kind; closed chains repeat their first point at the end.
struct PlanPolyline {
  LineKind kind = LineKind::Cut;
  std::vector<PlanPoint> points;
  // A fold drawn as perforation cuts (read from PERF_MOUNTAIN / PERF_VALLEY): one of the short cuts
  // that together stand for the fold, which runs on to the cuts they keep clear of.
  bool perforation = false;
  bool operator==(const PlanPolyline&) const = default;
};

struct PlanFace {
  Orientation orientation = Orientation::V;
  double depth_mm = 0;     // d of a V face, h of an H face, exactly as the arrangement holds it
  double area_mm2 = 0;     // in the plan
  PlanPoint inside;        // a plan point inside the face, to name where it is
  FaceStatus status = FaceStatus::Valid;
  bool fold_on_top = false;     // some fold runs along its upper side (in the plan)
  bool fold_on_bottom = false;  // some fold runs along its lower side
  bool support = false;         // added by the support stage
};

struct PlanOptions {
  // Cut contours are simplified within this distance (and never more than one pixel) of the raster
  // contour; where they run on the model's own edge, within 0.02 mm of it, and their junctions and
  // corners move onto it (chain_points.hpp). Zero keeps every chain on its pixel contour.
  // A pixel at the default 4 px/mm: a staircase's edge midpoints lie up to a pixel off the line
  // between its end corners, and 0.1 mm kept the steps of shallow staircases. The 37 models at
  // W = 3 mm went from 69,197 cut segments (41,645 under 1 mm) to 48,338 (22,127); at W = 2, 3 and
  // 5 mm places narrower than W 7,089 / 4,235 / 2,325 -> 7,119 / 4,226 / 2,303, mean p95 2.01 /
  // 1.79 / 1.88 -> 1.98 / 1.80 / 1.88 W (the worst, at 3 mm, 3.83 -> 4.00 W: bad_motorbike's
  // supports chose otherwise, its sliced plan the same).
  double simplify_mm = 0.25;
  // A V/H boundary within this fraction of W (plus one pixel) of its fold line Y = h - d becomes
  // that fold (§4.5: the faces are extended or trimmed to meet on it); farther off it is a cut.
  double fold_snap_fraction_of_W = 0.5;
};

/// The chains an exact plan drew unsimplified (simplified, they crossed another boundary), each by
/// an opaque key of its pixel corners and the planes on its sides, in the frame the plan was drawn
/// in. A plan built of the same raster plan changed a little starts them unsimplified and builds its
/// arrangement once; a key that matches no chain, or a chain that would not have crossed this time,
/// costs only a few vertices. A chain that fell back to its pixel contour is not among them.
struct ChainFallbacks {
  std::unordered_set<std::uint64_t> unsimplified;  // each chain by chain_fallback_key
};

struct Plan {
  Sheet sheet;
  std::vector<PlanFace> faces;          // indexed like the raster plan's faces: 0 back, 1 floor
  std::vector<PlanPolyline> lines;      // cuts, mountain and valley folds, and the sheet outline
  // The faces as regions of the sheet, for folding into 3D (fold3d.hpp): one per face (one per
  // connected part, should a face come in parts), with its orientation, depth, status and point.
  std::vector<PlanRegion> regions;
  Validity validity;
  double cut_mm = 0, mountain_mm = 0, valley_mm = 0;
  // Checks of the exact construction, for the report and the tests.
  bool arrangement_valid = false;       // CGAL's is_valid
  bool faces_tile_sheet = false;        // face areas sum to the sheet's (to 1e-9 of it)
  int arrangement_faces = 0;
  int pieces = 0;                       // pieces of paper: validity is decided on them
  int loose_card_pieces = 0;            // pieces of the back plane or the floor no fold holds
  int crumbs_cut_out = 0;               // floating pieces under W x W / 8 or among holes, and pieces of the back plane
                                        // or the floor that fall out (crumbs, slivers): on CUTOUT
  int label_conflicts = 0;              // arrangement faces without a clear majority label
  int raw_chains = 0;                   // boundaries left unsimplified to avoid a crossing
  int unsnapped_chains = 0;             // boundaries kept as pixel contours (no fold snapping) for it
  int unresolved_crossings = 0;         // boundaries that still touch another: must be 0
  int arrangement_builds = 0;           // of the arrangement: more where simplified chains crossed
  int lost_faces = 0;                   // raster faces that no arrangement face carries
  int collapsed_faces = 0;              // faces at most 2 px tall whose folds met when snapped
  int folds_snapped = 0;                // V/H boundaries moved onto their fold line
  double off_model_edges_mm = 0;        // the farthest a cut drawn on the model's edge passes from it
  int trimmed_to_card = 0;              // arrangement faces beyond the back plane or floor given to them
  bool simplified = false;              // every cut simplified, every fold candidate snapped
  ChainFallbacks fallbacks;             // the chains drawn unsimplified: `known` for a plan built again
};

/// Folds closer than this are one line, and an edge shorter than it joins nothing: the rounding of a
/// plan's coordinates to doubles in its files (about 1e-14 mm), with room to spare, and far below
/// any cutter's precision. The design and `origamic validate` both decide with it.
inline constexpr double kFoldLineTolerance_mm = 1e-6;

/// How far from its fold line a V/H boundary may run and still become that fold, in mm.
inline double fold_snap_tolerance_mm(const PlanOptions& options, const RasterPlan& raster_plan, const PixelGrid& grid) {
  return options.fold_snap_fraction_of_W * raster_plan.min_strip_mm + 1 / grid.px_per_mm;
}

/// Once the raster plan's V/H boundaries are moved to the pixel edge nearest their fold line, how
/// far from that line such a boundary lies at most: half a pixel, and a hair for the rounding of Y.
inline double aligned_fold_tolerance_mm(const PixelGrid& grid) { return 1 / grid.px_per_mm + 1e-9; }

/// Builds the exact plan from the raster plan (sheet in mm). Deterministic. The exact numbers are built
/// without thread safety, so calls from several threads take turns (one exact run at a time per
/// process, as for ExactPlan, add_supports, design and analyze_plan). The chains `known` start
/// unsimplified: those of a plan of the raster plan before a change (Plan::fallbacks).
Plan build_plan(const RasterMaps& maps, const RasterPlan& raster_plan, const Sheet& sheet, const PlanOptions& options,
                const ChainFallbacks& known = {});

}  // namespace origamic
