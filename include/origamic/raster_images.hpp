// SPDX-License-Identifier: GPL-3.0-or-later
// Pictures of the raster maps, for people checking what the later stages start from.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "origamic/raster.hpp"

namespace origamic {

/// Writes D, F and T as 16-bit grey PNGs (dark = near, as in the seed's Figure 4.2), N as an RGB PNG
/// (normal * 0.5 + 0.5) and the hit kind as a colour PNG (back grey, floor tan, model blue, outside
/// black) into dir, creating it. Each file appears complete or not at all.
/// \returns the paths written.
/// \throws OutputError if dir or a file cannot be written.
std::vector<std::filesystem::path> write_raster_images(const RasterMaps& maps,
                                                       const std::filesystem::path& dir);

}  // namespace origamic
