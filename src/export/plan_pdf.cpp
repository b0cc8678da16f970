// SPDX-License-Identifier: GPL-3.0-or-later
// The print-ready PDF: the plan at 1:1 on a page, with a legend, a scale bar and a caption.
#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <string>
#include <vector>

#include "number_text.hpp"
#include "origamic/error.hpp"
#include "origamic/plan_export.hpp"
#include "origamic/version.hpp"

namespace origamic {
namespace {

constexpr double kPointsPerMm = 72.0 / 25.4;  // 1 pt = 1/72 in = 25.4/72 mm, exactly
// 0.1 mm: the thick end of a cutter's hairline (LASER.md), still a clear line from any printer.
constexpr double kLineWidth_mm = 0.1;
constexpr double kPaperEdge_mm = 5;      // printers leave about 4 mm of the paper's edge unprinted
constexpr double kSheetEdge_mm = 3;      // the legend keeps this far inside the sheet
constexpr double kPlanClear_mm = 2;      // and this far from any plan line
constexpr double kText_mm = 2.2;         // legend labels (6.2 pt)
constexpr double kCaption_mm = 1.9;      // caption lines (5.4 pt)
constexpr double kSample_mm = 12;        // length of a legend's line sample
constexpr double kBar_mm = 10;           // the scale bar
constexpr double kCaptionWidth_mm = 85;  // caption lines wrap here (at ", ")

struct Box {
  double x = 0, y = 0, w = 0, h = 0;  // page mm, y down
};

struct Rgb {
  double r = 0, g = 0, b = 0;
};

Rgb rgb_of(const char* hex) {
  unsigned r = 0, g = 0, b = 0;
  std::sscanf(hex, "#%02x%02x%02x", &r, &g, &b);
  return {r / 255.0, g / 255.0, b / 255.0};
}

std::string number(double value) { return number_text(value); }

// Where the sheet sits on the page: page x = x0 + X, page y = y0 + (top - Y).
struct Frame {
  double x0 = 0, y0 = 0, top = 0;
  double x(const PlanPoint& p) const { return x0 + p.X; }
  double y(const PlanPoint& p) const { return y0 + top - p.Y; }
};

void stroke_pieces(cairo_t* cr, const DrawnLine& line, const Frame& frame) {
  for (const std::vector<PlanPoint>& piece : dash_pieces(line)) {
    cairo_move_to(cr, frame.x(piece[0]), frame.y(piece[0]));
    for (std::size_t i = 1; i < piece.size(); ++i) cairo_line_to(cr, frame.x(piece[i]), frame.y(piece[i]));
  }
  cairo_stroke(cr);
}

// Liang-Barsky: does the segment a-b meet the box?
bool meets(const Box& box, double ax, double ay, double bx, double by) {
  double t0 = 0, t1 = 1;
  const double dx = bx - ax, dy = by - ay;
  auto clip = [&](double p, double q) {  // p t <= q
    if (p == 0) return q >= 0;
    const double t = q / p;
    if (p < 0)
      t0 = std::max(t0, t);
    else
      t1 = std::min(t1, t);
    return t0 <= t1;
  };
  return clip(-dx, ax - box.x) && clip(dx, box.x + box.w - ax) && clip(-dy, ay - box.y) && clip(dy, box.y + box.h - ay);
}

// The legend and caption: what they say and how they are laid out.
struct Legend {
  struct Entry {
    std::string label;
    std::vector<DrawnLine> sample;  // in sample coordinates: X along it from 0, Y = 0
    Rgb colour;
  };
  std::vector<Entry> entries;
  std::vector<std::string> caption;
};

Legend legend_of(const ExportOptions& options, cairo_t* cr) {
  Legend legend;
  const FoldStyleOptions& folds = options.folds;
  const char* how = folds.style == FoldStyle::Score        ? " (score)"
                    : folds.style == FoldStyle::Perforated ? " (perforated)"
                                                           : "";
  const PlanPolyline straight{LineKind::Cut, {{0, 0}, {kSample_mm, 0}}};
  auto sample = [&](LineKind kind) {
    PlanPolyline line = straight;
    line.kind = kind;
    if (kind == LineKind::Cut || kind == LineKind::Outline)
      return std::vector<DrawnLine>{{kind == LineKind::Cut ? Layer::Cut : Layer::Outline, line.points, {}}};
    return draw_fold(line, {}, folds);
  };
  auto colour = [&](const std::vector<DrawnLine>& lines) {
    return rgb_of(layer_style(lines.front().layer, options.colours).rgb);
  };
  for (const auto& [kind, label] :
       {std::pair{LineKind::Cut, std::string("cut")}, std::pair{LineKind::Mountain, std::string("mountain fold") + how},
        std::pair{LineKind::Valley, std::string("valley fold") + how},
        std::pair{LineKind::Outline, std::string("sheet edge")}}) {
    std::vector<DrawnLine> lines = sample(kind);
    legend.entries.push_back({label, lines, colour(lines)});
  }
  // Caption: the model, the settings wrapped at ", ", the fold style, how to print.
  legend.caption.push_back("origamic " + std::string(version) + " plan of " +
                           (options.model.empty() ? "a model" : options.model));
  cairo_set_font_size(cr, kCaption_mm);
  std::string line;
  std::string rest = options.settings;
  while (!rest.empty()) {
    const std::size_t comma = rest.find(", ");
    const std::string part = rest.substr(0, comma);
    rest = comma == std::string::npos ? "" : rest.substr(comma + 2);
    const std::string joined = line.empty() ? part : line + ", " + part;
    cairo_text_extents_t extents;
    cairo_text_extents(cr, joined.c_str(), &extents);
    if (!line.empty() && extents.x_advance > kCaptionWidth_mm) {
      legend.caption.push_back(line + ",");
      line = part;
    } else {
      line = joined;
    }
  }
  if (!line.empty()) legend.caption.push_back(line);
  legend.caption.push_back(fold_style_summary(options.folds));
  legend.caption.push_back("1:1, units mm: print at 100 % (actual size); the bar is 10 mm long");
  return legend;
}

double text_width(cairo_t* cr, const std::string& text, double size) {
  cairo_set_font_size(cr, size);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text.c_str(), &extents);
  return extents.x_advance;
}

// The legend's shape and place. Wide: the samples and the scale bar in one row; tall: one above the
// other. The caption follows.
struct LegendLayout {
  bool wide = true;
  double x = 0, y = 0;  // its top-left corner, page mm, y down
};

// Lays the legend out, drawing it if asked; returns its box.
Box lay_out(cairo_t* cr, const Legend& legend, const LegendLayout& layout, bool draw) {
  const double row = 3.6, gap = 1.5, spacing = 4;
  const bool wide = layout.wide;
  const double x = layout.x, y = layout.y;
  double w = 0, cx = x, cy = y;
  auto item = [&](double label_x, const std::string& label) {
    if (draw) {
      cairo_set_source_rgb(cr, 0, 0, 0);
      cairo_set_font_size(cr, kText_mm);
      cairo_move_to(cr, label_x, cy + row / 2 + kText_mm * 0.35);
      cairo_show_text(cr, label.c_str());
    }
    const double right = label_x + text_width(cr, label, kText_mm);
    w = std::max(w, right - x);
    if (wide)
      cx = right + spacing;
    else
      cy += row;
  };
  for (const Legend::Entry& entry : legend.entries) {
    if (draw) {
      cairo_set_source_rgb(cr, entry.colour.r, entry.colour.g, entry.colour.b);
      for (const DrawnLine& line : entry.sample) stroke_pieces(cr, line, Frame{cx, cy + row / 2, 0});
    }
    item(cx + kSample_mm + gap, entry.label);
  }
  // The scale bar: a filled 10 mm x 1.2 mm rectangle (filled, so line caps cannot lengthen it).
  if (draw) {
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, cx, cy + row / 2 - 0.6, kBar_mm, 1.2);
    cairo_fill(cr);
  }
  item(cx + kBar_mm + gap, "10 mm");
  if (wide) cy += row;
  cy += 0.8;
  for (const std::string& text : legend.caption) {
    cy += kCaption_mm * 1.35;
    if (draw) {
      cairo_set_source_rgb(cr, 0, 0, 0);
      cairo_set_font_size(cr, kCaption_mm);
      cairo_move_to(cr, x, cy);
      cairo_show_text(cr, text.c_str());
    }
    w = std::max(w, text_width(cr, text, kCaption_mm));
  }
  return {x, y, w, cy + 0.6 * kCaption_mm - y};
}

