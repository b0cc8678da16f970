// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: what a support does to the picture (likeness.hpp). On every model pixel it covers, the
// card shows the support's plane instead of the face there: the support adds the error of its plane
// less the error of that face, each in full (support_picture.cpp). Off the model it adds
// nothing: there it covers the back plane, the floor, or paper the 45-degree view does not compare
// (under an overhang, behind a face).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "origamic/grid.hpp"
#include "origamic/oa.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"
#include "pixel_rect.hpp"

namespace origamic {

// A pixel of the raster plan: (column, row).
struct PixelAt {
  int c, r;
};

class SupportPicture {
 public:
  /// The picture of the raster plan as it is.
  SupportPicture(const RasterMaps& maps, const RasterPlan& raster_plan);

  /// The error a face of this plane would add over the pixels of the box, in mm of h + d times mm²
  /// of plan (negative where it would show the model better than what is there).
  double added_error(Orientation orientation, double depth_mm, PixelRect box) const;

  /// The error cutting face f out of the sheet would add: through the hole the back plane shows
  /// above the main fold and the floor below it, and no model. In mm times mm², as added_error.
  double hole_error(std::int32_t f) const { return hole_error_[static_cast<std::size_t>(f)]; }

  /// The mean error over `pixels` pixels of plan that `error` (as hole_error's) makes, in mm.
  double mean_error_mm(double error, std::int64_t pixels) const {
    return pixels > 0 ? error * grid_.px_per_mm * grid_.px_per_mm / static_cast<double>(pixels) : 0.0;
  }

  /// Where face f would best go when no support holds it: the neighbour (not the back plane, the
  /// floor, a hole, a support or a face in `not_into`) whose plane shows the model over f best (the
  /// least error added) and stays on the card there (on_card), and the error giving f to it would
  /// add, as hole_error; none (-1, infinite) where no neighbour's plane can. One entry per face of
  /// `faces`.
  struct Join {
    std::int32_t into = -1;
    double error = std::numeric_limits<double>::infinity();
  };
  std::vector<Join> nearest_joins(const RasterPlan& raster_plan, std::span<const std::int32_t> faces,
                                  std::span<const std::int32_t> not_into = {}) const;
  /// The same for one face, of its pixels as the plan is now.
  /// \pre `pixels` are all the pixels of one face, in row order.
  Join nearest_join(const RasterPlan& raster_plan, std::span<const PixelAt> pixels,
                    std::span<const std::int32_t> not_into = {}) const;

  /// Face f shared among its neighbours (those nearest_join may give to), grown out from their
  /// edges a pixel at a time, the pixel shown best first: each goes to the neighbour whose share
  /// reaches it first, so every share touches its neighbour, and where two shares meet the line
  /// between them is where their planes show the model equally well. `into` names each pixel's
  /// neighbour, in the order of `pixels`; empty (and the error infinite) where some pixel stays
  /// with none. The error is what the shares add, as hole_error.
  /// \pre `pixels` are all the pixels of one face, in row order.
  struct Shares {
    std::vector<std::int32_t> into;
    double error = std::numeric_limits<double>::infinity();
  };
  Shares shared_join(const RasterPlan& raster_plan, std::span<const PixelAt> pixels,
                     std::span<const std::int32_t> not_into = {}) const;

  /// The picture once some of face f's pixels show face `into`'s plane, as a share makes them (the
  /// raster plan's face map may already say so): what one built afresh would find, but for the
  /// order in which the hole error of `into` is summed. f's hole error is spent.
  /// \pre `pixels` are the pixels of f given to `into`; `plane` is `into`'s, not a hole.
  void give(std::int32_t f, std::int32_t into, const RasterFace& plane, std::span<const PixelAt> pixels);

 private:
  const RasterMaps& maps_;
  const PixelGrid& grid_;
  float hole_extra_mm_;
  int c0_ = 0, r0_ = 0;             // the model's first column and row: the tables start there
  Grid<float> model_key_;           // h + d of the model, NaN off it
  Grid<float> error_;               // |key of the face there - model key|, 0 off the model
  std::vector<double> hole_error_;  // per face
  // The faces a join may give to (not the back plane, the floor, a hole, a support or one of
  // `not_into`); the best of `neighbours` over `pixels`.
  std::vector<std::uint8_t> join_targets(const RasterPlan& raster_plan, std::span<const std::int32_t> not_into) const;
  Join best_join(const RasterPlan& raster_plan, std::span<const PixelAt> pixels,
                 std::span<const std::int32_t> neighbours) const;
  // Whether pixel (c, r) is the model's, which the picture compares.
  bool compared(int c, int r) const {
    return model_key_.contains(c - c0_, r - r0_) && !std::isnan(model_key_(c - c0_, r - r0_));
  }
  // What a pixel of the model at plan height Y adds to a hole: the back plane or the floor there,
  // and the extra for showing no model.
  float hole_at(double Y, double model) const {
    return static_cast<float>(std::abs(std::abs(Y) - model)) + hole_extra_mm_;
  }
  // The error a pixel (c, r) of the model adds shown at `key` instead of what shows there now.
  float added_at(int c, int r, double key) const {
    return std::abs(static_cast<float>(key) - model_key_(c - c0_, r - r0_)) - error_(c - c0_, r - r0_);
  }
};

}  // namespace origamic
