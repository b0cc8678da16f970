// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: how wide a set of pixels is at its widest, by the largest disc it holds (a Euclidean
// distance transform, Felzenszwalb and Huttenlocher 2012).
#pragma once

#include <utility>
#include <vector>

namespace origamic {

/// Twice the largest distance from the centre of a pixel of the set to the centre of the nearest
/// pixel outside it: the diameter of the widest disc the set holds, to a pixel. A strip k pixels
/// wide along a row or a column gives k (k + 1 for odd k: never less than the strip), one along a
/// diagonal about its width across; a crescent as narrow as a strip gives the strip's width,
/// however wide its bounding box. 0 for none. Memory: a double per pixel of the set's box.
double widest_disc_px(const std::vector<std::pair<int, int>>& pixels);

/// Whether the set holds a square of k by k of its pixels. A square of side ceil(w) holds a disc w
/// across (widest_disc_px >= w), and finding one is far cheaper than the distance transform: most
/// sets that are wide are found so at once. \pre pixels listed row by row, each row left to right.
bool holds_square_px(const std::vector<std::pair<int, int>>& pixels, int k);

}  // namespace origamic
