// SPDX-License-Identifier: GPL-3.0-or-later
// The origamic command: parses options, calls the library, reports. No algorithm lives here.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <numeric>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "origamic/design.hpp"
#include "origamic/error.hpp"
#include "origamic/fold3d.hpp"
#include "origamic/output.hpp"
#include "origamic/plan_analysis.hpp"
#include "origamic/plan_dxf_reader.hpp"
#include "origamic/plan_export.hpp"
#include "origamic/popup_files.hpp"
#include "origamic/raster_images.hpp"
#include "origamic/report.hpp"
#include "origamic/version.hpp"

namespace {

using origamic::InputError;

// A whole decimal number, or nothing.
std::optional<double> parse_number(std::string_view text) {
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// "210x297" -> Sheet.
origamic::Sheet parse_card(const std::string& text) {
  const auto x = text.find_first_of("xX");
  const auto width = parse_number(std::string_view(text).substr(0, x));
  const auto height = x == std::string::npos ? std::nullopt : parse_number(std::string_view(text).substr(x + 1));
  if (!width || !height) throw InputError("--card: expected WIDTHxHEIGHT in mm, such as 210x297, not '" + text + "'");
  return {*width, *height};
}

// "X,H,D" -> OA offset in mm.
glm::dvec3 parse_offset(const std::string& text) {
  glm::dvec3 v;
  std::string_view rest = text;
  for (int k = 0; k < 3; ++k) {
    const auto comma = k < 2 ? rest.find(',') : std::string_view::npos;
    const auto value = parse_number(rest.substr(0, comma));
    if (!value || (k < 2 && comma == std::string_view::npos))
      throw InputError("--offset: expected X,H,D in mm, such as 105,0,0, not '" + text + "'");
    v[k] = *value;
    rest = k < 2 ? rest.substr(comma + 1) : rest;
  }
  return v;
}

// The model's name without folders and extensions: "dragon.ply.gz" -> "dragon".
std::string model_name(const std::filesystem::path& file) {
  std::filesystem::path name = file.filename();
  if (name.extension() == ".gz" || name.extension() == ".GZ") name = name.stem();
  return name.stem().string();
}

struct DesignArgs {
  std::string model;
  std::string card = "210x297";
  std::string up = "y";
  double rotate_deg = origamic::PlacementOptions{}.rotate_deg;
  std::optional<double> scale;
  std::string offset;
  double margin_mm = origamic::PlacementOptions{}.margin_mm;
  double px_per_mm = origamic::RasterOptions{}.px_per_mm;
  double min_strip_mm = origamic::SliceOptions{}.min_strip_mm;
  std::string out_dir;
  std::string maps_dir;
  bool strict = false;
  bool no_supports = false;
  bool allow_dangling = false;
  bool allow_narrow = false;
  std::uint32_t seed = origamic::SupportOptions{}.seed;
  int orders = origamic::SupportOptions{}.orders;
  std::string colours = "laser";
  std::string dxf = "r12";
};

// Fabrication options of every plan file (issue 6, for makers).
struct FabricationArgs {
  std::string fold_style = "score";
  std::string perf = "1,1";
  double fold_inset_mm = origamic::FoldStyleOptions{}.inset_mm;
  std::string paper = "sheet";
};

void add_fabrication_options(CLI::App& design, FabricationArgs& args) {
  design.add_option("--fold-style", args.fold_style,
                    "folds as score (solid lines on MOUNTAIN/VALLEY), perforated (short cuts on "
                    "PERF_MOUNTAIN/PERF_VALLEY) or dashed (printed: mountain dash-dot, valley dashed)")
      ->check(CLI::IsMember({"score", "perforated", "dashed"}))
      ->capture_default_str();
  design.add_option("--perf", args.perf, "perforated folds: CUT,GAP lengths in mm")->capture_default_str();
  design.add_option("--fold-inset", args.fold_inset_mm, "perforations keep this far from every cut, mm")
      ->capture_default_str();
  design.add_option("--paper", args.paper, "PDF page: sheet (the sheet itself), a4 or letter (the sheet centred)")
      ->check(CLI::IsMember({"sheet", "a4", "letter"}))
      ->capture_default_str();
}

// "1,1" -> perforation cut and gap in mm.
void parse_perf(const std::string& text, origamic::FoldStyleOptions& folds) {
  const auto comma = text.find(',');
  const auto cut = parse_number(std::string_view(text).substr(0, comma));
  const auto gap = comma == std::string::npos ? std::nullopt : parse_number(std::string_view(text).substr(comma + 1));
  if (!cut || !gap) throw InputError("--perf: expected CUT,GAP in mm, such as 1,1, not '" + text + "'");
  folds.perf_cut_mm = *cut;
  folds.perf_gap_mm = *gap;
}

// The export options, checked against the sheet before any work is done.
origamic::ExportOptions export_options(const DesignArgs& args, const FabricationArgs& fabrication,
                                       const origamic::DesignOptions& design) {
  const origamic::Sheet& sheet = design.sheet;
  origamic::ExportOptions exports;
  exports.model = std::filesystem::path(args.model).filename().string();
  exports.settings = origamic::settings_text(design);
  exports.colours = args.colours == "craft" ? origamic::ColourPreset::Craft : origamic::ColourPreset::Laser;
  exports.dxf_version = args.dxf == "r2000" ? origamic::DxfVersion::R2000 : origamic::DxfVersion::R12;
  exports.folds.style = fabrication.fold_style == "perforated" ? origamic::FoldStyle::Perforated
                        : fabrication.fold_style == "dashed"   ? origamic::FoldStyle::Dashed
                                                               : origamic::FoldStyle::Score;
  parse_perf(fabrication.perf, exports.folds);
  exports.folds.inset_mm = fabrication.fold_inset_mm;
  exports.paper = fabrication.paper == "a4"       ? origamic::Paper::A4
                  : fabrication.paper == "letter" ? origamic::Paper::Letter
                                                  : origamic::Paper::Sheet;
  // The reproducible-builds convention: SOURCE_DATE_EPOCH dates the PDF, so a plan gives the same bytes.
  if (const char* date = std::getenv("SOURCE_DATE_EPOCH"); date && *date) {
    const std::string text = date;
    std::int64_t seconds = 0;
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), seconds);
    if (error != std::errc{} || end != text.data() + text.size() || seconds < 0 || seconds > origamic::kLatestPdfDate_s)
      throw InputError(
          "SOURCE_DATE_EPOCH: expected whole seconds since 1970 up to the year 9999, such as 1700000000, "
          "not '" +
          text + "'");
    exports.pdf_date_s = seconds;
  }
  origamic::check_export_options(exports, sheet);
  return exports;
}

