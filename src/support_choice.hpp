// SPDX-License-Identifier: GPL-3.0-or-later
// One round of supports (seed §4.4) on the raster plan: candidates from the unjoined top and bottom
// edges of invalid faces to the first face they can fold onto, chosen greedily and widened, then
// painted in as faces of their own (support_paint.cpp). The loop that runs the rounds is in
// supports.cpp.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"
#include "origamic/supports.hpp"
#include "origamic/validity.hpp"

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
  FoldLine near, far;  // where it folds onto `face` (or ends, in its plane) and onto `target`
  double cost = 0;
  int taken = 0;  // rows of `face` the support takes, on its edge
};

// What the loop needs to know of a plan: each face's status and which of its sides are folded.
struct Standing {
  Validity validity;
  std::vector<std::uint8_t> fold_on_top, fold_on_bottom;
};

/// The exact plan's word on each face, as the rounds read it.
Standing standing_of(const Plan& plan);

// What a round's supports may do; the loop (supports.cpp) allows more as the plain rules run out.
struct Reach {
  bool split_faces = true;  // cut a third face in two
  // Hold a face that fills half a W-wide block only farther than 2 W in from its edge (the tip of
  // a tapering facet, a spire's) where it does, the support taking the tip.
  bool below_tips = false;
  // Seed §4.4: at each end of a face's edge, also a support extended a strip width beyond the face
  // (twice as wide), at an extra cost of W: it can reach a face behind the corner that a W-wide one
  // cannot.
  bool corners = false;
};

/// Supports for the invalid faces, chosen greedily in their order, widened, never overlapping; not
/// yet painted. `exact` is the exact plan of `slices` before the supports `painted` since: the face
/// each support reaches is found on it and them (PlanBuild::faces_reached).
std::vector<Candidate> choose_supports(const RasterMaps& maps, const SliceResult& slices, const PlanBuild& exact,
                                       std::span<const Candidate> painted, const Standing& standing,
                                       const std::vector<std::int32_t>& invalid, const SupportOptions& options,
                                       Reach reach);

/// Paints the chosen supports into the raster plan as faces of their own (RasterFace::support).
void paint_supports(const std::vector<Candidate>& chosen, const PixelGrid& grid, double tolerance,
                    std::int64_t crumb_px, SliceResult& slices);

}  // namespace origamic
