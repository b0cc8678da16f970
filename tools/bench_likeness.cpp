// SPDX-License-Identifier: GPL-3.0-or-later
// Likeness benchmark: bench_likeness MODELS_DIR OUT_DIR [--only NAME]... [--seed N] [--min-strip W]
// [--where yes] [--merge-thin-slices yes]
// Designs every model of MODELS_DIR (MANIFEST.tsv's files at their up axis, then seedlike/*.stl up
// z) at the default options, and measures each finished plan as the user gets it: its DXF written,
// read back and analysed by `origamic validate`'s reader, its regions seen along the 45-degree view
// against the model's own depth (likeness.hpp). Prints per model the finished p95 and mean error
// (in W), the sliced p95, coverage, support and cut-out shares, faces, folds, whether it stands,
// its places narrower than W (read back, as `origamic validate --min-strip W` counts them), the
// time of the design and, of those places, the ones between two parallel folds less than W apart
// (PlanProblem::folds_apart_mm), then the means, and the chords narrower than W across all the
// places (PlanProblem::narrow_chords), which falls where a face loses a notch but stays narrow
// elsewhere, and the faces narrower than W everywhere (`thin`: no disc W across fits in them, to a
// pixel, widest_discs_px: slivers and strips, not faces narrow only at a tip or a notch);
// writes OUT_DIR/contact_sheet.png (per model: the model, the pop-up, the plan) and each model's
// pictures and DXF under OUT_DIR/models/.
#include <cairo.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "origamic/design.hpp"
#include "origamic/error.hpp"
#include "origamic/fold3d.hpp"
#include "origamic/likeness.hpp"
#include "origamic/output.hpp"
#include "origamic/plan_analysis.hpp"
#include "origamic/plan_dxf_reader.hpp"
#include "origamic/plan_export.hpp"
#include "origamic/render.hpp"

namespace fs = std::filesystem;
using namespace origamic;

namespace {

struct Model {
  fs::path file;
  UpAxis up = UpAxis::Z;
};

std::vector<Model> models_in(const fs::path& dir) {
  std::vector<Model> models;
  std::ifstream manifest(dir / "MANIFEST.tsv");
  std::string line;
  std::vector<std::string> header;
  auto split = [](const std::string& text) {
    std::vector<std::string> cells;
    std::stringstream in(text);
    for (std::string cell; std::getline(in, cell, '\t');) cells.push_back(cell);
    return cells;
  };
  if (std::getline(manifest, line)) header = split(line);
  const auto up_column = std::ranges::find(header, "up_axis") - header.begin();
  while (std::getline(manifest, line)) {
    const std::vector<std::string> cells = split(line);
    if (cells.empty() || !fs::exists(dir / cells[0])) continue;
    const bool y = up_column < static_cast<long>(cells.size()) && cells[up_column] == "y";
    models.push_back({dir / cells[0], y ? UpAxis::Y : UpAxis::Z});
  }
  std::vector<fs::path> seedlike;
  if (fs::is_directory(dir / "seedlike"))
    for (const auto& entry : fs::directory_iterator(dir / "seedlike"))
      if (entry.path().extension() == ".stl") seedlike.push_back(entry.path());
  std::ranges::sort(seedlike);
  for (const fs::path& file : seedlike) models.push_back({file, UpAxis::Z});
  return models;
}

std::string name_of(const fs::path& file) {
  std::string name = file.filename().string();
  return file.parent_path().filename() == "seedlike" ? "seedlike/" + name : name;
}

struct Row {
  std::string name;
  Likeness finished, sliced, read_back;
  int faces = 0, folds = 0, supports = 0, removed = 0;
  bool stands = false, read_back_stands = false;  // as designed and as read back
  int narrow = 0;                                 // places narrower than W, read back
  int parallel = 0;                               // of them, between two parallel folds under W apart
  int chords = 0;                                 // the chords narrower than W across those places
  int thin = 0;  // faces (regions, read back) narrower than W everywhere: no disc W across fits, to a pixel
  double design_s = 0;
  // Where the card is more than 2 W off its model: shares of the model's pixels showing a face of
  // the model, a support, the back plane or floor, or a hole (the finished card, as designed).
  std::array<double, 4> far_off{};
  std::string error;  // the design failed
};

// A cairo surface of a rendered picture.
cairo_surface_t* surface_of(const Image& image) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_RGB24, image.width, image.height);
  cairo_surface_flush(s);
  unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  for (int r = 0; r < image.height; ++r)
    for (int c = 0; c < image.width; ++c) {
      const std::uint8_t* p = &image.rgb[3 * (static_cast<std::size_t>(r) * image.width + c)];
      auto* q = reinterpret_cast<std::uint32_t*>(data + r * stride) + c;
      *q = (std::uint32_t{p[0]} << 16) | (std::uint32_t{p[1]} << 8) | p[2];
    }
  cairo_surface_mark_dirty(s);
  return s;
}

