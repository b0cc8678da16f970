// SPDX-License-Identifier: GPL-3.0-or-later
// Likeness: the finished card against its model, as the 45-degree view sees both (seed §4.1's
// depth map D, made a measure). Along the view every point of the card on the ray through plan
// point (X, Y) is the paper at (X, Y), so each plan pixel shows one face: a V face at depth d has
// the 45-degree key h + d = Y + 2d, an H face at height h the key 2h - Y. The model's key is its
// own front-most h + d there. A hole shows the plane behind it: the back plane (key Y) above the
// main fold, the floor (key -Y) below.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "origamic/grid.hpp"
#include "origamic/plan.hpp"
#include "origamic/plan_regions.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic {

/// What the card shows at a plan pixel.
enum class CardSurface : std::uint8_t {
  Model,    // a face sliced from the model
  Support,  // a support strip (seed §4.4)
  Back,     // the back plane, or a loose piece of it (V at depth 0)
  Floor,    // the floor, or a loose piece of it (H at height 0)
  Hole,     // nothing: cut out of the sheet, or a piece no fold places
  Outside,  // beyond the sheet
};

/// The card as the 45-degree view sees it, per plan pixel centre.
struct CardView {
  Grid<double> key_mm;  // h + d of the paper there (of the plane behind a hole)
  Grid<CardSurface> surface;
};

/// The raster plan's card: each pixel shows its face of `faces`.
CardView card_view(const PixelGrid& grid, const Grid<std::int32_t>& face, const std::vector<RasterFace>& faces);

/// A plan's card from its regions, each pixel centre in the region whose rings hold it (even-odd,
/// edges half-open so that regions tiling the sheet share no centre). `support` tells, per
/// PlanRegion::face, the supports (empty: none known, as for a plan read from its lines). Unplaced
/// and removed regions are holes.
CardView card_view(const PixelGrid& grid, std::span<const PlanRegion> regions, const std::vector<bool>& support);

/// A designed plan's card: its regions, its supports known from its faces.
CardView card_view(const PixelGrid& grid, const Plan& plan);

/// Per region, the widest disc it holds, in pixels, to a pixel (its pixel centres as card_view
/// finds them; 0 for a region that holds none): a face under W * px_per_mm is narrower than W
/// everywhere, a strip or a sliver, where a face narrow only at a tip or a notch is not.
std::vector<double> widest_discs_px(const PixelGrid& grid, std::span<const PlanRegion> regions);

/// The likeness of a card to its model, over the model's pixels.
struct Likeness {
  double mean_mm = 0, p95_mm = 0;  // |card key - model key|, mean and 95th percentile
  double mean_W = 0, p95_W = 0;    // the same in strip widths
  double coverage = 0;             // share shown as a face of the model or a support (not back, floor, hole)
  double support_share = 0;        // share shown as a support
  double cut_out_share = 0;        // share in holes
  std::int64_t model_pixels = 0;
};

/// Measures the card against the model's raster (`maps`, whose model pixels are the model's).
/// A model with no pixels has likeness zero throughout. \pre card and maps on the same grid, W > 0.
Likeness likeness(const RasterMaps& maps, const CardView& card, double W);

/// Per pixel |card key - model key| in mm over the model's pixels; -1 elsewhere.
Grid<float> likeness_error_map(const RasterMaps& maps, const CardView& card);

}  // namespace origamic
