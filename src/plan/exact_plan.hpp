// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the exact plan built in two steps, for the support loop (supports.cpp), which decides on
// many verdicts and keeps one, and the fold lines its supports leave on. build_plan (plan.hpp) is the
// library's call; this is its machinery.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "origamic/grid.hpp"
#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic {

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
  ExactPlan(const RasterMaps& maps, const RasterPlan& raster_plan, const Sheet& sheet, const PlanOptions& options,
            const ChainFallbacks& known = {});
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
  static void build(State& state, const RasterMaps& maps, const RasterPlan& raster_plan, const Sheet& sheet,
                    const PlanOptions& options, const ChainFallbacks& known);
  std::unique_ptr<State> state_;
};

}  // namespace origamic