// The 3D pop-up and its pictures (origamic/popup_files.hpp), written into --out.
struct PopupArgs {
  bool fold_model = false;
  bool renders = false;
  std::string render_size = "1200x900";
  double thickness_mm = 0;
};

void add_popup_options(CLI::App& design, PopupArgs& args) {
  design.add_flag(
      "--fold-model", args.fold_model,
      "also write the pop-up folded at 90 degrees as a mesh: MODEL_popup.obj and its materials MODEL_popup.mtl");
  design.add_flag("--renders", args.renders,
                  "also write pictures: the pop-up (MODEL_popup.png), the model from the same viewpoint "
                  "(MODEL_model.png) and the card opening (MODEL_opening.gif)");
  design.add_option("--render-size", args.render_size, "size of the pictures in pixels, WIDTHxHEIGHT; the GIF is half")
      ->capture_default_str();
  design
      .add_option("--thickness", args.thickness_mm, "paper thickness in mm for --fold-model and --renders (0: sheets)")
      ->capture_default_str();
}

origamic::PopupFileOptions popup_file_options(const PopupArgs& args, const std::string& out_dir) {
  origamic::PopupFileOptions options;
  options.fold_model = args.fold_model;
  options.renders = args.renders;
  options.thickness_mm = args.thickness_mm;
  const auto x = args.render_size.find_first_of("xX");
  const auto width = parse_number(std::string_view(args.render_size).substr(0, x));
  const auto height =
      x == std::string::npos ? std::nullopt : parse_number(std::string_view(args.render_size).substr(x + 1));
  if (!width || !height || *width != std::floor(*width) || *height != std::floor(*height) || std::abs(*width) > 1e6 ||
      std::abs(*height) > 1e6)
    throw InputError("--render-size: expected WIDTHxHEIGHT in whole pixels, such as 1200x900, not '" +
                     args.render_size + "'");
  options.render.width_px = static_cast<int>(*width);
  options.render.height_px = static_cast<int>(*height);
  if ((args.fold_model || args.renders) && out_dir.empty())
    throw InputError(std::string(args.fold_model ? "--fold-model" : "--renders") + ": needs --out DIR to write into");
  origamic::check_popup_file_options(options);
  return options;
}

