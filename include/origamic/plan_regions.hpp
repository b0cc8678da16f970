// SPDX-License-Identifier: GPL-3.0-or-later
// A plan read back from its lines alone (seed §4.4, "validating raster results"): the faces the cuts
// and folds enclose, each with the orientation and depth its folds give it. `origamic validate`
// produces it from any DXF; `origamic fold` folds it into the 3D pop-up.
#pragma once

#include <cstdint>
#include <vector>

#include "origamic/oa.hpp"
#include "origamic/validity.hpp"

namespace origamic {

/// One face of a plan as a region of the sheet, in plan mm.
struct PlanRegion {
  std::vector<std::vector<PlanPoint>> rings;  // outer boundary counter-clockwise first, then holes clockwise
  Orientation orientation = Orientation::V;   // V: parallel to the back plane; H: to the floor
  double depth_mm = 0;                        // d of a V face, h of an H face
  bool placed = false;                        // orientation and depth follow from the folds
  FaceStatus status = FaceStatus::Valid;
  PlanPoint inside;                           // a point inside it, to name where it is
  std::int32_t face = -1;                     // the design's face (Plan::faces) it is; -1 when read from lines
};

}  // namespace origamic
