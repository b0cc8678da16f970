// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 22: once supports hold every face, a face may show the model from a plane that no longer
// suits it. Supports gave it its neighbours' pixels (a round shaft's slices, none of which a support
// could hold alone, given to its front slice), or painted part of it over; a support itself lies in
// the plane its first fold gave it, across the model. Each such face takes the plane that shows the
// finished card's model best, its folds moving with it (move_plane), where the exact plan of the
// result still stands and shows the model better.
#pragma once

#include <functional>

#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/supports.hpp"

namespace origamic {

/// How a plan fares: whether it fails to stand, and the p95 and mean error of its card, in W; less
/// is better, standing first.
struct PlanFares {
  bool fails = false;
  double p95_W = 0, mean_W = 0;
  auto operator<=>(const PlanFares&) const = default;
};
PlanFares plan_fares(const RasterMaps& maps, const Plan& plan, double W, bool allow_dangling);

struct PlaneRefitOptions {
  // A face whose own pixels show the model at most this many W off at their 95th percentile keeps
  // its plane: the card's 95th percentile and mean hardly move with it, and trying each face costs.
  // At 0.5 W the 37 models at W = 3 mm came out the same (mean p95 1.77 W; seedlike/torus 1.07 ->
  // 1.06 W, one more place narrower than W).
  double min_face_p95_W = 1;
  // Exact plans built to confirm the planes found: one for all of them, then, while the plan does
  // not stand, one without the faces moved that it leaves unheld.
  int exact_builds = 3;
  // Passes, each finding planes on the plan the one before left, until one moves none: faces whose
  // neighbours moved may show the model better from another plane, or move now where a neighbour's
  // run had refused it. On the 37 models at W = 3 mm, refit once the frames were chosen, one pass
  // gave a mean p95 of 1.826 W, two 1.808 (arch_pavilion_csg 2.91 -> 2.73 W), four 1.801 (the
  // pavilion 2.57 W), eight the same as four; places narrower than W 3,879 -> 3,898.
  int passes = 8;
};

/// Each face (not a hole, the back plane or the floor) whose pixels show the model more than
/// options.min_face_p95_W off at their 95th percentile, the farthest off first, moves to the plane
/// among the 1st, 2nd, ... 99th percentiles of its pixels' model depths that lowers the card's
/// 95th percentile of error most, or else (a face of the model, not a support) its mean by half a
/// percent at least, both estimated on the raster plan; its folds move with it (move_plane, no
/// strip under W left beside them).
/// The exact plan of the moves is kept where it stands and shows the model better than the plan it
/// starts from (the 95th percentile first, then the mean); then planes are found again on the plan
/// kept, up to options.passes times; the report lists each face moved once
/// (SupportReport::planes_refit).
/// \pre W (the raster plan's min_strip_mm) > 0.
/// The exact plan of a raster plan as the plan it changes was drawn (build_plan where empty): a plan
/// the supports drew in the mirror image (SupportReport::drawn_in_mirror_image), whose drawing in
/// the user's frame does not stand, is judged so, its moves too. Such a builder may mirror the maps
/// that refit_planes and spread_fold_pairs are given in place while it runs, and gives them back.
using PlanBuilder = std::function<Plan(const RasterPlan&)>;

SupportedPlan refit_planes(const RasterMaps& maps, SupportedPlan supported, const Sheet& sheet,
                           const PlanOptions& plan_options, bool allow_dangling, const PlaneRefitOptions& options = {},
                           const PlanBuilder& build = {});

}  // namespace origamic
