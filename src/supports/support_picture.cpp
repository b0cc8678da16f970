// SPDX-License-Identifier: GPL-3.0-or-later
#include "support_picture.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <tuple>

#include "four_neighbours.hpp"

namespace origamic {
namespace {

// A pixel's error counts in full, mm of h + d: a support, a join or a hole that shows the model
// 9 W off costs three times one 3 W off. Counted up to a cap of 2 W (the p95 the card aims at),
// a strip 9 W off cost what one 2 W off did, and faces no support held went, join after join, to
// planes far off them (res_knot's rings of a loop, one after another, into one plane 12 mm below the
// last): mean p95 over the 37 models 2.48 -> 2.26 W (res_knot 8.90 -> 5.98, arch_pavilion_csg
// 6.95 -> 4.81). Beyond the cap at a fifth of its weight: 2.40; at half: 2.32; at twice: 2.27.
// A pixel in a hole costs 2 W more: it shows no model at all (coverage).
constexpr double kHoleExtra_W = 2;

// Calls visit(i, g) for each face g beside pixel i of a face (all its pixels given) that a join
// may give to (`target`).
template <typename Visit>
void for_each_target_beside(const Grid<std::int32_t>& face, std::span<const PixelAt> pixels,
                            const std::vector<std::uint8_t>& target, Visit&& visit) {
  const std::int32_t f = face(pixels.front().c, pixels.front().r);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    for (const auto& [dc, dr] : kFourNeighbours) {
      const int c = pixels[i].c + dc, r = pixels[i].r + dr;
      if (!face.contains(c, r)) continue;
      const std::int32_t g = face(c, r);
      if (g >= 0 && g != f && target[static_cast<std::size_t>(g)]) visit(i, g);
    }
}

}  // namespace

SupportPicture::SupportPicture(const RasterMaps& maps, const RasterPlan& raster_plan)
    : maps_(maps),
      grid_(maps.grid),
      hole_extra_mm_(static_cast<float>(kHoleExtra_W * raster_plan.min_strip_mm)),
      hole_error_(raster_plan.faces.size(), 0.0) {
  // Off the model nothing is compared: the tables cover the model's bounding box only.
  const PixelRect empty{grid_.cols, 0, grid_.rows, 0};
  const PixelRect bounds = tbb::parallel_reduce(
      tbb::blocked_range<int>(0, grid_.rows), empty,
      [&](const tbb::blocked_range<int>& rows, PixelRect box) {
        for (int row = rows.begin(); row < rows.end(); ++row)
          for (int col = 0; col < grid_.cols; ++col)
            if (maps.kind(col, row) == HitKind::Model)
              box = {std::min(box.c0, col), std::max(box.c1, col + 1), std::min(box.r0, row), row + 1};
        return box;
      },
      [](const PixelRect& a, const PixelRect& b) {
        return PixelRect{std::min(a.c0, b.c0), std::max(a.c1, b.c1), std::min(a.r0, b.r0), std::max(a.r1, b.r1)};
      });
  c0_ = bounds.c0, r0_ = bounds.r0;
  int c_end = bounds.c1, r_end = bounds.r1;
  if (c0_ >= c_end) c0_ = r0_ = c_end = r_end = 0;
  model_key_ = Grid<float>(c_end - c0_, r_end - r0_, std::numeric_limits<float>::quiet_NaN());
  error_ = Grid<float>(c_end - c0_, r_end - r0_, 0.0f);
  // What each pixel of a face adds to its hole error, NaN where it adds nothing.
  Grid<float> to_hole(c_end - c0_, r_end - r0_, std::numeric_limits<float>::quiet_NaN());
  const auto key_of = [&](const RasterFace& face, double Y) {
    return shown_key(face.orientation, face.depth_mm, face.hole, Y);
  };
  tbb::parallel_for(r0_, r_end, [&](int row) {
    const double Y = grid_.Y(row);
    for (int col = c0_; col < c_end; ++col) {
      if (maps.kind(col, row) != HitKind::Model) continue;
      const double model = maps.h_mm(col, row) + maps.d_mm(col, row);
      model_key_(col - c0_, row - r0_) = static_cast<float>(model);
      if (const std::int32_t f = raster_plan.face(col, row); f >= 0) {
        const auto error =
            static_cast<float>(std::abs(key_of(raster_plan.faces[static_cast<std::size_t>(f)], Y) - model));
        error_(col - c0_, row - r0_) = error;
        to_hole(col - c0_, row - r0_) = hole_at(Y, model) - error;
      }
    }
  });
  // In row order, one pixel after another: the sums do not depend on the threads.
  for (int row = r0_; row < r_end; ++row) {
    const std::int32_t* faces = &raster_plan.face.values[raster_plan.face.index(0, row)];
    const float* add = &to_hole.values[to_hole.index(0, row - r0_)];
    for (int col = c0_; col < c_end; ++col)
      if (!std::isnan(add[col - c0_])) hole_error_[static_cast<std::size_t>(faces[col])] += add[col - c0_];
  }
  for (double& e : hole_error_) e /= grid_.px_per_mm * grid_.px_per_mm;
}

std::vector<std::uint8_t> SupportPicture::join_targets(const RasterPlan& raster_plan,
                                                       std::span<const std::int32_t> not_into) const {
  std::vector<std::uint8_t> target(raster_plan.faces.size(), 0);
  for (std::size_t g = kFloorFace + 1; g < target.size(); ++g)
    target[g] = !raster_plan.faces[g].hole && !raster_plan.faces[g].support;
  for (const std::int32_t g : not_into) target[static_cast<std::size_t>(g)] = 0;
  return target;
}

// Each neighbour's plane is tried over the face's pixels, in pixel order; the first best is kept.
// The join's error is what it adds, as hole_error's.
SupportPicture::Join SupportPicture::best_join(const RasterPlan& raster_plan, std::span<const PixelAt> pixels,
                                               std::span<const std::int32_t> neighbours) const {
  Join nearest;
  for (const std::int32_t g : neighbours) {
    const RasterFace& plane = raster_plan.faces[static_cast<std::size_t>(g)];
    double sum = 0;
    bool stays = true;
    for (const auto& [c, r] : pixels) {
      const double Y = grid_.Y(r);
      stays &= on_card(plane.orientation, plane.depth_mm, Y);
      if (compared(c, r)) sum += added_at(c, r, key_of_plane(plane.orientation, plane.depth_mm, Y));
    }
    const double error = sum / (grid_.px_per_mm * grid_.px_per_mm);
    if (stays && error < nearest.error) nearest = {g, error};
  }
  return nearest;
}

// One pass gathers the pixels and the neighbours of the faces asked about.
std::vector<SupportPicture::Join> SupportPicture::nearest_joins(const RasterPlan& raster_plan,
                                                                std::span<const std::int32_t> faces,
                                                                std::span<const std::int32_t> not_into) const {
  const std::size_t n = raster_plan.faces.size();
  std::vector<std::int32_t> slot(n, -1);
  for (std::size_t i = 0; i < faces.size(); ++i)
    slot[static_cast<std::size_t>(faces[i])] = static_cast<std::int32_t>(i);
  const std::vector<std::uint8_t> target = join_targets(raster_plan, not_into);
  std::vector<std::vector<std::int32_t>> neighbours(faces.size());
  std::vector<std::vector<PixelAt>> pixels(faces.size());
  const Grid<std::int32_t>& face = raster_plan.face;
  for (int r = 0; r < face.rows; ++r)
    for (int c = 0; c < face.cols; ++c) {
      const std::int32_t f = face(c, r);
      if (f < 0 || slot[static_cast<std::size_t>(f)] < 0) continue;
      const auto i = static_cast<std::size_t>(slot[static_cast<std::size_t>(f)]);
      pixels[i].push_back({c, r});
      for (const auto& [dc, dr] : kFourNeighbours) {
        if (!face.contains(c + dc, r + dr)) continue;
        const std::int32_t g = face(c + dc, r + dr);
        if (g < 0 || g == f || !target[static_cast<std::size_t>(g)]) continue;
        if (std::find(neighbours[i].begin(), neighbours[i].end(), g) == neighbours[i].end()) neighbours[i].push_back(g);
      }
    }
  std::vector<Join> nearest(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i) nearest[i] = best_join(raster_plan, pixels[i], neighbours[i]);
  return nearest;
}

SupportPicture::Join SupportPicture::nearest_join(const RasterPlan& raster_plan, std::span<const PixelAt> pixels,
                                                  std::span<const std::int32_t> not_into) const {
  if (pixels.empty()) return {};
  std::vector<std::int32_t> neighbours;
  for_each_target_beside(raster_plan.face, pixels, join_targets(raster_plan, not_into),
                         [&](std::size_t, std::int32_t g) {
                           if (std::ranges::find(neighbours, g) == neighbours.end()) neighbours.push_back(g);
                         });
  return best_join(raster_plan, pixels, neighbours);
}

SupportPicture::Shares SupportPicture::shared_join(const RasterPlan& raster_plan, std::span<const PixelAt> pixels,
                                                   std::span<const std::int32_t> not_into) const {
  if (pixels.empty()) return {};
  int c_lo = pixels.front().c, c_hi = c_lo, r_lo = pixels.front().r, r_hi = r_lo;
  for (const auto& [c, r] : pixels)
    c_lo = std::min(c_lo, c), c_hi = std::max(c_hi, c), r_lo = std::min(r_lo, r), r_hi = std::max(r_hi, r);
  Grid<std::int32_t> slot(c_hi - c_lo + 1, r_hi - r_lo + 1, -1);
  for (std::size_t i = 0; i < pixels.size(); ++i)
    slot(pixels[i].c - c_lo, pixels[i].r - r_lo) = static_cast<std::int32_t>(i);
  // A pixel's error under neighbour g's plane. Off the model (paper the 45-degree view does not
  // see) it is none: such a pixel goes to the share that reaches it first. Ties go to the pixel
  // first in row order, then to the neighbour of the lower id, so the shares do not depend on
  // the order the queue was filled in.
  const auto cost = [&](std::size_t i, std::int32_t g) {
    const auto& [c, r] = pixels[i];
    if (!compared(c, r)) return 0.0;
    const RasterFace& plane = raster_plan.faces[static_cast<std::size_t>(g)];
    return std::abs(key_of_plane(plane.orientation, plane.depth_mm, grid_.Y(r)) -
                    static_cast<double>(model_key_(c - c0_, r - r0_)));
  };
  using Entry = std::tuple<double, std::size_t, std::int32_t>;  // cost, pixel, neighbour
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  const auto offer = [&](std::size_t i, std::int32_t g) {
    const RasterFace& plane = raster_plan.faces[static_cast<std::size_t>(g)];
    if (on_card(plane.orientation, plane.depth_mm, grid_.Y(pixels[i].r))) queue.emplace(cost(i, g), i, g);
  };
  for_each_target_beside(raster_plan.face, pixels, join_targets(raster_plan, not_into), offer);
  Shares shares;
  shares.into.assign(pixels.size(), -1);
  while (!queue.empty()) {
    const auto [e, i, g] = queue.top();
    queue.pop();
    if (shares.into[i] >= 0) continue;
    shares.into[i] = g;
    for (const auto& [dc, dr] : kFourNeighbours) {
      const int c = pixels[i].c + dc - c_lo, r = pixels[i].r + dr - r_lo;
      if (!slot.contains(c, r) || slot(c, r) < 0) continue;
      const auto j = static_cast<std::size_t>(slot(c, r));
      if (shares.into[j] < 0) offer(j, g);
    }
  }
  double sum = 0;
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    if (shares.into[i] < 0) return {};
    const auto& [c, r] = pixels[i];
    if (!compared(c, r)) continue;
    const RasterFace& plane = raster_plan.faces[static_cast<std::size_t>(shares.into[i])];
    sum += added_at(c, r, key_of_plane(plane.orientation, plane.depth_mm, grid_.Y(r)));
  }
  shares.error = sum / (grid_.px_per_mm * grid_.px_per_mm);
  return shares;
}

