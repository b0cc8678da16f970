// SPDX-License-Identifier: GPL-3.0-or-later
// The machine-readable report of a design and its one-line summary.
#pragma once

#include <filesystem>
#include <string>

#include "origamic/design.hpp"

namespace origamic {

/// The report as JSON text: input, sheet, placement (model -> OA transform in mm), raster
/// statistics, the raster plan, the exact plan with its verdict, and the time of each stage.
std::string report_json(const DesignResult& result, const DesignOptions& options);

/// One line for the terminal: what was designed and how it went.
std::string summary_line(const DesignResult& result);

}  // namespace origamic
