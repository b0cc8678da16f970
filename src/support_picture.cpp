// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_picture.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace origamic {
namespace {

// A pixel's error counts up to 2 W, the p95 error the finished card aims at: beyond it a pixel is
// wrong, whatever by how much, so a support that shows a strip 3 W off costs what one 2 W off
// costs, and a hole no more per pixel than the worst support. A pixel in a hole costs 1 W more: it
// shows no model at all (coverage).
constexpr double kErrorCap_W = 2;
constexpr double kHoleExtra_W = 2;

}  // namespace

SupportPicture::SupportPicture(const RasterMaps& maps, const SliceResult& slices)
    : grid_(maps.grid),
      cap_mm_(static_cast<float>(kErrorCap_W * slices.min_strip_mm)),
      model_key_(maps.grid.cols, maps.grid.rows, std::numeric_limits<float>::quiet_NaN()),
      error_(maps.grid.cols, maps.grid.rows, 0.0f),
      hole_error_(slices.faces.size(), 0.0) {
  Grid<float> hole_added(grid_.cols, grid_.rows, 0.0f);
  tbb::parallel_for(0, grid_.rows, [&](int row) {
    const double Y = grid_.Y(row);
    for (int col = 0; col < grid_.cols; ++col) {
      if (maps.kind(col, row) != HitKind::Model) continue;
      const double model = maps.h_mm(col, row) + maps.d_mm(col, row);
      model_key_(col, row) = static_cast<float>(model);
      const std::int32_t f = slices.face(col, row);
      if (f < 0) continue;
      const RasterFace& face = slices.faces[static_cast<std::size_t>(f)];
      const double key = face.hole                            ? std::abs(Y)
                         : face.orientation == Orientation::V ? Y + 2 * face.depth_mm
                                                              : 2 * face.depth_mm - Y;
      error_(col, row) = std::min(cap_mm_, static_cast<float>(std::abs(key - model)));
      hole_added(col, row) = std::min(cap_mm_, static_cast<float>(std::abs(std::abs(Y) - model))) +
                             static_cast<float>(kHoleExtra_W * slices.min_strip_mm) - error_(col, row);
    }
  });
  for (std::size_t i = 0; i < hole_added.size(); ++i)
    if (const std::int32_t f = slices.face.values[i]; f >= 0)
      hole_error_[static_cast<std::size_t>(f)] += hole_added.values[i];
  for (double& e : hole_error_) e /= grid_.px_per_mm * grid_.px_per_mm;
}

double SupportPicture::added_error(Orientation orientation, double depth_mm, int c0, int c1, int r0, int r1) const {
  c0 = std::max(c0, 0), c1 = std::min(c1, grid_.cols), r0 = std::max(r0, 0), r1 = std::min(r1, grid_.rows);
  double sum = 0;
  for (int row = r0; row < r1; ++row) {
    const double Y = grid_.Y(row);
    const auto key = static_cast<float>(orientation == Orientation::V ? Y + 2 * depth_mm : 2 * depth_mm - Y);
    const float* model = &model_key_.values[model_key_.index(0, row)];
    const float* now = &error_.values[error_.index(0, row)];
    for (int col = c0; col < c1; ++col)
      if (!std::isnan(model[col])) sum += std::min(cap_mm_, std::abs(key - model[col])) - now[col];
  }
  return sum / (grid_.px_per_mm * grid_.px_per_mm);
}

}  // namespace origamic
