// SPDX-License-Identifier: GPL-3.0-or-later
// Pictures of the raster maps, for people checking what the later stages start from.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "origamic/likeness.hpp"
#include "origamic/output.hpp"
#include "origamic/raster.hpp"
#include "origamic/segment.hpp"
#include "origamic/slice.hpp"

namespace origamic {

/// D, F and T as 16-bit grey PNGs (dark = near, as in the seed's Figure 4.2), N as an RGB PNG
/// (normal * 0.5 + 0.5; none where the maps have no normals: DesignOptions::keep_normals) and the
/// hit kind as a colour PNG (back grey, floor tan, model blue, outside black), named for the folder
/// dir. \throws OutputError if one cannot be encoded.
std::vector<OutputFile> raster_image_files(const RasterMaps& maps, const std::filesystem::path& dir);

/// The segmentation map S, the subsegment map SS and the face map as colour PNGs (one colour per id;
/// back plane grey, floor tan), plan_preview.png: the raster plan in the seed's style (§4.6), cuts
/// red, folds green, on white; and E.png, the likeness error of `card`, the finished plan as the
/// 45-degree view sees it (|card h + d - model h + d|: black where the card meets the model, white
/// at 2 W or more off; blue off the model). Named for the folder dir. \throws OutputError.
std::vector<OutputFile> slice_image_files(const RasterMaps& maps, const Segmentation& segmentation,
                                          const RasterPlan& raster_plan, const CardView& card,
                                          const std::filesystem::path& dir);

}  // namespace origamic
