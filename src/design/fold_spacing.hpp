// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23: two parallel folds closer than W leave a strip no one can fold. Across a strip between
// two folds the folds lie the difference of the planes beside it apart: an H(h) strip between V(d1)
// above and V(d2) below has its folds at h - d1 and h - d2, d2 - d1 apart, however wide its pixels
// are; a V strip between two H faces, their heights' difference. Supports and refit planes join
// faces whose planes lie a hair under W apart (prim_torus: 2.9985 mm at W = 3 mm). One of the two
// faces moves its plane away from the other's, its folds with it (move_plane), to W apart.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/supports.hpp"

namespace origamic {

/// A face of the raster plan lying in some column between two folds closer than W: the faces
/// above and below it, of one orientation, and the strip's, of the other.
struct FoldPair {
  std::int32_t above = 0, strip = 0, below = 0;
  double apart_mm = 0;  // how far apart the two folds lie: the planes of `above` and `below` apart
};

/// Each strip of the raster plan between two folds closer than W (the raster plan's
/// min_strip_mm), with the faces beside it, once, ordered by the faces. A fold is a V/H boundary
/// within `tolerance_mm` of its line Y = h - d (the exact plan snaps it there); holes fold nowhere.
std::vector<FoldPair> fold_pairs_under_W(const RasterPlan& raster_plan, const PixelGrid& grid, double tolerance_mm);

struct FoldSpacingOptions {
  // The card as estimated on the raster plan may show the model this much worse, in W, at its 95th
  // percentile and its mean, for a plane moved to part two folds; the exact plan, as much again.
  double may_add_p95_W = 0.05, may_add_mean_W = 0.02;
};

/// Whether the plan with the fold pairs parted is to be kept instead of the plan given (the design
/// compares their places narrower than W, measured exactly on their lines).
using FoldSpacingCheck = std::function<bool(const Plan& given, const Plan& parted)>;

/// For each fold pair, one of the two faces beside the strip (the one that shows the model better
/// so, not the back plane or the floor) moves its plane to W (and a micrometre) from the other's,
/// where move_plane can move its folds, no fold pair more is left on the raster plan, and the card
/// shows the model about as well (options). The exact plan of all moves is kept if it stands, shows
/// the model within the options' bounds of the plan given, and `keep` accepts it; the moves are
/// listed in SupportReport::planes_spread. \pre W (the raster plan's min_strip_mm) > 0.
SupportedPlan spread_fold_pairs(const RasterMaps& maps, SupportedPlan supported, const Sheet& sheet,
                                const PlanOptions& plan_options, bool allow_dangling, const FoldSpacingCheck& keep,
                                const FoldSpacingOptions& options = {});

}  // namespace origamic