void add_design_options(CLI::App& design, DesignArgs& args) {
  design.add_option("MODEL", args.model, "3D model: .obj, .stl, .ply or .off, optionally .gz")->required();
  design.add_option("--card", args.card, "flat sheet WIDTHxHEIGHT in mm; the main fold halves the height")
      ->capture_default_str();
  design.add_option("--up", args.up, "model axis pointing up: y (viewer at +z) or z (viewer at -y)")
      ->check(CLI::IsMember({"y", "z"}))
      ->capture_default_str();
  design.add_option("--rotate", args.rotate_deg, "turn the model about its up axis, degrees counter-clockwise")
      ->capture_default_str();
  design.add_option("--scale", args.scale, "mm per model unit (default: fit the sheet)");
  design.add_option("--offset", args.offset, "X,H,D in mm of the model's origin (default: on the floor, "
                                             "against the back plane, centred)");
  design.add_option("--margin", args.margin_mm, "auto-fit keeps the plan this far inside the sheet, mm")
      ->capture_default_str();
  design.add_option("--px-per-mm", args.px_per_mm, "raster resolution, pixels per mm")->capture_default_str();
  design.add_option("--min-strip", args.min_strip_mm, "W: minimum strip width in mm")->capture_default_str();
  design.add_option("--out", args.out_dir,
                    "write the plan (MODEL.dxf, MODEL.svg, MODEL.png, MODEL.pdf) and the report (MODEL.json) into "
                    "this folder");
  design.add_flag("--strict", args.strict,
                  "exit with status 3 when the plan is invalid (after writing it): it does not stand, or it has "
                  "places narrower than W and no --allow-narrow");
  design.add_flag("--no-supports", args.no_supports, "leave out the supports (seed §4.4): the plan as sliced");
  design.add_flag("--allow-dangling", args.allow_dangling,
                  "keep dangling faces (windows, balconies) instead of supporting them; the report lists them");
  design.add_flag("--allow-narrow", args.allow_narrow,
                  "a plan with places narrower than W (--min-strip) is valid all the same; the report lists them");
  design.add_option("--seed", args.seed, "the order in which invalid faces choose their supports")
      ->capture_default_str();
  design
      .add_option("--orders", args.orders,
                  "face orders tried, one after another from the seed, until the plan stands with under 15% of the "
                  "model cut out; the best is kept")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  design.add_option("--colours", args.colours,
                    "layer colours: laser (cut black, mountain red, valley blue, outline green) or craft (cut "
                    "blue, mountain green, valley red, outline black)")
      ->check(CLI::IsMember({"laser", "craft"}))
      ->capture_default_str();
  design.add_option("--dxf", args.dxf, "DXF flavour: r12 (read by everything) or r2000 (LWPOLYLINE)")
      ->check(CLI::IsMember({"r12", "r2000"}))
      ->capture_default_str();
  design.add_option(
      "--dump-maps", args.maps_dir,
      "write the maps (D, F, T, N, hit kind, segments S, subsegments SS, faces, likeness error E), a plan preview "
      "and the plan's places narrower than W (narrow) as PNGs here");
}

std::string one_line(std::string_view message);

// The stage a run is in, on one line of a terminal (stderr, and only when it is a terminal: a
// script or a log gets the summary alone); the line is cleared when the run ends, however it ends.
class Progress {
 public:
  Progress() : shown_(::isatty(STDERR_FILENO) == 1) {}
  ~Progress() { clear(); }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  void show(std::string_view stage) {
    if (!shown_) return;
    std::fprintf(stderr, "\r\033[Korigamic: %s...", one_line(stage).c_str());
    on_screen_ = true;
  }
  void clear() {
    if (on_screen_) std::fputs("\r\033[K", stderr);
    on_screen_ = false;
  }

 private:
  bool shown_;
  bool on_screen_ = false;
};

