// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: what the plan's DXF, SVG and PNG writers share.
#pragma once

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include "origamic/fold_style.hpp"

namespace origamic {

/// Text for a one-line field of a file (DXF comments, PNG text): no line breaks.
inline std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  return text;
}

/// The layers the drawing uses, in the order a laser should run them.
inline std::vector<Layer> used_layers(const DrawnPlan& drawn) {
  std::vector<Layer> layers;
  for (const Layer layer : kLayerOrder)
    if (std::ranges::any_of(drawn.lines, [&](const DrawnLine& l) { return l.layer == layer; })) layers.push_back(layer);
  return layers;
}

/// The points of a polyline as a file writes them, `written(point)` being what the file holds for a
/// point (its coordinates as the file's doubles or text): a point the file would write as the one
/// before it is left out, and a line left with one point is no line (empty). Two plan points a
/// rounding apart (a cut of 1e-14 mm where snapped lines meet) become one point in the file, where
/// a laser would burn a dot for the zero-length line and a reader finds nothing.
template <class Written>
std::vector<PlanPoint> as_written(std::span<const PlanPoint> points, Written written) {
  std::vector<PlanPoint> kept;
  for (const PlanPoint& p : points)
    if (kept.empty() || written(p) != written(kept.back())) kept.push_back(p);
  if (kept.size() < 2) kept.clear();
  return kept;
}

}  // namespace origamic