struct PngReader {
  const std::string& bytes;
  std::size_t at = 0;
};

cairo_surface_t* surface_of_png(const std::string& bytes) {
  PngReader reader{bytes};
  return cairo_image_surface_create_from_png_stream(
      [](void* closure, unsigned char* data, unsigned int length) {
        auto* r = static_cast<PngReader*>(closure);
        if (r->at + length > r->bytes.size()) return CAIRO_STATUS_READ_ERROR;
        std::memcpy(data, r->bytes.data() + r->at, length);
        r->at += length;
        return CAIRO_STATUS_SUCCESS;
      },
      &reader);
}

// One cell of the contact sheet: the model, the pop-up and the plan, with the model's numbers.
struct Cell {
  std::string title, numbers;
  cairo_surface_t *model = nullptr, *popup = nullptr, *plan = nullptr;
};

constexpr int kPictureW = 320, kPictureH = 240, kPlanW = 170, kTextH = 34;

void draw_cell(cairo_t* cr, const Cell& cell, double x, double y) {
  const auto put = [&](cairo_surface_t* s, double at_x, double w, double h) {
    if (!s) return;
    const double sw = cairo_image_surface_get_width(s), sh = cairo_image_surface_get_height(s);
    const double scale = std::min(w / sw, h / sh);
    cairo_save(cr);
    cairo_translate(cr, at_x + (w - sw * scale) / 2, y + kTextH + (h - sh * scale) / 2);
    cairo_scale(cr, scale, scale);
    cairo_set_source_surface(cr, s, 0, 0);
    cairo_paint(cr);
    cairo_restore(cr);
  };
  put(cell.model, x, kPictureW, kPictureH);
  put(cell.popup, x + kPictureW, kPictureW, kPictureH);
  put(cell.plan, x + 2 * kPictureW, kPlanW, kPictureH);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, 13);
  cairo_move_to(cr, x + 6, y + 14);
  cairo_show_text(cr, cell.title.c_str());
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 11);
  cairo_move_to(cr, x + 6, y + 29);
  cairo_show_text(cr, cell.numbers.c_str());
}

void write_contact_sheet(const std::vector<Cell>& cells, const fs::path& file) {
  const int cell_w = 2 * kPictureW + kPlanW + 10, cell_h = kTextH + kPictureH + 8, per_row = 2;
  const int rows = static_cast<int>((cells.size() + per_row - 1) / per_row);
  cairo_surface_t* sheet = cairo_image_surface_create(CAIRO_FORMAT_RGB24, per_row * cell_w, std::max(1, rows * cell_h));
  cairo_t* cr = cairo_create(sheet);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  for (std::size_t i = 0; i < cells.size(); ++i)
    draw_cell(cr, cells[i], static_cast<double>(i % per_row) * cell_w, static_cast<double>(i / per_row) * cell_h);
  cairo_destroy(cr);
  cairo_surface_write_to_png(sheet, file.c_str());
  cairo_surface_destroy(sheet);
}

int fold_lines(const Plan& plan) {
  return static_cast<int>(std::ranges::count_if(
      plan.lines, [](const PlanPolyline& l) { return l.kind == LineKind::Mountain || l.kind == LineKind::Valley; }));
}

bool where_maps = false;  // --where: a picture per model of where the card is more than 2 W off

