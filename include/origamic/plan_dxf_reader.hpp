// SPDX-License-Identifier: GPL-3.0-or-later
// Reading a plan back from a DXF file (seed §4.4, "validating raster results"): any plan, written by
// origamic or drawn by hand, as cut, mountain, valley and outline polylines in plan coordinates.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "origamic/plan.hpp"

namespace origamic {

/// The layers a plan's lines are read from. Names compare case-insensitively, as in CAD programs.
struct LayerNames {
  std::string cut = "CUT";            // cuts
  std::string mountain = "MOUNTAIN";  // mountain folds
  std::string valley = "VALLEY";      // valley folds
  std::string outline = "OUTLINE";    // the sheet's edge (optional)
  std::string cut_out = "CUTOUT";     // cuts around pieces cut out of the sheet: they fall out
  // Folds drawn as perforation cuts: each fold's short cuts, stopping short of the cuts it meets.
  std::string perforated_mountain = "PERF_MOUNTAIN";
  std::string perforated_valley = "PERF_VALLEY";
};

/// The drawing unit a DXF declares in $INSUNITS.
enum class DrawingUnit : std::uint8_t { Millimetre, Centimetre, Metre, Inch, Foot };

/// The plan as drawn, in the drawing's own unit.
struct DxfDrawing {
  std::vector<PlanPolyline> lines;  // in `unit`; closed polylines repeat their first point at the end
  DrawingUnit unit = DrawingUnit::Millimetre;
  int ignored_entities = 0;               // entities on other layers (texts, dimensions, frames)
  std::vector<std::string> other_layers;  // the layers they were on, sorted
};

/// Millimetres per drawing unit: 1, 10, 1000, 25.4, 304.8.
double mm_per_unit(DrawingUnit unit);
const char* to_string(DrawingUnit unit);

/// Reads an ASCII DXF (R12 or later) with dxflib: LINE, POLYLINE (with its VERTEXes) and LWPOLYLINE
/// entities on the plan's layers, in model space, outside block definitions; the closed flag closes a
/// polyline. Coordinates are taken exactly as the file's doubles, Z is ignored, and a 2D polyline
/// whose extrusion is (0, 0, -1) is mirrored into world X as CAD programs draw it.
/// $INSUNITS 4 (mm) is assumed when absent or 0 (unitless); 1 (in), 2 (ft), 5 (cm) and 6 (m) are
/// recorded in `unit`.
/// \throws InputError naming the file for a missing, unreadable, empty, binary, truncated (no EOF)
/// or non-DXF file, for any other $INSUNITS, for arcs (bulges, ARC, CIRCLE, ELLIPSE, SPLINE), block
/// references, mesh polylines or polylines out of the XY plane on the plan's layers, and when no cut
/// or fold line is found.
DxfDrawing read_dxf_drawing(const std::filesystem::path& file, const LayerNames& layers);

/// The same plan in millimetres: each coordinate multiplied by mm_per_unit and rounded to the
/// nearest double (exact for a drawing in mm). For exact work on drawings in other units, pass
/// read_dxf_drawing's lines and unit to analyze_plan instead. \throws InputError as above.
std::vector<PlanPolyline> read_plan_dxf(const std::filesystem::path& file, const LayerNames& layers);

}  // namespace origamic
