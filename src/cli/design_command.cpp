// SPDX-License-Identifier: GPL-3.0-or-later
// `origamic design`: a model in, the plan's files, its report and its pictures out (commands.hpp).
#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "commands.hpp"
#include "origamic/output.hpp"
#include "origamic/plan_export.hpp"
#include "origamic/popup_files.hpp"
#include "origamic/raster_images.hpp"
#include "origamic/report.hpp"

namespace origamic::cli {
namespace {

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

}  // namespace

void add_fabrication_options(CLI::App& design, FabricationArgs& args) {
  design
      .add_option("--fold-style", args.fold_style,
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
  design.add_option("--offset", args.offset,
                    "X,H,D in mm of the model's origin (default: on the floor, "
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
  design.add_flag("--merge-thin-slices", args.merge_thin_slices,
                  "also merge each slice narrower than W everywhere (a crescent where a curved surface turns "
                  "sideways) into its neighbour: about half as many faces narrower than W, such slopes in coarser "
                  "steps");
  design.add_option("--seed", args.seed, "the order in which invalid faces choose their supports")
      ->capture_default_str();
  design
      .add_option("--orders", args.orders,
                  "face orders tried, one after another from the seed, until the plan stands with under 15% of the "
                  "model cut out; the best is kept")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  design
      .add_option("--colours", args.colours,
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
  options.slice.merge_thin_slices = args.merge_thin_slices;
  options.supports.enabled = !args.no_supports;
  options.supports.allow_dangling = args.allow_dangling;
  options.allow_narrow = args.allow_narrow;
  options.keep_normals = !args.maps_dir.empty();  // N.png
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

}  // namespace origamic::cli
