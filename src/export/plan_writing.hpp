// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: what the plan's DXF, SVG and PNG writers share.
#pragma once

#include <algorithm>
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

}  // namespace origamic
