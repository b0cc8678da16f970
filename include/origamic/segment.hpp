// SPDX-License-Identifier: GPL-3.0-or-later
// Surface segmentation (seed §4.2): region growing over the raster maps into smooth surface regions.
#pragma once

#include <cstdint>
#include <vector>

#include "origamic/grid.hpp"
#include "origamic/raster.hpp"

namespace origamic {

struct SegmentOptions {
  // A pixel joins a segment when the quadratic through its three in-line neighbours predicts its
  // 45-degree depth within this. 0.5 mm is two pixels at 4 px/mm: the steps at occlusions on the
  // seedlike models are over 1 mm, while smooth surfaces are predicted to under 0.05 mm.
  double depth_tol_mm = 0.5;
  // ... plus this fraction of the last in-line depth step: faceted curves seen at grazing angles
  // (the sides of a 96-gon cylinder) change slope by up to 40% from one facet to the next.
  double depth_tol_of_step = 0.5;
  // ... and its normal within this angle. Smoothed normals of the sphere and cylinder models turn
  // under 2 degrees a pixel; the sharp edges of boxes and roofs turn 30 degrees or more.
  double normal_tol_deg = 12.0;
};

/// Segment ids: the back plane and the floor are segments of their own.
inline constexpr std::int32_t kBackSegment = 0;
inline constexpr std::int32_t kFloorSegment = 1;
inline constexpr std::int32_t kNoSegment = -1;  // outside the sheet

struct Segmentation {
  Grid<std::int32_t> segment;            // S: one id per smooth surface region, kNoSegment outside
  std::int32_t count = 2;                // ids are 0 .. count - 1
  std::vector<std::int64_t> pixels;      // pixel count of each segment
};

/// Grows segments in scan order over model pixels (deterministic); back and floor pixels form the
/// segments kBackSegment and kFloorSegment.
Segmentation segment(const RasterMaps& maps, const SegmentOptions& options);

}  // namespace origamic