// The library names an option at fault by its field (InputError::field); the command line by its
// flag. Fields joined by '/' are at fault together; each becomes its flag, once.
std::string flags_of(const std::string& fields) {
  static const std::map<std::string, std::string> flag = {
      {"Sheet", "--card"},
      {"PlacementOptions::rotate_deg", "--rotate"},
      {"PlacementOptions::scale", "--scale"},
      {"PlacementOptions::offset_mm", "--offset"},
      {"PlacementOptions::margin_mm", "--margin"},
      {"RasterOptions::px_per_mm", "--px-per-mm"},
      {"SliceOptions::min_strip_mm", "--min-strip"},
      {"AnalysisOptions::min_strip_mm", "--min-strip"},
      {"AnalysisOptions::tolerance_mm", "--tolerance"},
      {"FoldStyleOptions::perf_cut_mm", "--perf"},
      {"FoldStyleOptions::perf_gap_mm", "--perf"},
      {"FoldStyleOptions::inset_mm", "--fold-inset"},
      {"ExportOptions::paper", "--paper"},
      {"ExportOptions::pdf_date_s", "SOURCE_DATE_EPOCH"},
      {"FoldOptions::angle_deg", "--angle"},
      {"FoldOptions::thickness_mm", "--thickness"},
      {"RenderOptions::width_px", "--render-size"},
      {"RenderOptions::height_px", "--render-size"},
  };
  std::string flags;
  for (std::size_t at = 0; at <= fields.size();) {
    const std::size_t end = std::min(fields.find('/', at), fields.size());
    const std::string field = fields.substr(at, end - at);
    const auto known = flag.find(field);
    const std::string name = known != flag.end() ? known->second : field;  // a field no flag sets
    if (flags != name && !flags.ends_with("/" + name)) flags += (flags.empty() ? "" : "/") + name;
    at = end + 1;
  }
  return flags;
}

// An InputError as the command line says it: the flag for the library's field, the plan's file for
// its lines.
std::string cli_message(const InputError& e, const std::string& plan_file = {}) {
  if (e.field.empty()) return e.what();
  if (e.field == "lines" && !plan_file.empty()) return plan_file + ": " + e.problem;
  return flags_of(e.field) + ": " + e.problem;
}

int run_design(const DesignArgs& args, const FabricationArgs& fabrication, const PopupArgs& popup_args) {
  const origamic::PopupFileOptions popup_options = popup_file_options(popup_args, args.out_dir);
  origamic::DesignOptions options;
  options.sheet = parse_card(args.card);
  options.placement.up = args.up == "z" ? origamic::UpAxis::Z : origamic::UpAxis::Y;
  options.placement.rotate_deg = args.rotate_deg;
  options.placement.scale = args.scale;
  if (!args.offset.empty()) options.placement.offset_mm = parse_offset(args.offset);
  options.placement.margin_mm = args.margin_mm;
  options.raster.px_per_mm = args.px_per_mm;
  options.slice.min_strip_mm = args.min_strip_mm;
  options.supports.enabled = !args.no_supports;
  options.supports.allow_dangling = args.allow_dangling;
  options.allow_narrow = args.allow_narrow;
  options.supports.seed = args.seed;
  options.supports.orders = args.orders;
  const origamic::ExportOptions exports = export_options(args, fabrication, options);

  // A folder that cannot be made is reported before any work and before any file is written.
  for (const std::string& dir : {args.out_dir, args.maps_dir})
    if (!dir.empty() && std::filesystem::exists(dir) && !std::filesystem::is_directory(dir))
      throw origamic::OutputError(dir + ": cannot create folder (a file is in the way)");

  Progress progress;
  options.on_stage = [&](std::string_view stage) { progress.show(stage); };
  // Pictures of the model need its mesh again: then it is read here, once, and designed from.
  std::optional<origamic::LoadedMesh> model;
  origamic::DesignResult result;
  if (popup_options.renders && !args.out_dir.empty()) {
    progress.show("reading the model");
    const auto start = std::chrono::steady_clock::now();
    model = origamic::load_mesh(args.model, options.load);
    const double load_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    result = origamic::design(*model, options, args.model);
    result.times.insert(result.times.begin(), {"load", load_ms});
  } else {
    result = origamic::design(args.model, options);
  }
  progress.show("writing the files");
  // Every file is rendered first, then all are written together: a failure leaves none behind.
  std::vector<origamic::OutputFile> files;
  std::string written;
  if (!args.out_dir.empty()) {
    const std::string base = (std::filesystem::path(args.out_dir) / model_name(args.model)).string();
    files.push_back({base + ".json", origamic::report_json(result, options)});
    for (auto& file : origamic::plan_files(result.plan, exports, base)) files.push_back(std::move(file));
    written += "plan: " + base + ".{dxf,svg,png,pdf}\nreport: " + base + ".json\n";
    static const origamic::TriangleMesh no_model;  // both lvalues: the model is not copied
    for (auto& file : origamic::popup_files(result, options, base, popup_options, model ? model->mesh : no_model)) {
      written += "3D: " + file.path.string() + "\n";
      files.push_back(std::move(file));
    }
  }
  if (!args.maps_dir.empty()) {
    for (auto& file : origamic::raster_image_files(result.maps, args.maps_dir)) files.push_back(std::move(file));
    for (auto& file :
         origamic::slice_image_files(result.maps, result.segmentation, result.raster_plan, result.card, args.maps_dir))
      files.push_back(std::move(file));
    std::vector<origamic::NarrowChord> narrow;
    for (const origamic::PlanProblem& place : result.narrow_strips) narrow.push_back({place.from, place.to});
    const std::filesystem::path narrow_png = std::filesystem::path(args.maps_dir) / "narrow.png";
    files.push_back({narrow_png, origamic::narrow_places_png(result.plan, exports, narrow)});
    written += "maps: " + args.maps_dir + "/{D,F,T,N,kind,S,SS,faces,E,plan_preview,narrow}.png\n";
  }
  origamic::write_files(files);
  progress.clear();
  std::printf("%s\n%s", origamic::summary_line(result).c_str(), written.c_str());
  return args.strict && !origamic::design_valid(result) ? 3 : 0;
}

