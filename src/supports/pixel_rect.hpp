// SPDX-License-Identifier: GPL-3.0-or-later
// Internal to the supports stage: a rectangle of the raster plan's pixels.
#pragma once

namespace origamic {

struct PixelRect {
  int c0, c1, r0, r1;  // pixels [c0, c1) x [r0, r1)
};

inline bool overlaps(const PixelRect& a, const PixelRect& b) {
  return a.c0 < b.c1 && b.c0 < a.c1 && a.r0 < b.r1 && b.r0 < a.r1;
}

}  // namespace origamic