struct Placement {
  Box box;
  bool wide = true;
  bool second_page = false;
};

// The page and the sheet on it.
struct SheetOnPage {
  PageSize page;
  Sheet sheet;
  Frame frame;  // where the sheet sits
};

// Where the legend goes, in order of preference: the paper's margin beside the sheet (it stays off
// the card); a corner of the sheet whose box, widened by kPlanClear_mm, meets no plan line (the auto
// fit leaves the sheet's corners empty for most models); else a second page of the same size.
Placement place_legend(cairo_t* cr, const Legend& legend, const DrawnPlan& drawn, const SheetOnPage& on_page) {
  const PageSize& page = on_page.page;
  const Frame& frame = on_page.frame;
  const Box sheet_box{frame.x0, frame.y0, on_page.sheet.width_mm, on_page.sheet.height_mm};
  auto fits_page = [&](const Box& b) {
    return b.x >= kPaperEdge_mm && b.y >= kPaperEdge_mm && b.x + b.w <= page.width_mm - kPaperEdge_mm &&
           b.y + b.h <= page.height_mm - kPaperEdge_mm;
  };
  auto clear_of_plan = [&](const Box& b) {
    const Box wider{b.x - kPlanClear_mm, b.y - kPlanClear_mm, b.w + 2 * kPlanClear_mm, b.h + 2 * kPlanClear_mm};
    for (const DrawnLine& line : drawn.lines) {
      if (line.layer == Layer::Outline) continue;
      for (std::size_t i = 1; i < line.points.size(); ++i)
        if (meets(wider, frame.x(line.points[i - 1]), frame.y(line.points[i - 1]), frame.x(line.points[i]),
                  frame.y(line.points[i])))
          return false;
    }
    return true;
  };
  for (const bool wide : {true, false}) {  // the paper's margins: below, above, left, right of the sheet
    const Box size = lay_out(cr, legend, {wide, 0, 0}, false);
    const double left = std::max(kPaperEdge_mm, sheet_box.x);
    for (const Box b :
         {Box{left, sheet_box.y + sheet_box.h + kPlanClear_mm, size.w, size.h},
          Box{left, sheet_box.y - kPlanClear_mm - size.h, size.w, size.h},
          Box{sheet_box.x - kPlanClear_mm - size.w, std::max(kPaperEdge_mm, sheet_box.y), size.w, size.h},
          Box{sheet_box.x + sheet_box.w + kPlanClear_mm, std::max(kPaperEdge_mm, sheet_box.y), size.w, size.h}})
      if (fits_page(b)) return {b, wide, false};
  }
  for (const bool wide : {true, false}) {  // the sheet's corners: bottom left, bottom right, top left, top right
    const Box size = lay_out(cr, legend, {wide, 0, 0}, false);
    const double left = std::max(sheet_box.x + kSheetEdge_mm, kPaperEdge_mm);
    const double right = std::min(sheet_box.x + sheet_box.w - kSheetEdge_mm, page.width_mm - kPaperEdge_mm) - size.w;
    const double top = std::max(sheet_box.y + kSheetEdge_mm, kPaperEdge_mm);
    const double bottom = std::min(sheet_box.y + sheet_box.h - kSheetEdge_mm, page.height_mm - kPaperEdge_mm) - size.h;
    for (const Box b : {Box{left, bottom, size.w, size.h}, Box{right, bottom, size.w, size.h},
                        Box{left, top, size.w, size.h}, Box{right, top, size.w, size.h}})
      if (fits_page(b) && b.x >= sheet_box.x && b.y >= sheet_box.y && b.x + b.w <= sheet_box.x + sheet_box.w &&
          b.y + b.h <= sheet_box.y + sheet_box.h && clear_of_plan(b))
        return {b, wide, false};
  }
  const Box size = lay_out(cr, legend, {false, 0, 0}, false);
  return {{kPaperEdge_mm, kPaperEdge_mm, size.w, size.h}, false, true};
}

