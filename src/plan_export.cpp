// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/plan_export.hpp"

#include <cairo.h>
#include <dxflib/dl_dxf.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <string_view>

#include "origamic/error.hpp"

namespace origamic {
namespace {

constexpr LineKind kDrawOrder[] = {LineKind::Mountain, LineKind::Valley, LineKind::Cut, LineKind::Outline};

// Coordinates with fixed decimals: 1e-6 mm keeps every exact value to far better than 0.001 mm.
std::string mm(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6f", value);
  std::string s = text;
  s.erase(s.find_last_not_of('0') + 1);
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

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

LayerStyle layer_style(LineKind kind, ColourPreset preset) {
  const bool laser = preset == ColourPreset::Laser;
  switch (kind) {
    case LineKind::Cut: return laser ? LayerStyle{"CUT", 7, "#000000"} : LayerStyle{"CUT", 5, "#0000ff"};
    case LineKind::Mountain: return laser ? LayerStyle{"MOUNTAIN", 1, "#ff0000"} : LayerStyle{"MOUNTAIN", 3, "#00e000"};
    case LineKind::Valley: return laser ? LayerStyle{"VALLEY", 5, "#0000ff"} : LayerStyle{"VALLEY", 1, "#ff0000"};
    case LineKind::Outline: return laser ? LayerStyle{"OUTLINE", 3, "#00e000"} : LayerStyle{"OUTLINE", 7, "#000000"};
  }
  return {"0", 7, "#000000"};
}

std::string plan_dxf(const Plan& plan, const ExportOptions& options) {
  // dxflib writes to a named file only: a private temporary one, read back and removed.
  std::string temp = (std::filesystem::temp_directory_path() / "origamic-dxf-XXXXXX").string();
  const int fd = ::mkstemp(temp.data());
  if (fd < 0) throw OutputError("DXF: cannot create a temporary file in " + std::filesystem::temp_directory_path().string());
  ::close(fd);
  struct Remove {
    std::string path;
    ~Remove() { std::remove(path.c_str()); }
  } remove_temp{temp};
  {
    const DL_Codes::version version = options.dxf_version == DxfVersion::R12 ? DL_Codes::AC1009 : DL_Codes::AC1015;
    DL_Dxf dxf;
    std::unique_ptr<DL_WriterA> dw(dxf.out(temp.c_str(), version));
    if (!dw || dw->openFailed()) throw OutputError("DXF: cannot write the temporary file " + temp);
    dxf.writeHeader(*dw);
    dw->dxfString(9, "$INSUNITS");
    dw->dxfInt(70, 4);  // millimetres
    dw->dxfString(9, "$MEASUREMENT");
    dw->dxfInt(70, 1);  // metric
    dw->dxfString(9, "$EXTMIN");
    dw->dxfReal(10, 0.0);
    dw->dxfReal(20, plan.sheet.min_Y());
    dw->dxfString(9, "$EXTMAX");
    dw->dxfReal(10, plan.sheet.width_mm);
    dw->dxfReal(20, plan.sheet.max_Y());
    dw->sectionEnd();
    dw->sectionTables();
    dxf.writeVPort(*dw);
    dw->tableLinetypes(3);
    dxf.writeLinetype(*dw, DL_LinetypeData("BYBLOCK", "", 0, 0, 0.0));
    dxf.writeLinetype(*dw, DL_LinetypeData("BYLAYER", "", 0, 0, 0.0));
    dxf.writeLinetype(*dw, DL_LinetypeData("CONTINUOUS", "Solid line", 0, 0, 0.0));
    dw->tableEnd();
    dw->tableLayers(5);
    dxf.writeLayer(*dw, DL_LayerData("0", 0), DL_Attributes("", 7, 0, "CONTINUOUS", 1.0));
    for (const LineKind kind : kDrawOrder) {
      const LayerStyle style = layer_style(kind, options.colours);
      dxf.writeLayer(*dw, DL_LayerData(style.name, 0), DL_Attributes("", style.aci, 0, "CONTINUOUS", 1.0));
    }
    dw->tableEnd();
    dw->tableStyle(1);
    dxf.writeStyle(*dw, DL_StyleData("standard", 0, 2.5, 1.0, 0.0, 0, 2.5, "txt", ""));
    dw->tableEnd();
    dxf.writeView(*dw);
    dxf.writeUcs(*dw);
    dw->tableAppid(1);
    dxf.writeAppid(*dw, "ACAD");
    dw->tableEnd();
    dxf.writeDimStyle(*dw, 1, 1, 1, 1, 1);
    if (options.dxf_version == DxfVersion::R2000) {
      dxf.writeBlockRecord(*dw);
      dw->tableEnd();
    }
    dw->sectionEnd();
    dw->sectionBlocks();
    dxf.writeBlock(*dw, DL_BlockData("*Model_Space", 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(*dw, "*Model_Space");
    dxf.writeBlock(*dw, DL_BlockData("*Paper_Space", 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(*dw, "*Paper_Space");
    if (options.dxf_version == DxfVersion::R2000) {  // dxflib's block records and layouts name it
      dxf.writeBlock(*dw, DL_BlockData("*Paper_Space0", 0, 0.0, 0.0, 0.0));
      dxf.writeEndBlock(*dw, "*Paper_Space0");
    }
    dw->sectionEnd();
    dw->sectionEntities();
    for (const LineKind kind : kDrawOrder) {
      const LayerStyle style = layer_style(kind, options.colours);
      const DL_Attributes attributes(style.name, style.aci, 0, "CONTINUOUS", 1.0);
      for (const PlanPolyline& line : plan.lines) {
        if (line.kind != kind || line.points.size() < 2) continue;
        const bool closed = line.points.size() > 3 && line.points.front().X == line.points.back().X &&
                            line.points.front().Y == line.points.back().Y;
        const std::size_t count = line.points.size() - (closed ? 1 : 0);
        dxf.writePolyline(*dw, DL_PolylineData(static_cast<int>(count), 0, 0, closed ? 1 : 0), attributes);
        for (std::size_t i = 0; i < count; ++i)
          dxf.writeVertex(*dw, DL_VertexData(line.points[i].X, line.points[i].Y, 0.0, 0.0));
        dxf.writePolylineEnd(*dw);
      }
    }
    dw->sectionEnd();
    if (options.dxf_version == DxfVersion::R2000) {
      dxf.writeObjects(*dw);
      dxf.writeObjectsEnd(*dw);
    }
    dw->dxfEOF();
    dw->close();
  }
  std::ifstream in(temp, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw OutputError("DXF: cannot read back the temporary file " + temp);
  if (bytes.size() < 4 || bytes.compare(bytes.size() - 4, 4, "EOF\n") != 0)
    throw OutputError("DXF: dxflib wrote an incomplete file (disk full?)");
  return bytes;
}

std::string plan_svg(const Plan& plan, const ExportOptions& options) {
  const double width = plan.sheet.width_mm, height = plan.sheet.height_mm, top = plan.sheet.max_Y();
  std::ostringstream svg;
  svg << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<svg xmlns=\"http://www.w3.org/2000/svg\" xmlns:inkscape=\"http://www.inkscape.org/namespaces/inkscape\""
      << " width=\"" << mm(width) << "mm\" height=\"" << mm(height) << "mm\" viewBox=\"0 0 " << mm(width) << ' '
      << mm(height) << "\">\n"
      << "<title>origamic plan: " << xml_escaped(options.model) << "</title>\n"
      << "<desc>Units: mm, 1 user unit = 1 mm. Plan X along the main fold from the sheet's left edge;"
      << " SVG y = " << mm(top) << " - plan Y (the main fold is at y = " << mm(top) << "). " << xml_escaped(options.settings)
      << "</desc>\n";
  for (const LineKind kind : kDrawOrder) {
    const LayerStyle style = layer_style(kind, options.colours);
    svg << "<g id=\"" << style.name << "\" inkscape:groupmode=\"layer\" inkscape:label=\"" << style.name
        << "\" fill=\"none\" stroke=\"" << style.rgb << "\" stroke-width=\"0.0254\">\n";
    for (const PlanPolyline& line : plan.lines) {
      if (line.kind != kind || line.points.size() < 2) continue;
      svg << "<polyline points=\"";
      for (std::size_t i = 0; i < line.points.size(); ++i)
        svg << (i ? " " : "") << mm(line.points[i].X) << ',' << mm(top - line.points[i].Y);
      svg << "\"/>\n";
    }
    svg << "</g>\n";
  }
  svg << "</svg>\n";
  return svg.str();
}

std::string plan_png(const Plan& plan, const ExportOptions& options) {
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
  for (const LineKind kind : kDrawOrder) {
    const double dash_dot[] = {2.0, 0.8, 0.3, 0.8}, dash[] = {1.5, 1.0};
    if (kind == LineKind::Mountain) cairo_set_dash(cr, dash_dot, 4, 0);
    else if (kind == LineKind::Valley) cairo_set_dash(cr, dash, 2, 0);
    else cairo_set_dash(cr, nullptr, 0, 0);
    if (kind == LineKind::Cut) cairo_set_source_rgb(cr, 0.86, 0, 0);
    else if (kind == LineKind::Outline) cairo_set_source_rgb(cr, 0.3, 0.3, 0.3);
    else cairo_set_source_rgb(cr, 0, 0.63, 0);
    for (const PlanPolyline& line : plan.lines) {
      if (line.kind != kind || line.points.size() < 2) continue;
      cairo_move_to(cr, line.points[0].X, line.points[0].Y);
      for (std::size_t i = 1; i < line.points.size(); ++i) cairo_line_to(cr, line.points[i].X, line.points[i].Y);
      cairo_stroke(cr);
    }
  }
  cairo_destroy(cr);
  std::string bytes;
  const cairo_status_t status = cairo_surface_write_to_png_stream(
      surface,
      [](void* closure, const unsigned char* data, unsigned int length) {
        static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
        return CAIRO_STATUS_SUCCESS;
      },
      &bytes);
  cairo_surface_destroy(surface);
  if (status != CAIRO_STATUS_SUCCESS) throw OutputError("plan PNG: cannot encode (" +
                                                         std::string(cairo_status_to_string(status)) + ")");
  return bytes;
}

}  // namespace origamic
