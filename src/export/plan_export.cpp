// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/plan_export.hpp"

#include <cairo.h>
#include <tbb/parallel_invoke.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "origamic/error.hpp"
#include "origamic/mm_text.hpp"
#include "origamic/version.hpp"
#include "plan_writing.hpp"
#include "png_image.hpp"

namespace origamic {
namespace {

std::string xml_escaped(std::string_view text) {
  std::string out;
  for (const char c : text) switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  return out;
}

}  // namespace

LayerStyle layer_style(Layer layer, ColourPreset preset) {
  const bool laser = preset == ColourPreset::Laser;
  switch (layer) {
    case Layer::Cut: return laser ? LayerStyle{"CUT", 7, "#000000"} : LayerStyle{"CUT", 5, "#0000ff"};
    // Cut like CUT, in its colour; a layer of its own names the pieces that fall out.
    case Layer::CutOut: return laser ? LayerStyle{"CUTOUT", 7, "#000000"} : LayerStyle{"CUTOUT", 5, "#0000ff"};
    case Layer::Mountain: return laser ? LayerStyle{"MOUNTAIN", 1, "#ff0000"} : LayerStyle{"MOUNTAIN", 3, "#00e000"};
    case Layer::Valley: return laser ? LayerStyle{"VALLEY", 5, "#0000ff"} : LayerStyle{"VALLEY", 1, "#ff0000"};
    case Layer::PerfMountain: return LayerStyle{"PERF_MOUNTAIN", 6, "#ff00ff"};
    case Layer::PerfValley: return LayerStyle{"PERF_VALLEY", 4, "#00ffff"};
    case Layer::Outline: return laser ? LayerStyle{"OUTLINE", 3, "#00e000"} : LayerStyle{"OUTLINE", 7, "#000000"};
  }
  return {"0", 7, "#000000"};
}

LayerStyle layer_style(LineKind kind, ColourPreset preset) {
  switch (kind) {
    case LineKind::Cut: return layer_style(Layer::Cut, preset);
    case LineKind::CutOut: return layer_style(Layer::CutOut, preset);
    case LineKind::Mountain: return layer_style(Layer::Mountain, preset);
    case LineKind::Valley: return layer_style(Layer::Valley, preset);
    case LineKind::Outline: return layer_style(Layer::Outline, preset);
  }
  return layer_style(Layer::Cut, preset);
}

std::string plan_description(const Plan& plan, const ExportOptions& options) {
  std::string text = "origamic " + std::string(version) + " plan of " +
                     (options.model.empty() ? "a model" : options.model) +
                     "; units mm, 1:1 (plan X along the main fold from the sheet's left edge, Y up from the main fold);"
                     " sheet " + mm_text(plan.sheet.width_mm) + " x " + mm_text(plan.sheet.height_mm) + " mm";
  if (!options.settings.empty()) text += "; " + options.settings;
  return one_line(text + "; " + fold_style_summary(options.folds));
}

std::string plan_svg(const Plan& plan, const ExportOptions& options) {
  const DrawnPlan drawn = draw_plan(plan, options.folds);
  const double width = plan.sheet.width_mm, height = plan.sheet.height_mm, top = plan.sheet.max_Y();
  const std::string title = "origamic plan: " + xml_escaped(options.model);
  const std::string description = xml_escaped(plan_description(plan, options)) +
                                  ". SVG: 1 user unit = 1 mm; SVG y = " + mm_text(top) +
                                  " - plan Y (the main fold is at y = " + mm_text(top) + ").";
  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\""
      << " xmlns:rdf=\"http://www.w3.org/1999/02/22-rdf-syntax-ns#\" xmlns:cc=\"http://creativecommons.org/ns#\""
      << " xmlns:dc=\"http://purl.org/dc/elements/1.1/\""
      << " width=\"" << mm_text(width) << "mm\" height=\"" << mm_text(height) << "mm\" viewBox=\"0 0 " << mm_text(width)
      << ' ' << mm_text(height) << "\">\n"
      << "<title>" << title << "</title>\n"
      << "<desc>" << description << "</desc>\n"
      // Dublin Core in Inkscape's form, so its Document Metadata dialog shows it.
      << "<metadata><rdf:RDF><cc:Work rdf:about=\"\"><dc:format>image/svg+xml</dc:format><dc:title>" << title
      << "</dc:title><dc:description>" << description << "</dc:description><dc:creator><cc:Agent><dc:title>origamic "
      << version << "</dc:title></cc:Agent></dc:creator></cc:Work></rdf:RDF></metadata>\n";
  for (const Layer layer : used_layers(drawn)) {
    const LayerStyle style = layer_style(layer, options.colours);
    svg << "<g id=\"" << style.name << "\" inkscape:groupmode=\"layer\" inkscape:label=\"" << style.name
        << "\" fill=\"none\" stroke=\"" << style.rgb << "\" stroke-width=\"0.0254\">\n";
    for (const DrawnLine& line : drawn.lines) {
      if (line.layer != layer) continue;
      const auto in_file = [&](const PlanPoint& p) { return mm_text(p.X) + ',' + mm_text(top - p.Y); };
      const std::vector<PlanPoint> points = as_written(line.points, in_file);
      if (points.empty()) continue;
      svg << "<polyline points=\"";
      for (std::size_t i = 0; i < points.size(); ++i) svg << (i ? " " : "") << in_file(points[i]);
      svg << '"';
      if (!line.dash_mm.empty()) {
        svg << " stroke-dasharray=\"";
        for (std::size_t i = 0; i < line.dash_mm.size(); ++i) svg << (i ? " " : "") << mm_text(line.dash_mm[i]);
        svg << '"';
      }
      svg << "/>\n";
    }
    svg << "</g>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

namespace {

// The plan in the seed's style at preview_px_per_mm, with `marks` in blue over it: RGB bytes.
struct PlanPicture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};
PlanPicture plan_picture(const Plan& plan, const ExportOptions& options, std::span<const NarrowChord> marks) {
  // The seed's figures show fold directions by pattern: the score style is previewed dashed.
  FoldStyleOptions folds = options.folds;
  if (folds.style == FoldStyle::Score) folds.style = FoldStyle::Dashed;
  const DrawnPlan drawn = draw_plan(plan, folds);
  const double scale = options.preview_px_per_mm;
  const int w = static_cast<int>(std::ceil(plan.sheet.width_mm * scale));
  const int h = static_cast<int>(std::ceil(plan.sheet.height_mm * scale));
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h);
  cairo_t* cr = cairo_create(surface);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_translate(cr, 0, plan.sheet.max_Y() * scale);
  cairo_scale(cr, scale, -scale);
  cairo_set_line_width(cr, 1.0 / scale);
  for (const Layer layer : kLayerOrder) {
    if (layer == Layer::Cut || layer == Layer::CutOut) cairo_set_source_rgb(cr, 0.86, 0, 0);
    else if (layer == Layer::Outline) cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    else cairo_set_source_rgb(cr, 0, 0.63, 0);
    for (const DrawnLine& line : drawn.lines) {
      if (line.layer != layer) continue;
      for (const std::vector<PlanPoint>& piece : dash_pieces(line)) {
        cairo_move_to(cr, piece[0].X, piece[0].Y);
        for (std::size_t i = 1; i < piece.size(); ++i) cairo_line_to(cr, piece[i].X, piece[i].Y);
      }
      cairo_stroke(cr);
    }
  }
  // Marks in whole pixels of one colour; a chord shorter than a pixel is a dot.
  constexpr double kSquare_px = 11;
  cairo_set_source_rgb(cr, 0, 0.24, 1);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const NarrowChord& mark : marks) {
    cairo_set_line_width(cr, 3 / scale);
    cairo_move_to(cr, mark.from.X, mark.from.Y);
    cairo_line_to(cr, mark.to.X, mark.to.Y);
    cairo_stroke(cr);
    cairo_set_line_width(cr, 1 / scale);
    const double side = kSquare_px / scale;
    cairo_rectangle(cr, (mark.from.X + mark.to.X - side) / 2, (mark.from.Y + mark.to.Y - side) / 2, side, side);
    cairo_stroke(cr);
  }
  cairo_destroy(cr);
  cairo_surface_flush(surface);
  const cairo_status_t status = cairo_surface_status(surface);
  if (status != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(surface);
    throw OutputError("plan PNG: cannot draw (" + std::string(cairo_status_to_string(status)) + ")");
  }
  // Cairo's RGB24 pixels are native-endian 32-bit 0xXXRRGGBB words; libpng takes RGB bytes.
  PlanPicture picture{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3)};
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint32_t pixel;
      std::memcpy(&pixel, data + static_cast<std::ptrdiff_t>(y) * stride + 4 * x, 4);
      std::uint8_t* out =
          &picture.rgb[(static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)) * 3];
      out[0] = static_cast<std::uint8_t>(pixel >> 16), out[1] = static_cast<std::uint8_t>(pixel >> 8),
      out[2] = static_cast<std::uint8_t>(pixel);
    }
  cairo_surface_destroy(surface);
  return picture;
}

}  // namespace

