// SPDX-License-Identifier: GPL-3.0-or-later
// Issue 23 (seed §4.3.2: no strip under W): two parallel folds closer than W leave a strip no one
// can fold. Across a strip the two folds lie the difference of the planes beside it apart: an H(h)
// strip between V(d1) above and V(d2) below folds at h - d1 and h - d2, d2 - d1 apart, however wide
// its pixels are; a V strip between two H faces, their heights' difference. Supports and refit
// planes join faces whose planes lie a hair under W apart (prim_torus: 2.9985 mm at W = 3 mm). One
// of the two faces moves its plane away from the other's, its folds with it, to W apart, or into
// it, the strip closed (a support 0.12 mm proud of a slice: arch_fzk_haus).
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/supports.hpp"
#include "plane_refit.hpp"

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
  // The card may show the model this much worse at its 95th percentile of error, in W, for the
  // planes moved: estimated on the raster plan against the plan given, then on the exact plan.
  // Over the 37 models at W = 2 / 3 / 5 mm the mean p95 moved by 0.005 / 0.001 / 0 W.
  double may_add_p95_W = 0.05;
  // And this much worse at its mean error, in W, likewise.
  double may_add_mean_W = 0.02;
  // Exact plans built at most: where one does not stand, the moves beside the faces it leaves
  // unheld are taken back and the rest built again; so too where the check refuses one for its
  // places. Over the 37 models at W = 2, 3 and 5 mm a second plan stood on 4 (bad_motorbike at
  // 3 mm kept 17 of its 19 moves; arch_temple, csg_menger_slice and res_armadillo at 2 mm, all but
  // one; measured with giver_keeps_px 0). prim_cone at 3 mm takes the third: its first does not
  // stand, its second adds places.
  int exact_builds = 3;
  // Where no move parts a fold pair while each face it takes rows from keeps W of its run there (or
  // none: a run under W is a place narrower than W), one that leaves such a face this many pixels
  // may (0: no second try; 2 px is 0.5 mm at 4 px/mm). Over the 37 models at W = 2 / 3 / 5 mm, at
  // 2 px: fold pairs 224 / 149 / 111 -> 198 / 117 / 106, all places narrower than W 6,228 / 3,834 /
  // 2,177 -> 6,267 / 3,830 / 2,188, faces narrower than W everywhere 296 / 243 / 174 -> 314 / 249 /
  // 177, the mean p95 1.914 / 1.714 / 1.622 -> 1.914 / 1.716 / 1.619 W. At 1 px, 185 / 117 / 109
  // pairs, but the first spread plans of res_dragon_full and seedlike/sphere did not stand and were
  // built again (0.5 s and 0.15 s longer); at 2 px both stood at once. Spread first at 1 px and
  // again keeping W where that plan was refused: 155 / 98 / 89 pairs, and that time besides.
  int giver_keeps_px = 2;
};

/// The design's word on a plan with fold pairs parted, against the plan given (it compares their
/// places narrower than W, measured exactly on their lines): whether to keep it, and where not, the
/// places the parted plan has that the given has not (`worse_at`) and those it has parted
/// (`better_at`), so that the moves beside the places they add may be left out.
struct FoldSpacingVerdict {
  bool keep = false;
  std::vector<PlanPoint> worse_at = {}, better_at = {};
};
using FoldSpacingCheck = std::function<FoldSpacingVerdict(const Plan& given, const Plan& parted)>;

/// For each fold pair, the nearest W apart first, one of the two faces beside the strip (not the
/// back plane or the floor) moves its plane, its folds with it (move_plane): to W (and 2
/// kFoldLineTolerance_mm) from the other's, or into the other's, the strip closed and the two faces
/// one (two folds one step). Of the four moves, those that leave fewer pairs in the face's columns,
/// no face unheld on the raster plan's folds that was held, and the card estimated on the raster
/// within the options' bounds of the plan given, the one that shows the model better. A strip
/// parted by a boundary of two coplanar faces (a support beside a slice in its plane) is not seen.
/// The exact plan of all moves is kept if it stands, shows the model within the options' bounds of
/// the plan given, and `keep` accepts it; the moves are listed in SupportReport::planes_spread.
/// Where it does not stand, the faces whose moves changed a pixel of, or next to, a face it leaves
/// unheld may not move, and the pairs are spread again (up to `exact_builds` plans); likewise where
/// `keep` refuses it, the faces of the moves with more than one place it names worse than better
/// within W of a pixel they changed (a move parts a pair: one place more is a fair trade), and the
/// faces beside their strips. A move leaves each face it takes rows from W of its run there or none
/// of it; where no such move parts a pair, one may leave such a face options.giver_keeps_px.
/// \pre W (the raster plan's min_strip_mm) > 0.
SupportedPlan spread_fold_pairs(const RasterMaps& maps, SupportedPlan supported, const Sheet& sheet,
                                const PlanOptions& plan_options, bool allow_dangling, const FoldSpacingCheck& keep,
                                const FoldSpacingOptions& options = {}, const PlanBuilder& build = {});

}  // namespace origamic
