// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the finished card's error estimated on its raster plan, pixel by pixel, as faces'
// planes move (plane_refit.cpp, fold_spacing.cpp): the counts likeness() takes its 95th percentile
// and mean from, kept up to date in log time per pixel.
#pragma once

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "origamic/likeness.hpp"
#include "origamic/oa.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic::raster_card {

// The card's errors, counted in bins of W / 256 (the last bin holds all beyond 64 W), with their sum:
// the 95th percentile, as likeness() takes it, to a bin, and the mean, as a face's pixels change.
// A Fenwick tree counts the errors up to a bin in log time.
class ErrorCounts {
 public:
  static constexpr int kBinsPerW = 256;
  static constexpr int kBins = 1 << 14;
  explicit ErrorCounts(double W) : bin_mm_(W / kBinsPerW), tree_(kBins + 1, 0) { assert(W > 0); }
  // The counts of the errors given, those not negative (a pixel off the model has none): as add(e, 1)
  // for each in turn, the tree built once (linear: an add walks it, a cache miss a level; the card
  // of seedlike/torus, 1 Mpx, was a third of its planes' refit).
  ErrorCounts(double W, std::span<const double> errors_mm) : ErrorCounts(W) {
    for (const double e : errors_mm)
      if (e >= 0) sum_mm_ += e, ++pixels_, ++tree_[static_cast<std::size_t>(bin(e) + 1)];
    for (int i = 1; i <= kBins; ++i)
      if (const int parent = i + (i & -i); parent <= kBins)
        tree_[static_cast<std::size_t>(parent)] += tree_[static_cast<std::size_t>(i)];
  }

  void add(double error_mm, int count) {
    sum_mm_ += count * error_mm;
    pixels_ += count;
    for (int i = bin(error_mm) + 1; i <= kBins; i += i & -i) tree_[static_cast<std::size_t>(i)] += count;
  }

  // The errors in bins 0 .. b.
  std::int64_t up_to(int b) const {
    std::int64_t n = 0;
    for (int i = b + 1; i > 0; i -= i & -i) n += tree_[static_cast<std::size_t>(i)];
    return n;
  }

  // The bin of the 95th percentile of these errors and `more` (count_up_to(b): how many of them lie
  // in bins 0 .. b; `more_pixels` in all, `more_mm` their sum), and the sum of all: less is a better
  // card, the 95th percentile first. `more` may take some of these errors out as it puts others in
  // (count_up_to(b) net of those, more_pixels and more_mm too): a face's pixels in another plane.
  template <typename CountUpTo>
  std::pair<int, double> fares_with(CountUpTo count_up_to, std::int64_t more_pixels, double more_mm) const {
    const std::int64_t n = pixels_ + more_pixels;
    if (n == 0) return {0, 0};
    const auto k = static_cast<std::int64_t>(0.95 * static_cast<double>(n - 1));  // as likeness() picks it
    int lo = 0, hi = kBins - 1;  // the first bin with more than k errors up to it
    while (lo < hi) {
      const int mid = (lo + hi) / 2;
      if (up_to(mid) + count_up_to(mid) > k)
        hi = mid;
      else
        lo = mid + 1;
    }
    return {lo, sum_mm_ + more_mm};
  }
  std::pair<int, double> fares() const {
    return fares_with([](int) { return std::int64_t{0}; }, 0, 0.0);
  }

  // The bin of an error: bins 0 .. kBins - 1.
  int bin_of(double error_mm) const { return bin(error_mm); }

  // The first error past bin b.
  double past(int b) const { return b + 1 >= kBins ? std::numeric_limits<double>::infinity() : (b + 1) * bin_mm_; }

 private:
  int bin(double error_mm) const {
    return static_cast<int>(std::min<double>(kBins - 1, error_mm / bin_mm_));  // clamped before the cast
  }
  double bin_mm_;
  std::vector<std::int64_t> tree_;
  double sum_mm_ = 0;
  std::int64_t pixels_ = 0;
};

// The finished card, estimated on its raster plan: each model pixel's error and the counts of all.
class RasterCard {
 public:
  RasterCard(const RasterMaps& maps, const RasterPlan& raster_plan)
      : maps_(maps), error_(errors(raster_plan)), counts_(raster_plan.min_strip_mm, error_.values) {}

  // The error of pixel (c, r) shown by a face's plane, as likeness() measures it.
  double error(const RasterFace& face, int c, int r) const {
    const double key = shown_key(face.orientation, face.depth_mm, face.hole, maps_.grid.Y(r));
    return std::abs(key - (maps_.h_mm(c, r) + maps_.d_mm(c, r)));
  }

  // Pixel (c, r) as the raster plan shows it now.
  void update(const RasterPlan& raster_plan, int c, int r) {
    if (maps_.kind(c, r) != HitKind::Model) return;
    double& e = error_(c, r);
    if (e >= 0) counts_.add(e, -1);
    e = shown_error(raster_plan, c, r);
    counts_.add(e, 1);
  }

  double error_at(int c, int r) const { return error_(c, r); }
  ErrorCounts& counts() { return counts_; }
  const ErrorCounts& counts() const { return counts_; }

 private:
  // The error of model pixel (c, r) as the raster plan shows it (off the sheet: as a hole).
  double shown_error(const RasterPlan& raster_plan, int c, int r) const {
    const std::int32_t f = raster_plan.face(c, r);
    return f < 0 ? std::abs(shown_key(Orientation::V, 0, true, maps_.grid.Y(r)) - (maps_.h_mm(c, r) + maps_.d_mm(c, r)))
                 : error(raster_plan.faces[static_cast<std::size_t>(f)], c, r);
  }
  // Each pixel's error, -1 off the model.
  Grid<double> errors(const RasterPlan& raster_plan) const {
    Grid<double> shown(maps_.grid.cols, maps_.grid.rows, -1.0);
    for (int r = 0; r < maps_.grid.rows; ++r)
      for (int c = 0; c < maps_.grid.cols; ++c)
        if (maps_.kind(c, r) == HitKind::Model) shown(c, r) = shown_error(raster_plan, c, r);
    return shown;
  }

  const RasterMaps& maps_;
  Grid<double> error_;
  ErrorCounts counts_;
};

struct PixelAt {
  int c = 0, r = 0;
};

}  // namespace origamic::raster_card
