// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the support choice in a frame a mirrored model shares. The choice breaks its ties one
// way (block columns left to right, a support widened to the left first, its ray right of the
// column's centre), so a model and its mirror image would get supports of their own. It runs on
// whichever of the raster plan and its mirror image comes first in an order that mirroring reverses
// (`first_support_frame`), and what it gives back is mirrored back: the mirrored model's raster plan
// is the mirror image of the model's, so both choose on the same picture.
#pragma once

#include "origamic/plan.hpp"
#include "origamic/raster.hpp"
#include "origamic/slice.hpp"
#include "origamic/supports.hpp"

namespace origamic {

/// The frame the supports are chosen in first. Reading the model's columns from both ends inwards,
/// pixel by pixel down them (by kind of paper, its plane, where a face begins and whether it runs on
/// inwards), the first that differ decide: the lesser on the left, the plan itself; on the right, its
/// mirror image. The order does not depend on face ids, and moving the model along the fold does not
/// change it; mirroring the model turns it round. (Either way round serves: over the 37 models of
/// ../shared/models the first frame's choice gave a mean p95 of 2.70 W this way and 2.67 W the other;
/// this way the full dragon's costs it under 1 W, 1.75 against 1.09 W sliced, so its design needs no
/// second frame, which would double its 3 s.) `Only` (the plan itself, and no other frame) when the
/// pixel lattice is not symmetric on the sheet (no exact mirror image) or the columns read the same
/// from both ends.
enum class SupportFrame { Only, Plan, MirrorImage };
SupportFrame first_support_frame(const RasterPlan& raster_plan, const PixelGrid& grid, const Sheet& sheet);

/// The maps mirrored along the main fold, in place (X to the sheet's width less X; a normal's x
/// negated). Mirroring twice gives them back bit for bit, their breaks being multiples of 1/2048 of
/// the way between pixel centres, as raster() puts them.
void mirror_in_place(RasterMaps& maps);

/// The maps in their mirror image for as long as it lives, and given back as they were when it ends,
/// by an exception too. (Mirroring itself throws nothing but an allocation failure of the threads'
/// tasks, which ends the program in the destructor.)
class MirroredMaps {
 public:
  explicit MirroredMaps(RasterMaps& maps);
  ~MirroredMaps();
  MirroredMaps(const MirroredMaps&) = delete;
  MirroredMaps& operator=(const MirroredMaps&) = delete;

 private:
  RasterMaps& maps_;
};

/// The raster plan mirrored (face ids kept; its subsegments too where it has them, which design()
/// sets aside for the support stage; block_subsegment, which nothing reads after slicing, as it
/// is). Mirroring twice gives it back.
RasterPlan mirror_image(RasterPlan raster_plan);

/// The faces renumbered in the order a row-major scan meets them (the back plane and the floor
/// first): the ids a mirror image's slicing would not give. Faces without pixels, which the loop
/// never chooses for, come last in their old order.
RasterPlan with_faces_in_scan_order(RasterPlan raster_plan);

/// A supported plan chosen on the mirror image, mirrored back: its raster plan, its exact plan's
/// lines, faces and regions, and the places its report names.
SupportedPlan mirror_image(SupportedPlan supported, const Sheet& sheet);

}  // namespace origamic