void SupportPicture::give(std::int32_t f, std::int32_t into, const RasterFace& plane, std::span<const PixelAt> pixels) {
  double moved = 0;
  for (const auto& [c, r] : pixels) {
    if (!model_key_.contains(c - c0_, r - r0_) || maps_.kind(c, r) != HitKind::Model) continue;
    const double model = maps_.h_mm(c, r) + maps_.d_mm(c, r);
    const double Y = grid_.Y(r);
    float& error = error_(c - c0_, r - r0_);
    error = static_cast<float>(std::abs(key_of_plane(plane.orientation, plane.depth_mm, Y) - model));
    moved += hole_at(Y, model) - error;
  }
  hole_error_[static_cast<std::size_t>(into)] += moved / (grid_.px_per_mm * grid_.px_per_mm);
  hole_error_[static_cast<std::size_t>(f)] = 0;
}

double SupportPicture::added_error(Orientation orientation, double depth_mm, PixelRect box) const {
  const int c0 = std::max(box.c0, c0_), c1 = std::min(box.c1, c0_ + error_.cols), r0 = std::max(box.r0, r0_),
            r1 = std::min(box.r1, r0_ + error_.rows);
  double sum = 0;
  for (int row = r0; row < r1; ++row) {
    const double Y = grid_.Y(row);
    const auto key = static_cast<float>(key_of_plane(orientation, depth_mm, Y));
    const float* model = &model_key_.values[model_key_.index(0, row - r0_)];
    const float* now = &error_.values[error_.index(0, row - r0_)];
    for (int k = c0 - c0_; k < c1 - c0_; ++k)
      if (!std::isnan(model[k])) sum += std::abs(key - model[k]) - now[k];
  }
  return sum / (grid_.px_per_mm * grid_.px_per_mm);
}

}  // namespace origamic
