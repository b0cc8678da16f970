// SPDX-License-Identifier: GPL-3.0-or-later
// The exact core (seed §4.4 validity, §4.5, §4.6): the raster plan's face boundaries become a CGAL
// arrangement over an exact kernel; folds are placed on their exact lines Y = h - d and every edge is
// classified exactly. This header is CGAL-free: it hands out the result in plan millimetres.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
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
inline bool is_cut(LineKind kind) { return kind == LineKind::Cut || kind == LineKind::CutOut || kind == LineKind::Outline; }

/// A chain of plan segments of one kind; closed chains repeat their first point at the end.
struct PlanPolyline {
  LineKind kind = LineKind::Cut;
  std::vector<PlanPoint> points;
  // A fold drawn as perforation cuts (read from PERF_MOUNTAIN / PERF_VALLEY): one of the short cuts
  // that together stand for the fold, which runs on to the cuts they keep clear of.
  bool perforation = false;
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
  // contour; folds and junctions are not moved by it.
  double simplify_mm = 0.1;
  // A V/H boundary within this fraction of W (plus one pixel) of its fold line Y = h - d becomes
  // that fold (§4.5: the faces are extended or trimmed to meet on it); farther off it is a cut.
  double fold_snap_fraction_of_W = 0.5;
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
  int crumbs_cut_out = 0;               // floating pieces under W x W / 8 or among holes: on CUTOUT
  int label_conflicts = 0;              // arrangement faces without a clear majority label
  int raw_chains = 0;                   // boundaries left unsimplified to avoid a crossing
  int unsnapped_chains = 0;             // boundaries kept as pixel contours (no fold snapping) for it
  int unresolved_crossings = 0;         // boundaries that still touch another: must be 0
  int lost_faces = 0;                   // raster faces that no arrangement face carries
  int collapsed_faces = 0;              // faces at most 2 px tall whose folds met when snapped
  int folds_snapped = 0;                // V/H boundaries moved onto their fold line
  int trimmed_to_card = 0;              // faces whose part beyond the back plane or floor was cut off
  bool simplified = false;              // every cut simplified, every fold candidate snapped
};

/// Folds closer than this are one line, and an edge shorter than it joins nothing: the rounding of a
/// plan's coordinates to doubles in its files (about 1e-14 mm), with room to spare, and far below
/// any cutter's precision. The design and `origamic validate` both decide with it.
inline constexpr double kFoldLineTolerance_mm = 1e-6;

/// How far from its fold line a V/H boundary may run and still become that fold, in mm.
inline double fold_snap_tolerance_mm(const PlanOptions& options, const RasterPlan& slices, const PixelGrid& grid) {
  return options.fold_snap_fraction_of_W * slices.min_strip_mm + 1 / grid.px_per_mm;
}

/// After align_folds_to_lines, how far from its fold line an aligned boundary lies at most: half a
/// pixel, and a hair for the rounding of Y.
inline double aligned_fold_tolerance_mm(const PixelGrid& grid) { return 1 / grid.px_per_mm + 1e-9; }

/// Builds the exact plan from the raster plan (sheet in mm). Deterministic. The exact numbers are built
/// without thread safety, so calls from several threads take turns (one exact run at a time per
/// process, as for ExactPlan, add_supports, design and analyze_plan).
Plan build_plan(const RasterMaps& maps, const RasterPlan& slices, const Sheet& sheet, const PlanOptions& options);

/// The plan line Y = h - d, taken exactly (the difference of the two doubles, unrounded): where a
/// fold between H(h) and V(d) lies.
struct FoldLine {
  double h = 0, d = 0;
};

/// Seed §4.4: a support leaving a face at OA height h and depth d, going up the plan (down), can
/// fold onto a V face behind it (in front of it) or an H face above it (below it): on a V face at
/// depth d' where Y = h - d', on an H face at height h' where Y = h' - d.
inline bool support_folds_onto(Orientation orientation, double depth_mm, bool up, double h, double d) {
  if (orientation == Orientation::V) return up ? depth_mm < d : depth_mm > d;
  return up ? depth_mm > h : depth_mm < h;
}
inline bool support_folds_onto(const RasterFace& target, bool up, double h, double d) {
  return support_folds_onto(target.orientation, target.depth_mm, up, h, d);
}
/// Where that support folds onto a face of the given plane: Y = h - d' on V(d'), Y = h' - d on H(h').
inline FoldLine support_fold(Orientation orientation, double depth_mm, double h, double d) {
  return orientation == Orientation::V ? FoldLine{h, depth_mm} : FoldLine{depth_mm, d};
}

/// A face painted into the raster plan after its exact plan was built, as a vertical ray crossing
/// it meets it: the stretch of the ray between two lines (in either order). A support's ends are
/// its fold lines; other changes end on pixel edges (FoldLine{Y, 0}).
struct PaintedBand {
  Orientation orientation = Orientation::V;
  double depth_mm = 0;
  FoldLine a, b;
};

/// build_plan in two steps, for a loop that decides on many verdicts and keeps one: the verdict
/// (the faces' statuses, orientations, depths, areas and folds on top and bottom, the validity, the
/// arrangement's checks; no lines nor their lengths, no regions, inside points, lost or collapsed
/// faces), then, from the arrangement kept, the plan in full, as build_plan gives it. Same rules.
class ExactPlan {
 public:
  ExactPlan(const RasterMaps& maps, const RasterPlan& slices, const Sheet& sheet, const PlanOptions& options);
  ~ExactPlan();
  ExactPlan(ExactPlan&&) noexcept;
  ExactPlan& operator=(ExactPlan&&) noexcept;

  const Plan& verdict() const;
  Plan full() const;
  /// The raster plan the arrangement was built of (its boundaries aligned to their fold lines), and
  /// its faces: what the arrangement's labels name.
  const Grid<std::int32_t>& face_map() const;
  const std::vector<RasterFace>& faces() const;

  /// A vertical ray up (or down) the plan from (x, from_Y), for a support leaving a face at OA
  /// height h and depth d.
  struct Ray {
    double x = 0, from_Y = 0;
    bool up = true;
    double h = 0, d = 0;
    std::span<const PaintedBand> painted = {};  // faces painted since the plan, across the ray
    double short_mm = 0;                        // how far before a face a fold still lands on it (>= 0)
  };
  /// Where a support may fold onto another face (seed §4.4, "the first face behind or above"):
  /// the faces the ray meets, nearest first, each where the support would fold onto it. That is a
  /// V face at depth d' behind d (in front going down) where the ray meets it at Y = h - d', or an
  /// H face at height h' above h (below) where it meets it at Y = h' - d. Decided exactly on the
  /// arrangement, with h and d the doubles the support will carry, so the fold the next plan draws
  /// there lies on the face. The painted faces cover what the arrangement holds there. Cut-out
  /// faces hold nothing and are passed over. A face is also met where the fold falls up to
  /// `short_mm` before it: a support painted to it there has its end within that of the fold line,
  /// and the next plan snaps it on. Thread-safe.
  struct Reached {
    std::int32_t face;  // the arrangement's label, or -1 for a painted band
    Orientation orientation;
    double depth_mm;
    double Y;  // the fold's Y (nearest double)
  };
  std::vector<Reached> faces_reached(const Ray& ray) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace origamic