cairo_status_t append(void* closure, const unsigned char* data, unsigned int length) {
  try {
    static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
    return CAIRO_STATUS_SUCCESS;
  } catch (...) {
    return CAIRO_STATUS_WRITE_ERROR;
  }
}

}  // namespace

PageSize pdf_page(const Sheet& sheet, Paper paper) {
  if (!(std::isfinite(sheet.width_mm) && std::isfinite(sheet.height_mm) && sheet.width_mm > 0 && sheet.height_mm > 0))
    throw InputError("Sheet", "the sheet must have a positive, finite width and height");
  if (paper == Paper::Sheet) return {sheet.width_mm, sheet.height_mm};
  const PageSize size = paper == Paper::A4 ? PageSize{210, 297} : PageSize{215.9, 279.4};
  if (sheet.width_mm <= size.width_mm && sheet.height_mm <= size.height_mm) return size;
  if (sheet.width_mm <= size.height_mm && sheet.height_mm <= size.width_mm) return {size.height_mm, size.width_mm};
  throw InputError("ExportOptions::paper", "the " + number(sheet.width_mm) + "x" + number(sheet.height_mm) +
                   " mm sheet does not fit on " + (paper == Paper::A4 ? "A4" : "Letter") + " paper (" +
                   number(size.width_mm) + "x" + number(size.height_mm) + " mm) either way up");
}