std::string plan_png(const Plan& plan, const ExportOptions& options) {
  const PlanPicture picture = plan_picture(plan, options, {});
  const double scale = options.preview_px_per_mm;
  return encode_png("plan PNG", picture.width, picture.height, picture.rgb,
                    {.texts = {{"Title", one_line("origamic plan: " + options.model)},
                               {"Description", plan_description(plan, options) + "; preview at " + mm_text(scale) +
                                                   " px/mm: cuts red, folds green (mountain dash-dot, valley dashed)"},
                               {"Software", std::string("origamic ") + version}},
                     .px_per_mm = scale});
}

std::vector<std::uint8_t> narrow_places_rgb(const Plan& plan, const ExportOptions& options,
                                            std::span<const NarrowChord> chords) {
  return plan_picture(plan, options, chords).rgb;
}

std::string narrow_places_png(const Plan& plan, const ExportOptions& options, std::span<const NarrowChord> chords) {
  const PlanPicture picture = plan_picture(plan, options, chords);
  return encode_png(
      "narrow places PNG", picture.width, picture.height, picture.rgb,
      {.texts = {{"Title", one_line("origamic places narrower than W: " + options.model)},
                 {"Description", std::to_string(chords.size()) + " places narrower than W, blue, each in a square"},
                 {"Software", std::string("origamic ") + version}},
       .px_per_mm = options.preview_px_per_mm});
}

std::vector<OutputFile> plan_files(const Plan& plan, const ExportOptions& options, const std::string& base) {
  std::string dxf, svg, png, pdf;
  tbb::parallel_invoke([&] { dxf = plan_dxf(plan, options); }, [&] { svg = plan_svg(plan, options); },
                       [&] { png = plan_png(plan, options); }, [&] { pdf = plan_pdf(plan, options); });
  return {{base + ".dxf", std::move(dxf)},
          {base + ".svg", std::move(svg)},
          {base + ".png", std::move(png)},
          {base + ".pdf", std::move(pdf)}};
}

}  // namespace origamic