// Per plan pixel of the model: grey within 2 W; more than 2 W off on a model face red where the
// sliced plan was within 2 W there (the supports' doing), dark red where it was not; on a support
// blue, on the back plane or floor green, in a hole yellow. Off the model: white.
void write_where_map(const Model& model, const DesignOptions& options, const DesignResult& result,
                     const Grid<float>& error, double far, const fs::path& file) {
  DesignOptions unsupported = options;
  unsupported.supports.enabled = false;
  const DesignResult sliced = design(model.file, unsupported);
  const Grid<float> sliced_error = likeness_error_map(sliced.maps, sliced.card);
  Image image{error.cols, error.rows, std::vector<std::uint8_t>(3 * error.values.size(), 255), {}};
  for (std::size_t i = 0; i < error.values.size(); ++i) {
    std::array<std::uint8_t, 3> c = {255, 255, 255};
    if (error.values[i] >= 0 && !(error.values[i] > far)) c = {190, 190, 190};
    if (error.values[i] > far) switch (result.card.surface.values[i]) {
        case CardSurface::Model: c = sliced_error.values[i] > far ? std::array<std::uint8_t, 3>{120, 0, 0}
                                                                   : std::array<std::uint8_t, 3>{255, 0, 0}; break;
        case CardSurface::Support: c = {0, 60, 255}; break;
        case CardSurface::Hole: c = {240, 200, 0}; break;
        default: c = {0, 170, 0}; break;
      }
    std::copy(c.begin(), c.end(), image.rgb.begin() + static_cast<std::ptrdiff_t>(3 * i));
  }
  write_files({{file, image_png(image, file.stem().string())}});
}

