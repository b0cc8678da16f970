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
  double preview_px_per_mm = 4;
};

struct LayerStyle {
  const char* name;       // CUT, MOUNTAIN, VALLEY, OUTLINE
  int aci;                // AutoCAD colour index
  const char* rgb;        // the same colour for SVG, #rrggbb
};

/// The layer of a line kind under a colour preset.
LayerStyle layer_style(LineKind kind, ColourPreset preset);

/// Writes the plan as ASCII DXF through dxflib: $INSUNITS = 4 (mm) and $MEASUREMENT = 1, layers CUT,
/// MOUNTAIN, VALLEY, OUTLINE, every entity with its layer and explicit colour, one polyline per
/// chain, folds first and the outline last (the order a laser should run them).
/// \throws OutputError naming the file; no partial file is left.
void write_plan_dxf(const Plan& plan, const std::filesystem::path& file, const ExportOptions& options);

/// Writes the plan as SVG in mm (width/height in mm, viewBox in mm, no transforms), one Inkscape
/// layer group per line kind, hairline strokes. \throws OutputError; no partial file is left.
void write_plan_svg(const Plan& plan, const std::filesystem::path& file, const ExportOptions& options);

/// Writes a PNG picture of the plan in the seed's style: cuts red, folds green (mountain dash-dot,
/// valley dashed), on white. \throws OutputError; no partial file is left.
void write_plan_png(const Plan& plan, const std::filesystem::path& file, const ExportOptions& options);

}  // namespace origamic