namespace {

// The PDF date of a moment, ISO 8601 in UTC as cairo takes it.
std::string iso_date(std::int64_t seconds) {
  const auto time = static_cast<std::time_t>(seconds);
  std::tm utc{};
  if (seconds < 0 || seconds > kLatestPdfDate_s || !gmtime_r(&time, &utc))
    throw InputError("ExportOptions::pdf_date_s", std::to_string(seconds) + " s since 1970 is not between 0 and " +
                     std::to_string(kLatestPdfDate_s) + " (the year 9999)");
  char iso[32];
  std::strftime(iso, sizeof iso, "%Y-%m-%dT%H:%M:%SZ", &utc);
  return iso;
}

}  // namespace

void check_export_options(const ExportOptions& options, const Sheet& sheet) {
  check_fold_style(options.folds);
  pdf_page(sheet, options.paper);
  if (options.pdf_date_s) iso_date(*options.pdf_date_s);
}

std::string plan_pdf(const Plan& plan, const ExportOptions& options) {
  const PageSize page = pdf_page(plan.sheet, options.paper);
  const DrawnPlan drawn = draw_plan(plan, options.folds);
  std::string bytes;
  cairo_surface_t* surface =
      cairo_pdf_surface_create_for_stream(append, &bytes, page.width_mm * kPointsPerMm, page.height_mm * kPointsPerMm);
  const std::string title = "origamic plan: " + options.model;
  const std::string keywords = "origamic, Origamic Architecture, pop-up card, " + options.model + ", " +
                               fold_style_name(options.folds.style) + " folds, units mm, scale 1:1";
  const std::string creator = "origamic " + std::string(version);
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_TITLE, title.c_str());
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_SUBJECT, plan_description(plan, options).c_str());
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_KEYWORDS, keywords.c_str());
  cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATOR, creator.c_str());
  if (options.pdf_date_s) {
    const std::string date = iso_date(*options.pdf_date_s);
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_CREATE_DATE, date.c_str());
    cairo_pdf_surface_set_metadata(surface, CAIRO_PDF_METADATA_MOD_DATE, date.c_str());
  }
  cairo_t* cr = cairo_create(surface);
  cairo_scale(cr, kPointsPerMm, kPointsPerMm);  // from here on, 1 user unit = 1 mm
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_line_width(cr, kLineWidth_mm);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);  // a perforation or a dash is exactly as long as drawn

  const Frame frame{(page.width_mm - plan.sheet.width_mm) / 2, (page.height_mm - plan.sheet.height_mm) / 2,
                    plan.sheet.max_Y()};
  for (const Layer layer : kLayerOrder) {
    const Rgb c = rgb_of(layer_style(layer, options.colours).rgb);
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    for (const DrawnLine& line : drawn.lines)
      if (line.layer == layer) stroke_pieces(cr, line, frame);
  }
  const Legend legend = legend_of(options, cr);
  const Placement at = place_legend(cr, legend, drawn, {page, plan.sheet, frame});
  if (at.second_page) cairo_show_page(cr);
  lay_out(cr, legend, {at.wide, at.box.x, at.box.y}, true);
  cairo_show_page(cr);
  cairo_destroy(cr);
  cairo_surface_finish(surface);
  const cairo_status_t status = cairo_surface_status(surface);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS)
    throw OutputError("plan PDF: cairo failed (" + std::string(cairo_status_to_string(status)) + ")");
  return bytes;
}

}  // namespace origamic