Row measure(const Model& model, const DesignOptions& base, const fs::path& out, Cell& cell) {
  Row row;
  row.name = name_of(model.file);
  DesignOptions options = base;
  options.placement.up = model.up;
  const auto start = std::chrono::steady_clock::now();
  const DesignResult result = design(model.file, options);
  row.design_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  row.finished = result.likeness;
  row.sliced = result.sliced_likeness;
  row.faces = static_cast<int>(result.plan.faces.size()) - 2;
  row.folds = fold_lines(result.plan);
  row.supports = result.supports.supports;
  row.removed = result.plan.validity.removed;
  row.stands = plan_stands(result.plan, false);
  const Grid<float> error = likeness_error_map(result.maps, result.card);
  const double far = 2 * options.slice.min_strip_mm;
  for (std::size_t i = 0; i < error.values.size(); ++i) {
    if (!(error.values[i] > far)) continue;
    const CardSurface at = result.card.surface.values[i];
    const std::size_t kind = at == CardSurface::Model     ? 0
                             : at == CardSurface::Support ? 1
                             : at == CardSurface::Hole    ? 3
                                                          : 2;
    row.far_off[kind] += 1;
  }
  for (double& share : row.far_off) share /= std::max<std::int64_t>(1, result.likeness.model_pixels);

  // The plan as the user gets it: its DXF, read back by the validator's reader.
  const std::string stem = fs::path(row.name).filename().stem().string();
  const fs::path dxf = out / (stem + ".dxf");
  ExportOptions exports;
  exports.model = row.name;
  write_files({{dxf, plan_dxf(result.plan, exports)}});
  const std::vector<PlanPolyline> lines = read_plan_dxf(dxf, {});
  const PlanAnalysis analysis = analyze_plan(lines, {.min_strip_mm = options.slice.min_strip_mm});
  row.narrow =
      static_cast<int>(std::ranges::count(analysis.problems, PlanProblemKind::NarrowStrip, &PlanProblem::kind));
  row.parallel = analysis.narrow_between_folds;
  for (const PlanProblem& p : analysis.problems) row.chords += p.narrow_chords;
  row.read_back_stands = analysis.errors == row.narrow;  // a narrow strip is an error; it stands if only those
  row.read_back = likeness(result.maps, card_view(result.maps.grid, analysis.regions, {}), options.slice.min_strip_mm);
  const std::vector<double> discs = widest_discs_px(result.maps.grid, analysis.regions);
  for (std::size_t i = 0; i < discs.size(); ++i) {
    const PlanRegion& region = analysis.regions[i];
    row.thin += region.placed && region.status != FaceStatus::Removed &&
                discs[i] < options.slice.min_strip_mm * result.maps.grid.px_per_mm;
  }

  if (where_maps) write_where_map(model, options, result, error, far, out / (stem + "_where.png"));

  // Pictures: the model and the pop-up from one viewpoint, and the plan.
  RenderOptions view_options{.width_px = kPictureW, .height_px = kPictureH, .samples = 1};
  const ColouredMesh popup = popup_scene(fold_popup(result.plan.regions, options.sheet, {.angle_deg = 90}), true);
  const ColouredMesh placed =
      model_scene(apply(result.placement, load_mesh(model.file, options.load).mesh), options.sheet);
  const auto [lo, hi] = bounds_of({&popup, &placed});
  const View view = frame_view(lo, hi, view_options);
  const Image model_image = render(placed, view, view_options), popup_image = render(popup, view, view_options);
  exports.preview_px_per_mm = 2;
  const std::string plan_png_bytes = plan_png(result.plan, exports);
  write_files({{out / (stem + "_model.png"), image_png(model_image, stem)},
               {out / (stem + "_popup.png"), image_png(popup_image, stem)},
               {out / (stem + "_plan.png"), plan_png_bytes}});
  cell.model = surface_of(model_image);
  cell.popup = surface_of(popup_image);
  cell.plan = surface_of_png(plan_png_bytes);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: bench_likeness MODELS_DIR OUT_DIR [--only NAME]... [--seed N] [--min-strip W] [--where yes] "
                 "[--merge-thin-slices yes]\n");
    return 2;
  }
  const fs::path models_dir = argv[1], out = argv[2];
  DesignOptions options;
  std::vector<std::string> only;
  for (int i = 3; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--only") == 0)
      only.push_back(argv[i + 1]);
    else if (std::strcmp(argv[i], "--seed") == 0)
      options.supports.seed = static_cast<std::uint32_t>(std::stoul(argv[i + 1]));
    else if (std::strcmp(argv[i], "--where") == 0 && std::strcmp(argv[i + 1], "yes") == 0)
      where_maps = true;
    else if (std::strcmp(argv[i], "--min-strip") == 0)
      options.slice.min_strip_mm = std::stod(argv[i + 1]);
    else if (std::strcmp(argv[i], "--merge-thin-slices") == 0 && std::strcmp(argv[i + 1], "yes") == 0)
      options.slice.merge_thin_slices = true;
    else
      return std::fprintf(stderr, "bench_likeness: unknown option %s\n", argv[i]), 2;
  }
  fs::create_directories(out / "models");
  std::vector<Row> rows;
  std::vector<Cell> cells;
  std::printf("%-30s %7s %7s %7s %7s %7s %7s %7s %5s %5s %5s %-9s %6s %6s %5s %5s\n", "model", "p95 W", "mean W",
              "sliced", "p95 rb", "cover", "suppt", "cutout", "faces", "folds", "rm", "stands", "narrow", "time s",
              "folds<W", "thin");
  for (const Model& model : models_in(models_dir)) {
    const std::string name = name_of(model.file);
    if (!only.empty() && std::ranges::find(only, name) == only.end()) continue;
    Cell cell;
    cell.title = name;
    Row row;
    try {
      row = measure(model, options, out / "models", cell);
    } catch (const std::exception& e) {
      row = Row();
      row.name = name;
      row.error = e.what();
    }
    if (!row.error.empty()) {
      std::printf("%-30s FAILED: %s\n", name.c_str(), row.error.c_str());
      continue;
    }
    char numbers[256];
    std::snprintf(
        numbers, sizeof numbers, "p95 %.2f W (sliced %.2f), mean %.2f W, cover %.1f%%, supports %.1f%%, cut %.1f%%, %s",
        row.finished.p95_W, row.sliced.p95_W, row.finished.mean_W, 100 * row.finished.coverage,
        100 * row.finished.support_share, 100 * row.finished.cut_out_share, row.stands ? "stands" : "does not stand");
    cell.numbers = numbers;
    std::printf("%-30s %7.2f %7.2f %7.2f %7.2f %6.1f%% %6.1f%% %6.2f%% %5d %5d %5d %-9s %6d %6.2f %5d %5d\n",
                name.c_str(), row.finished.p95_W, row.finished.mean_W, row.sliced.p95_W, row.read_back.p95_W,
                100 * row.finished.coverage, 100 * row.finished.support_share, 100 * row.finished.cut_out_share,
                row.faces, row.folds, row.removed,
                row.stands && row.read_back_stands ? "yes"
                : row.stands                       ? "rb-NO"
                                                   : "NO",
                row.narrow, row.design_s, row.parallel, row.thin);
    std::fflush(stdout);
    rows.push_back(row);
    cells.push_back(cell);
  }
  if (rows.empty()) return 1;
  std::printf("\nwhere the card is more than 2 W off its model, as shares of the model's pixels:\n");
  std::printf("%-30s %7s %7s %7s %7s\n", "model", "model", "support", "card", "hole");
  for (const Row& r : rows)
    std::printf("%-30s %6.2f%% %6.2f%% %6.2f%% %6.2f%%\n", r.name.c_str(), 100 * r.far_off[0], 100 * r.far_off[1],
                100 * r.far_off[2], 100 * r.far_off[3]);
  const auto n = static_cast<double>(rows.size());
  const auto mean = [&](auto field) {
    double sum = 0;
    for (const Row& r : rows) sum += field(r);
    return sum / n;
  };
  const auto worst = [&](auto field) {
    const Row* w = &rows.front();
    for (const Row& r : rows)
      if (field(r) > field(*w)) w = &r;
    return std::pair{field(*w), w->name};
  };
  const auto [p95_max, p95_at] = worst([](const Row& r) { return r.finished.p95_W; });
  const auto [added_max, added_at] = worst([](const Row& r) { return r.finished.p95_W - r.sliced.p95_W; });
  const auto [cut_max, cut_at] = worst([](const Row& r) { return r.finished.cut_out_share; });
  const auto [uncover_max, uncover_at] = worst([](const Row& r) { return 1 - r.finished.coverage; });
  const auto [readback_gap, readback_at] =
      worst([](const Row& r) { return std::abs(r.finished.p95_W - r.read_back.p95_W); });
  const int stand =
      static_cast<int>(std::ranges::count_if(rows, [](const Row& r) { return r.stands && r.read_back_stands; }));
  std::printf("\n%zu models: p95 mean %.2f W (worst %.2f W, %s); mean error mean %.2f W; sliced p95 mean %.2f W\n",
              rows.size(), mean([](const Row& r) { return r.finished.p95_W; }), p95_max, p95_at.c_str(),
              mean([](const Row& r) { return r.finished.mean_W; }), mean([](const Row& r) { return r.sliced.p95_W; }));
  std::printf("supports add at most %.2f W to p95 (%s)\n", added_max, added_at.c_str());
  std::printf(
      "coverage mean %.1f%% (lowest %.1f%%, %s); supports mean %.1f%%; cut out mean %.2f%% (worst %.2f%%, %s)\n",
      100 * mean([](const Row& r) { return r.finished.coverage; }), 100 * (1 - uncover_max), uncover_at.c_str(),
      100 * mean([](const Row& r) { return r.finished.support_share; }),
      100 * mean([](const Row& r) { return r.finished.cut_out_share; }), 100 * cut_max, cut_at.c_str());
  std::printf("stand, by the design and read back: %d of %zu; read-back p95 differs by at most %.3f W (%s)\n", stand,
              rows.size(), readback_gap, readback_at.c_str());
  const int clean = static_cast<int>(std::ranges::count(rows, 0, &Row::narrow));
  int narrow = 0;
  for (const Row& r : rows) narrow += r.narrow;
  int parallel = 0, chords = 0, thin = 0;
  for (const Row& r : rows) parallel += r.parallel, chords += r.chords, thin += r.thin;
  std::printf(
      "no place narrower than W, read back: %d of %zu; places narrower than W: %d in all, %d of them between two "
      "parallel folds; %d chords narrower than W across them\n",
      clean, rows.size(), narrow, parallel, chords);
  std::printf("faces narrower than W everywhere (no disc W across fits in them, to a pixel), read back: %d in all\n",
              thin);
  std::printf("design time: mean %.2f s, total %.1f s\n", mean([](const Row& r) { return r.design_s; }),
              mean([](const Row& r) { return r.design_s; }) * n);
  write_contact_sheet(cells, out / "contact_sheet.png");
  // And in pages of a dozen models, easier to look at.
  constexpr std::size_t kPerPage = 12;
  for (std::size_t page = 0; page * kPerPage < cells.size(); ++page) {
    const auto from = cells.begin() + static_cast<std::ptrdiff_t>(page * kPerPage);
    const auto to = cells.begin() + static_cast<std::ptrdiff_t>(std::min(cells.size(), (page + 1) * kPerPage));
    write_contact_sheet({from, to}, out / ("contact_sheet_" + std::to_string(page + 1) + ".png"));
  }
  for (Cell& c : cells)
    for (cairo_surface_t* s : {c.model, c.popup, c.plan})
      if (s) cairo_surface_destroy(s);
  std::printf("contact sheet: %s\n", (out / "contact_sheet.png").c_str());
  return 0;
}
