// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: faces numbered by the plane they lie in, so that a pixel's plane compares as one integer.
#pragma once

#include <cstdint>
#include <map>
#include <utility>

#include "origamic/slice.hpp"

namespace origamic {

/// Numbers planes (orientation and depth) from 0 in the order first asked; a hole has none, -1. One
/// numbering may serve several lists of faces.
class PlaneNumbers {
 public:
  std::int32_t operator()(const RasterFace& face) {
    if (face.hole) return -1;
    return planes_.try_emplace({face.orientation, face.depth_mm}, static_cast<std::int32_t>(planes_.size()))
        .first->second;
  }

 private:
  std::map<std::pair<Orientation, double>, std::int32_t> planes_;
};

}  // namespace origamic
