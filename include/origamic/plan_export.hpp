// SPDX-License-Identifier: GPL-3.0-or-later
// The plan as files for laser cutters, cutting plotters, CAD and people: DXF, SVG and a PNG preview,
// all in plan millimetres (X along the main fold from the sheet's left edge, Y up from the fold).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include "origamic/plan.hpp"

namespace origamic {

enum class ColourPreset : std::uint8_t {
  Laser,  // LightBurn habit: cut black, mountain red, valley blue, outline green
  Craft,  // craft-site habit: cut blue, mountain green, valley red, outline black
};

enum class DxfVersion : std::uint8_t { R12, R2000 };

struct ExportOptions {
  std::string model;          // named in every file's metadata
  std::string settings;       // the options that made the plan, one line, for the same
  ColourPreset colours = ColourPreset::Laser;
  DxfVersion dxf_version = DxfVersion::R12;  // R12 is read by every importer tried
  double preview_px_per_mm = 4;  // the PNG preview's resolution
};

struct LayerStyle {
  const char* name;       // CUT, MOUNTAIN, VALLEY, OUTLINE
  int aci;                // AutoCAD colour index
  const char* rgb;        // the same colour for SVG, #rrggbb
};

/// The layer of a line kind under a colour preset.
LayerStyle layer_style(LineKind kind, ColourPreset preset);

/// The plan as ASCII DXF, written by dxflib: $INSUNITS = 4 (mm) and $MEASUREMENT = 1, layers CUT,
/// MOUNTAIN, VALLEY, OUTLINE, every entity with its layer and explicit colour, one polyline per
/// chain, folds first and the outline last (the order a laser should run them). Coordinates carry
/// 16 decimals. \throws OutputError if dxflib cannot write its temporary file.
std::string plan_dxf(const Plan& plan, const ExportOptions& options);

/// The plan as SVG in mm (width/height in mm, viewBox in mm, no transforms; SVG y = half the sheet
/// height - plan Y), one Inkscape layer group per line kind, hairline strokes, 6 decimals.
std::string plan_svg(const Plan& plan, const ExportOptions& options);

/// A PNG picture of the plan in the seed's style (§4.6 figures): cuts red, folds green (mountain
/// dash-dot, valley dashed), on white, at preview_px_per_mm. \throws OutputError.
std::string plan_png(const Plan& plan, const ExportOptions& options);

}  // namespace origamic
