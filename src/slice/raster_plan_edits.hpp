// SPDX-License-Identifier: GPL-3.0-or-later
// Edits of a raster plan's face map that slicing, the exact plan and the support loop share:
// coplanar faces merged, faces in parts split, V/H boundaries moved onto their fold lines, a plane
// moved with its folds.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "origamic/raster.hpp"
#include "origamic/slice.hpp"

namespace origamic {

/// Touching faces of one orientation and one depth lie in one plane: they become one face (a
/// removed thin face or a support had parted them). Faces left without pixels are dropped, except
/// the back plane and the floor; ids are renumbered in order and pixel counts recomputed.
RasterPlan merge_coplanar_faces(RasterPlan raster_plan);

/// Touching faces of one orientation whose depths differ by at most tolerance_mm are one sheet of
/// paper: a faceted tower's facets a fraction of a millimetre apart, which no support can join (the
/// fold would need a strip thinner than a pixel). Each group, its depths within the tolerance of each
/// other, becomes one face at their mean depth by pixels (the back plane and the floor keep depth 0);
/// supports and holes are left alone. Ids are renumbered as merge_coplanar_faces does.
RasterPlan merge_near_coplanar_faces(RasterPlan raster_plan, double tolerance_mm);

/// A face whose pixels fall apart into several 4-connected parts (a support cut through it, or the
/// exact plan found it in pieces) is that many pieces of paper: each part but the largest becomes a
/// face of its own, with the same plane, appended in order; a part under `min_part_px` pixels or
/// `min_part_cols` columns wide (a crumb, a sliver; a whole face under `min_part_px`, the back
/// plane and the floor aside) joins the neighbouring face it shares the most pixel sides with.
struct FacePart {
  std::int32_t face = 0;  // the new face
  std::int32_t from = 0;  // the face it was part of
};
struct SplitFaces {
  RasterPlan raster_plan;
  std::vector<FacePart> parts;  // the new faces
};
SplitFaces split_disconnected_faces(RasterPlan raster_plan, const std::vector<std::int32_t>& faces,
                                    std::int64_t min_part_px, int min_part_cols);

/// Seed §4.5 on the raster: where a V(d) face and an H(h) face meet one above the other within
/// `tolerance_mm` of their fold line Y = h - d, the boundary moves to the pixel boundary nearest
/// that line, column by column, as long as both faces keep a pixel in the column. The exact plan
/// then moves it onto the line by under half a pixel and cannot cross a neighbouring boundary on
/// the way. Pixel counts are kept up to date.
RasterPlan align_folds_to_lines(RasterPlan raster_plan, const PixelGrid& grid, double tolerance_mm);

/// Face f's plane moved to `depth_mm` (d of a V face, h of an H face) with its folds: wherever f
/// and a face of the other orientation meet one above the other within `tolerance_mm` of their
/// fold line, their boundary moves as the line does (to the pixel edge nearest the new line where
/// it lay on the one nearest the old, as many rows off it where it lay off it), f taking the
/// other's pixels or giving it its own. A face whose run in a column ends before the new line
/// gives the whole run there, and the taker meets the face beyond it; not where that face is f,
/// nor, where f gives, where f is folded to it (that fold moves too).
/// Nothing where a fold cannot move so: a face giving pixels would keep fewer than `min_run_px`
/// rows of its run in the column, counted as all the folds' moves leave it (f gives rows at one
/// fold as it takes as many at the other), where its run there had as many before and keeps some;
/// or a third face lies between the old and the new line with the giver beyond it, or the new line
/// lies off the sheet; or where the move leaves a face in more 4-connected parts than it was.
/// `columns` (first, last), if given, holds every column of f: only those are searched for its
/// folds. With `onto`, a face of f's orientation in the plane `depth_mm`, two folds become one
/// step: where another face lies between f and `onto` in a column, folded to both, f takes all of
/// its rows there (its strip closes), and f becomes part of `onto` (f keeps no pixel; the runs
/// kept and the parts after the move are counted as one face's). Nothing if no strip closes, or
/// where a face between them is not folded to both (it would lie between two parts of `onto`).
/// \pre f is a face of the plan, not the back plane, the floor or a hole; `onto`, if given, is
/// another face, not a hole, of f's orientation and depth `depth_mm`.
std::optional<RasterPlan> move_plane(const RasterPlan& raster_plan, const PixelGrid& grid, std::int32_t f,
                                     double depth_mm, double tolerance_mm, int min_run_px,
                                     std::optional<std::pair<int, int>> columns = std::nullopt,
                                     std::optional<std::int32_t> onto = std::nullopt);

/// The smaller side, in pixels, of the oriented bounding box (principal axes) of a pixel set.
double oriented_box_min_side_px(const std::vector<std::pair<int, int>>& pixels);

}  // namespace origamic
