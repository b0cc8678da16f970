// SPDX-License-Identifier: GPL-3.0-or-later
// The plan as files for laser cutters, cutting plotters, CAD and people: DXF, SVG, a PNG preview and
// a print-ready PDF, all in plan millimetres (X along the main fold from the sheet's left edge, Y up
// from the fold), the folds drawn in a fabrication style (fold_style.hpp).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "origamic/fold_style.hpp"
#include "origamic/oa.hpp"
#include "origamic/output.hpp"
#include "origamic/plan.hpp"

namespace origamic {

enum class ColourPreset : std::uint8_t {
  Laser,  // LightBurn habit: cut black, mountain red, valley blue, outline green
  Craft,  // craft-site habit: cut blue, mountain green, valley red, outline black
};

enum class DxfVersion : std::uint8_t { R12, R2000 };

enum class Paper : std::uint8_t {
  Sheet,   // the PDF page is the sheet itself
  A4,      // 210 x 297 mm
  Letter,  // 8.5 x 11 in = 215.9 x 279.4 mm
};

struct ExportOptions {
  std::string model;          // named in every file's metadata
  std::string settings;       // the options that made the plan (card, W, ...), one line, for the same
  ColourPreset colours = ColourPreset::Laser;
  DxfVersion dxf_version = DxfVersion::R12;  // R12 is read by every importer tried
  double preview_px_per_mm = 4;  // the PNG preview's resolution
  FoldStyleOptions folds;     // score, perforated or dashed folds, in every file
  Paper paper = Paper::Sheet; // the PDF's page; the sheet is centred on it
  // The PDF's creation date in seconds since 1970 (UTC), so that the same plan gives the same bytes
  // (the CLI takes SOURCE_DATE_EPOCH); none: the moment it is written.
  std::optional<std::int64_t> pdf_date_s;
};

/// The latest date a PDF can carry (9999-12-31T23:59:59Z), in seconds since 1970.
inline constexpr std::int64_t kLatestPdfDate_s = 253402300799;

struct LayerStyle {
  const char* name;       // CUT, MOUNTAIN, VALLEY, PERF_MOUNTAIN, PERF_VALLEY, OUTLINE
  int aci;                // AutoCAD colour index
  const char* rgb;        // the same colour for SVG and PDF, #rrggbb
};

/// The layer of a line kind under a colour preset (score style: folds on MOUNTAIN and VALLEY).
LayerStyle layer_style(LineKind kind, ColourPreset preset);

/// A drawn layer's name and colour. Perforations are magenta (PERF_MOUNTAIN, ACI 6) and cyan
/// (PERF_VALLEY, ACI 4) under both presets: colours neither preset uses, so a laser's cut settings
/// can go to them apart from the scores.
LayerStyle layer_style(Layer layer, ColourPreset preset);

struct PageSize {
  double width_mm = 0;
  double height_mm = 0;
};

/// The PDF page in mm for a sheet on a paper: the sheet itself for Paper::Sheet, else the paper
/// upright if the sheet fits so, else turned. \throws InputError naming ExportOptions::paper if the sheet fits
/// the paper neither way.
PageSize pdf_page(const Sheet& sheet, Paper paper);

/// One line for every file's metadata: the model, the units and plan axes, the sheet, the settings
/// and the fold style, such as "origamic plan of house.obj; units mm (X along the main fold, ...); ...".
std::string plan_description(const Plan& plan, const ExportOptions& options);

/// Checks every export option before any work: the fold style (check_fold_style), that the sheet
/// fits the paper and that the PDF date is one (0 to kLatestPdfDate_s). \throws InputError naming the
/// option.
void check_export_options(const ExportOptions& options, const Sheet& sheet);

/// The plan as ASCII DXF, written by dxflib: 999 comment lines naming the model, units, settings
/// and fold style first; $INSUNITS = 4 (mm) and $MEASUREMENT = 1; layers in kLayerOrder (scores
/// and perforations first, the outline last), only those used; every entity with its layer and
/// explicit colour; one polyline per chain. Perforations and the dashes of dashed folds are
/// separate LINE entities: real segments look the same in every program, whereas a linetype is
/// drawn only where linetypes are implemented, at that program's line-type scale.
/// Coordinates carry 16 decimals. \throws OutputError if dxflib cannot write its temporary file.
std::string plan_dxf(const Plan& plan, const ExportOptions& options);

/// The plan's lines (folds scored) as plan_dxf writes them and `origamic validate` reads them back:
/// Y up from the sheet's lower edge (plan Y plus half the sheet's height, in the file's doubles), a
/// point the file writes as the one before it left out, a line left with one point dropped. Points
/// a rounding apart in the plan (a fold on h - d and a support's corner on the pixel lattice,
/// 7e-15 mm apart) are one point there.
std::vector<PlanPolyline> plan_dxf_lines(const Plan& plan);

/// The plan as SVG in mm (width/height in mm, viewBox in mm, no transforms; SVG y = half the sheet
/// height - plan Y), <title>, <desc> and Dublin Core <metadata>, one Inkscape layer group per used
/// layer, hairline strokes, 6 decimals. Dashed folds stay one polyline each with their fitted
/// stroke-dasharray; perforations are one two-point polyline per cut.
std::string plan_svg(const Plan& plan, const ExportOptions& options);

/// A PNG picture of the plan in the seed's style (§4.6 figures): cuts red, folds green (mountain
/// dash-dot and valley dashed under the score and dashed styles, the perforation cuts under the
/// perforated style), on white, at preview_px_per_mm, with tEXt chunks (title, description,
/// software) and pHYs set to the resolution. \throws OutputError.
std::string plan_png(const Plan& plan, const ExportOptions& options);

/// A chord across a face where it is narrower than W, from side to side (plan mm, Y up from the
/// main fold), as the plan's analysis reports it.
struct NarrowChord {
  PlanPoint from, to;
};

/// plan_png's picture with each chord over it in blue, three pixels wide, inside a blue square of
/// 11 pixels (a chord a hundredth of a millimetre long shows at a glance): RGB bytes, row 0 at the
/// top, ceil(sheet width x preview_px_per_mm) by ceil(height x it). \throws OutputError.
std::vector<std::uint8_t> narrow_places_rgb(const Plan& plan, const ExportOptions& options,
                                            std::span<const NarrowChord> chords);

/// narrow_places_rgb as a PNG, for `--dump-maps` (narrow.png). \throws OutputError.
std::string narrow_places_png(const Plan& plan, const ExportOptions& options, std::span<const NarrowChord> chords);

/// The plan as a print-ready PDF at exactly 1:1 (1 pt = 25.4/72 mm), drawn by cairo: the page is
/// pdf_page(sheet, paper) with the sheet centred on it, 0.1 mm lines in the layer colours and the
/// fold style, a legend (line samples, a 10 mm scale bar labelled "10 mm") and a caption (model,
/// settings, fold style), placed clear of the plan: in the paper's margin if it has room, else in
/// the first sheet corner whose box crosses no plan line, else on a second page. Title, subject,
/// keywords and creator are set as PDF metadata. \throws InputError if the sheet does not fit the
/// paper, OutputError if cairo fails.
std::string plan_pdf(const Plan& plan, const ExportOptions& options);

/// The plan's four files, rendered in parallel (each is a pure function of the plan): `base` + .dxf,
/// .svg, .png and .pdf, in that order, not yet written.
std::vector<OutputFile> plan_files(const Plan& plan, const ExportOptions& options, const std::string& base);

}  // namespace origamic