struct ValidateArgs {
  std::string plan;
  double min_strip_mm = origamic::AnalysisOptions{}.min_strip_mm;
  double tolerance_mm = origamic::AnalysisOptions{}.tolerance_mm;
  bool json = false;
  origamic::LayerNames layers;
};

// Folds drawn as perforation cuts are read as the folds they stand for, run on to the cuts.
void add_perforation_layers(CLI::App& command, origamic::LayerNames& layers) {
  command
      .add_option("--perf-mountain-layer", layers.perforated_mountain, "layer of mountain folds drawn as perforations")
      ->capture_default_str();
  command.add_option("--perf-valley-layer", layers.perforated_valley, "layer of valley folds drawn as perforations")
      ->capture_default_str();
}

void add_validate_options(CLI::App& validate, ValidateArgs& args) {
  validate.add_option("PLAN", args.plan, "plan as ASCII DXF: cuts, mountain and valley folds on their layers, in mm, "
                                         "Y = 0 the main fold")
      ->required();
  validate
      .add_option("--min-strip", args.min_strip_mm, "W: report faces narrower than this along X or Y, mm (0: no check)")
      ->capture_default_str();
  validate.add_option("--tolerance", args.tolerance_mm,
                      "a fold and the line Y = h - d of its faces agree within this, mm (absorbs the rounding of "
                      "coordinates in the file)")
      ->capture_default_str();
  validate.add_flag("--json", args.json, "print the report as JSON instead of text");
  validate.add_option("--cut-layer", args.layers.cut, "layer of the cuts")->capture_default_str();
  validate.add_option("--mountain-layer", args.layers.mountain, "layer of the mountain folds")->capture_default_str();
  validate.add_option("--valley-layer", args.layers.valley, "layer of the valley folds")->capture_default_str();
  validate.add_option("--outline-layer", args.layers.outline,
                      "layer of the sheet's edge (without one, the sheet is the bounding box of every line)")
      ->capture_default_str();
  add_perforation_layers(validate, args.layers);
}

