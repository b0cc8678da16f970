// SPDX-License-Identifier: GPL-3.0-or-later
// One round of supports (seed §4.4) on the raster plan: candidates from the unjoined top and bottom
// edges of invalid faces to the first face they can fold onto, chosen greedily and widened, then
// painted in as faces of their own (support_paint.cpp). The loop that runs the rounds is in
// supports.cpp.
#pragma once

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "exact_plan.hpp"
#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"
#include "origamic/supports.hpp"
#include "origamic/validity.hpp"
#include "pixel_rect.hpp"
#include "support_ears.hpp"

namespace origamic {

// A support: a W-wide (or wider) block of the raster plan between the face it holds and the face it
// reaches, turned into a face of its own.
struct Candidate {
  std::int32_t face = 0, target = 0;
  int c0 = 0, c1 = 0;  // pixel columns [c0, c1)
  int r0 = 0, r1 = 0;  // pixel rows [r0, r1) the support covers
  int face_row = 0;    // the row of `face` just outside the support
  int target_row = 0;  // the row of `target` just outside it, on the other side
  Orientation orientation = Orientation::V;
  double depth_mm = 0;
  FoldLine near, far;              // where it folds onto `face` (or ends, in its plane) and onto `target`
  double cost = 0;                 // the picture's, and a little for its length (the faces it cuts aside)
  double picture_mm = 0;           // the error it adds to the picture, per W x W of plan (part of its cost)
  std::vector<std::int32_t> cuts;  // the faces it cuts in two
  int taken = 0;                   // rows of `face` the support takes, on its edge
  // The strip under W it leaves `face` or `target`, at the block column's centre, between its fold
  // and a parallel one beyond: the narrowest such, infinite where it leaves none.
  double thin_strip_mm = std::numeric_limits<double>::infinity();
  bool leaves_thin_strip() const { return thin_strip_mm != std::numeric_limits<double>::infinity(); }
  // Its block column reaches past the end of the face it holds (one at least W wide) over the back
  // plane or the floor: the support is drawn only as far as that face's side, narrower than W.
  bool past_end = false;

  PixelRect pixels() const { return {c0, c1, r0, r1}; }
};

// What the loop needs to know of a plan: each face's status and which of its sides are folded.
struct FaceVerdicts {
  Validity validity;
  std::vector<std::uint8_t> fold_on_top, fold_on_bottom;
};

/// The folds of the raster plan: wherever a V(d) pixel and an H(h) pixel meet one above the other
/// within `tolerance` of Y = h - d, as the exact plan snaps them (plan.hpp), the upper face first; a
/// run of one pair once, in row order.
std::vector<FoldEdge> raster_folds(const PixelGrid& grid, const RasterPlan& raster_plan, double tolerance);

/// The face graph read from the raster plan's folds (the upper face first). Rebuilding the exact
/// plan costs 50-700 ms; this costs a few, so rounds run on it and the exact plan only confirms (and
/// overrides) its verdict.
FaceVerdicts raster_verdicts(const PixelGrid& grid, const RasterPlan& raster_plan, double tolerance);

/// The faces (the back plane and the floor aside) whose verdict says they need a support.
std::vector<std::int32_t> unsupported(const FaceVerdicts& verdicts, bool allow_dangling);

/// The exact plan's word on each face, as the rounds read it.
FaceVerdicts verdicts_of(const Plan& plan);

// What a round's supports may do; the loop (supports.cpp) allows more as the plain rules run out.
struct SupportReach {
  bool split_faces = true;  // cut a third face in two
  // Hold a face that fills half a W-wide block only farther than 2 W in from its edge (the tip of
  // a tapering facet, a spire's) where it does, the support taking the tip.
  bool below_tips = false;
  // Seed §4.4: at each end of a face's edge, also a support extended a strip width beyond the face
  // (twice as wide), at an extra cost of W: it can reach a face behind the corner that a W-wide one
  // cannot.
  bool corners = false;
};

// What a round of supports reads: the maps, the raster plan as it is now, the exact plan last built
// of it, the supports painted since, and the raster plan's folds (raster_folds).
struct SupportRound {
  const RasterMaps& maps;
  const RasterPlan& raster_plan;
  const ExactPlan& exact_plan;
  std::span<const Candidate> painted;
  std::span<const FoldEdge> folds;
};

/// The candidate supports from both edges of the faces (seed §4.4, a few per ray: the first faces
/// it can fold onto), each with its cost and the faces it cuts in two; what choose_supports chooses
/// among (the round's folds are not read).
std::vector<Candidate> support_candidates(const SupportRound& round, const std::vector<std::int32_t>& faces,
                                          SupportReach reach);

/// The ear search's edge of a candidate support: its cost and what else it costs. Cutting a face in
/// two leaves a piece to hold: a face not yet held costs the split cost, one that stands (`stands`,
/// per face) ten times that, its pieces needing holding anew. A support shorter than W leaves a
/// strip narrower than W between its two parallel folds: it costs the short support cost more.
SupportEdge support_edge(const Candidate& c, const std::vector<std::uint8_t>& stands, const SupportOptions& options,
                         double W);

struct SupportChoice {
  std::vector<Candidate> supports;
  // Invalid faces whose every ear costs the picture more than cutting them out or giving them to a
  // neighbour would: the face, the picture cost of its cheapest ear and that of its hole (per W x W
  // of plan, as Candidate::cost).
  struct CostlyFace {
    std::int32_t face;
    double hold, hole;
  };
  std::vector<CostlyFace> cut_out;
};

/// Supports for the invalid faces, chosen ear by ear (support_ears.hpp), the cheapest first, over
/// the plan's folds and the candidates of both edges of every invalid face; widened, never
/// overlapping; not yet painted. The face each support reaches is found on the round's exact plan
/// and the supports painted since (ExactPlan::faces_reached). A candidate costs the error it adds
/// to the picture and a little for its length (and much for each face it cuts in two). A face is
/// held only where that costs no more than the error a hole in its place would add (seed §4.4 shows
/// supports always exist; here they must also be worth it). A face `hold_at_any_cost` marks (by
/// id) is held whatever that costs, or given to a neighbour: no hole is weighed for it.
SupportChoice choose_supports(const SupportRound& round, const FaceVerdicts& verdicts,
                              const std::vector<std::int32_t>& invalid, const SupportOptions& options,
                              SupportReach reach, const std::vector<std::uint8_t>& hold_at_any_cost = {});

/// Makes every face of the raster plan one piece of paper, as the exact plan judges them: each
/// 4-connected part of a face (a loose piece of the back plane or the floor too) becomes a face of
/// its own, a part under crumb_px pixels joins a neighbour. The face graph of the rounds is then the
/// exact plan's graph of pieces.
RasterPlan split_into_pieces(RasterPlan raster_plan, std::int64_t crumb_px);

/// Paints the chosen supports into the raster plan as faces of their own (RasterFace::support),
/// then splits it into pieces.
RasterPlan paint_supports(RasterPlan raster_plan, const std::vector<Candidate>& chosen, const PixelGrid& grid,
                          double tolerance, std::int64_t crumb_px);

}  // namespace origamic