int run_validate(const ValidateArgs& args) {
  const origamic::DxfDrawing drawing = origamic::read_dxf_drawing(args.plan, args.layers);
  origamic::AnalysisOptions options;
  options.min_strip_mm = args.min_strip_mm;
  options.tolerance_mm = args.tolerance_mm;
  options.unit = drawing.unit;
  origamic::PlanAnalysis analysis;
  try {
    analysis = origamic::analyze_plan(drawing.lines, options);
  } catch (const InputError& e) {
    throw InputError(cli_message(e, args.plan));  // the file for problems of the plan's lines
  }
  if (args.json) {
    std::fputs(origamic::analysis_json(analysis, args.plan).c_str(), stdout);
  } else {
    std::printf("%s\n", origamic::analysis_summary_line(analysis).c_str());
    if (analysis.main_fold_Y != 0 && !analysis.problems.empty())
      std::printf("note: places are given with Y up from the main fold, which the drawing has at Y = %g\n",
                  analysis.main_fold_Y);
    for (const origamic::PlanProblem& p : analysis.problems)
      std::printf("%s: %s: %s\n", origamic::is_error(p.kind) ? "error" : "warning",
                  std::string(origamic::to_string(p.kind)).c_str(), p.message.c_str());
  }
  return analysis.valid() ? 0 : 3;
}

// `origamic fold PLAN.dxf`: any plan, read and placed as `validate` does, folded at an angle.
struct FoldArgs {
  std::string plan;
  double angle_deg = 90;
  double thickness_mm = 0;
  std::string out;
  origamic::LayerNames layers;
};

void add_fold_options(CLI::App& fold, FoldArgs& args) {
  fold.add_option("PLAN", args.plan, "plan as ASCII DXF (cuts, mountain and valley folds on their layers, in mm)")
      ->required();
  fold.add_option("--angle", args.angle_deg, "opening angle in degrees: 0 closed, 90 standing, 180 flat")
      ->capture_default_str();
  fold.add_option("--thickness", args.thickness_mm, "paper thickness in mm (0: zero-thickness sheets)")
      ->capture_default_str();
  fold.add_option("-o,--out", args.out, "the folded pop-up as a mesh: .obj (with its .mtl), .ply, .gltf or .glb")
      ->required();
  fold.add_option("--cut-layer", args.layers.cut, "layer of the cuts")->capture_default_str();
  fold.add_option("--mountain-layer", args.layers.mountain, "layer of the mountain folds")->capture_default_str();
  fold.add_option("--valley-layer", args.layers.valley, "layer of the valley folds")->capture_default_str();
  add_perforation_layers(fold, args.layers);
}

int run_fold(const FoldArgs& args) {
  const std::string extension = std::filesystem::path(args.out).extension().string();
  const std::map<std::string, origamic::MeshFormat> formats = {{".obj", origamic::MeshFormat::Obj},
                                                               {".ply", origamic::MeshFormat::Ply},
                                                               {".gltf", origamic::MeshFormat::Gltf},
                                                               {".glb", origamic::MeshFormat::Glb}};
  const auto format = formats.find(extension);
  if (format == formats.end())
    throw InputError("--out: expected a .obj, .ply, .gltf or .glb file, not '" + args.out + "'");
  const origamic::DxfDrawing drawing = origamic::read_dxf_drawing(args.plan, args.layers);
  origamic::AnalysisOptions options;
  options.unit = drawing.unit;
  origamic::PlanAnalysis analysis;
  try {
    analysis = origamic::analyze_plan(drawing.lines, options);
  } catch (const InputError& e) {
    throw InputError(cli_message(e, args.plan));
  }
  const origamic::PlanBox& box = analysis.sheet;
  const origamic::Sheet sheet{box.max_X - box.min_X, 2 * std::max(box.max_Y, -box.min_Y)};
  const origamic::FoldedPopup popup =
      origamic::fold_popup(analysis.regions, sheet, {.angle_deg = args.angle_deg, .thickness_mm = args.thickness_mm});
  origamic::write_files(origamic::folded_mesh_files(popup, args.out, format->second));
  std::printf("%s\nfolded at %g degrees: %s (%d faces not reached by any fold left out)\n",
              origamic::analysis_summary_line(analysis).c_str(), args.angle_deg, args.out.c_str(),
              popup.unplaced_regions);
  return 0;
}

}  // namespace

namespace {

// An error as one line of plain text: a name or layer read from a file may hold a newline, a tab or
// a terminal escape, which are shown as \xNN instead.
std::string one_line(std::string_view message) {
  std::string line;
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      line += escaped;
    } else {
      line += c;
    }
  }
  return line;
}

void print_error(std::string_view prefix, std::string_view message, std::string_view suffix = "") {
  std::fprintf(stderr, "origamic: %s%s%s\n", std::string(prefix).c_str(), one_line(message).c_str(),
               std::string(suffix).c_str());
}

// Edits (insertions, deletions, substitutions) between two words: the nearest name is suggested.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  std::iota(row.begin(), row.end(), std::size_t{0});
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0]++;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// "; did you mean X?" for the nearest of `names` within a third of the word's length, or "".
std::string suggestion(std::string_view word, const std::vector<std::string>& names) {
  const std::string* best = nullptr;
  std::size_t fewest = word.size() / 3 + 1;
  for (const std::string& name : names)
    if (const std::size_t d = edit_distance(word, name); d < fewest) fewest = d, best = &name;
  return best ? "; did you mean " + *best + "?" : "";
}

// A parse error in words a user can act on, naming the option and the help that lists it.
std::string parse_problem(const CLI::ParseError& e, const CLI::App& app, int argc, char** argv) {
  const CLI::App* used = nullptr;
  for (const CLI::App* sub : app.get_subcommands({})) if (sub->parsed()) used = sub;
  const std::string help = used ? " (see origamic " + used->get_name() + " --help)" : " (see origamic --help)";
  const std::string message = e.what();
  if (dynamic_cast<const CLI::ExtrasError*>(&e) && used) {
    std::vector<std::string> names;
    for (const CLI::Option* option : used->get_options())
      for (const std::string& long_name : option->get_lnames()) names.push_back("--" + long_name);
    for (int i = 2; i < argc; ++i) {
      const std::string_view word = argv[i];
      if (word.rfind("--", 0) != 0) continue;
      const std::string name(word.substr(0, word.find('=')));
      if (std::ranges::find(names, name) == names.end())
        return name + ": no such option of origamic " + used->get_name() + suggestion(name, names) + help;
    }
  }
  // CLI11 says "Could not convert: --angle = abc".
  if (const auto at = message.find("Could not convert: "); at != std::string::npos) {
    const std::string rest = message.substr(at + 19);
    if (const auto equals = rest.find(" = "); equals != std::string::npos)
      return rest.substr(0, equals) + ": '" + rest.substr(equals + 3) + "' is not a number" + help;
  }
  return message + help;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"origamic: Origamic Architecture pop-up plans from 3D models", "origamic"};
  app.set_version_flag("--version,-V", std::string("origamic ") + origamic::version);
  app.require_subcommand(1);
  DesignArgs design_args;
  CLI::App* design = app.add_subcommand("design", "design a pop-up plan for a 3D model");
  add_design_options(*design, design_args);
  FabricationArgs fabrication_args;
  add_fabrication_options(*design, fabrication_args);
  PopupArgs popup_args;
  add_popup_options(*design, popup_args);
  ValidateArgs validate_args;
  CLI::App* validate = app.add_subcommand("validate", "check a plan (DXF), made by origamic or by hand: faces, folds, "
                                                      "validity; exit 0 valid, 3 invalid");
  add_validate_options(*validate, validate_args);
  FoldArgs fold_args;
  CLI::App* fold = app.add_subcommand("fold", "fold a plan (DXF) into its 3D pop-up at an opening angle: a mesh");
  add_fold_options(*fold, fold_args);

  // The first word names a command; `help` asks for the help, as --help does.
  if (argc >= 2 && argv[1][0] != '-') {
    const std::string word = argv[1];
    const std::vector<std::string> commands = {"design", "validate", "fold"};
    if (word == "help") {
      std::fputs(app.help().c_str(), stdout);
      return 0;
    }
    if (std::ranges::find(commands, word) == commands.end()) {
      print_error("", "unknown command '" + word + "'" + suggestion(word, commands),
                  " (the commands are design, validate and fold; see origamic --help)");
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    print_error("", parse_problem(e, app, argc, argv));
    return 2;
  }

  try {
    if (*validate) return run_validate(validate_args);
    if (*fold) return run_fold(fold_args);
    if (*design) return run_design(design_args, fabrication_args, popup_args);
    return 2;  // CLI11 requires one subcommand
  } catch (const origamic::InputError& e) {
    print_error("", cli_message(e));
    return 2;
  } catch (const origamic::OutputError& e) {
    print_error("", e.what());
    return 2;
  } catch (const std::filesystem::filesystem_error& e) {
    print_error("", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "origamic: out of memory\n");
    return 2;
  } catch (const std::exception& e) {
    print_error("internal error: ", e.what());
    return 2;
  }
}
