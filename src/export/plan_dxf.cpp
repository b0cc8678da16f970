// SPDX-License-Identifier: GPL-3.0-or-later
// The plan as DXF, written by dxflib.
#include <dxflib/dl_dxf.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "origamic/error.hpp"
#include "origamic/mm_text.hpp"
#include "origamic/plan_export.hpp"
#include "plan_writing.hpp"

namespace origamic {
namespace {

// Perforations and dashes are written as many short separate segments.
bool drawn_in_pieces(const DrawnLine& line) {
  return !line.dash_mm.empty() || line.layer == Layer::PerfMountain || line.layer == Layer::PerfValley;
}

// dxflib writes the R2000 OBJECTS section without owners: every object gets its owner handle (330)
// after its own (5), the dictionary that lists it, or 0 for the root dictionary, as AutoCAD writes
// them (ezdxf's audit fixed 13 of them in each plan).
std::string with_object_owners(const std::string& dxf) {
  std::vector<std::string> lines;
  for (std::size_t at = 0; at < dxf.size();) {
    const std::size_t end = std::min(dxf.find('\n', at), dxf.size());
    lines.push_back(dxf.substr(at, end - at));
    at = end + 1;
  }
  const auto trim = [](const std::string& text) {
    const auto first = text.find_first_not_of(' ');
    return first == std::string::npos ? std::string() : text.substr(first);
  };
  std::size_t begin = lines.size();
  for (std::size_t i = 0; i + 1 < lines.size(); i += 2)
    if (trim(lines[i]) == "2" && lines[i + 1] == "OBJECTS") begin = i + 2;
  std::map<std::string, std::string> owner;
  std::string type, handle;
  for (std::size_t i = begin; i + 1 < lines.size(); i += 2) {
    const std::string code = trim(lines[i]), &value = lines[i + 1];
    if (code == "0") type = value, handle.clear();
    if (code == "5") handle = value;
    if ((code == "350" || code == "360") && (type == "DICTIONARY" || type == "ACDBDICTIONARYWDFLT"))
      owner.emplace(value, handle);
  }
  std::string out;
  out.reserve(dxf.size() + 16 * owner.size());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    out += lines[i];
    out += '\n';
    const bool owned_here = i >= begin && (i - begin) % 2 == 1 && trim(lines[i - 1]) == "5" &&
                            (i + 1 >= lines.size() || trim(lines[i + 1]) != "330");
    if (owned_here) {
      const auto found = owner.find(lines[i]);
      out += "330\n" + (found == owner.end() ? std::string("0") : found->second) + "\n";
    }
  }
  if (!dxf.empty() && dxf.back() != '\n') out.pop_back();
  return out;
}

// A plan Y as the file holds it: cutter beds and CAD pages start at the lower-left corner, so the
// file does too (Inkscape's DXF import put the floor half below the page). Adding half the sheet
// rounds a fold's Y by at most half an ulp of the sum (1.4e-14 mm on A4), far inside validate's
// 1e-6 mm fold tolerance.
double dxf_file_Y(const Sheet& sheet, double Y) { return Y + sheet.half_height_mm(); }

// The plan as the DXF's sections write it.
struct DxfDrawing {
  const Sheet& sheet;
  const ExportOptions& options;
  const DrawnPlan& drawn;
  std::vector<Layer> layers;  // those drawn, in cutting order

  double file_Y(double Y) const { return dxf_file_Y(sheet, Y); }
  bool r2000() const { return options.dxf_version == DxfVersion::R2000; }
};

// 999 comments: readers skip them (AutoCAD's OPEN ignores them), people and scripts read them.
void write_comments(DL_WriterA& dw, const DxfDrawing& drawing) {
  const ExportOptions& options = drawing.options;
  dw.dxfString(999, "origamic plan of " + one_line(options.model.empty() ? "a model" : options.model));
  dw.dxfString(999,
               "units: mm ($INSUNITS 4, $MEASUREMENT 1), scale 1:1; origin at the sheet's lower-left corner: X "
               "along the main fold from the left edge, Y up from the bottom edge; the main fold at Y = " +
                   mm_text(drawing.file_Y(0)));
  dw.dxfString(999, "sheet " + mm_text(drawing.sheet.width_mm) + " x " + mm_text(drawing.sheet.height_mm) + " mm");
  if (!options.settings.empty()) dw.dxfString(999, "settings: " + one_line(options.settings));
  dw.dxfString(999, fold_style_summary(options.folds));
  std::string order = "layers, in cutting order:";
  for (const Layer layer : drawing.layers) order += std::string(" ") + layer_style(layer, options.colours).name;
  dw.dxfString(999, order);
}

void write_header(DL_Dxf& dxf, DL_WriterA& dw, const Sheet& sheet) {
  dxf.writeHeader(dw);
  dw.dxfString(9, "$INSUNITS");
  dw.dxfInt(70, 4);  // millimetres
  dw.dxfString(9, "$MEASUREMENT");
  dw.dxfInt(70, 1);  // metric
  dw.dxfString(9, "$EXTMIN");
  dw.dxfReal(10, 0.0);
  dw.dxfReal(20, 0.0);
  dw.dxfString(9, "$EXTMAX");
  dw.dxfReal(10, sheet.width_mm);
  dw.dxfReal(20, sheet.height_mm);
  dw.sectionEnd();
}

void write_layer_table(DL_Dxf& dxf, DL_WriterA& dw, const DxfDrawing& drawing) {
  dw.tableLayers(static_cast<int>(drawing.layers.size()) + 1);
  dxf.writeLayer(dw, DL_LayerData("0", 0), DL_Attributes("", 7, 0, "CONTINUOUS", 1.0));
  for (const Layer layer : drawing.layers) {
    const LayerStyle style = layer_style(layer, drawing.options.colours);
    dxf.writeLayer(dw, DL_LayerData(style.name, 0), DL_Attributes("", style.aci, 0, "CONTINUOUS", 1.0));
  }
  dw.tableEnd();
}

void write_tables(DL_Dxf& dxf, DL_WriterA& dw, const DxfDrawing& drawing) {
  dw.sectionTables();
  dxf.writeVPort(dw);
  dw.tableLinetypes(3);
  dxf.writeLinetype(dw, DL_LinetypeData("BYBLOCK", "", 0, 0, 0.0));
  dxf.writeLinetype(dw, DL_LinetypeData("BYLAYER", "", 0, 0, 0.0));
  dxf.writeLinetype(dw, DL_LinetypeData("CONTINUOUS", "Solid line", 0, 0, 0.0));
  dw.tableEnd();
  write_layer_table(dxf, dw, drawing);
  dw.tableStyle(1);
  // dxflib gives R2000's DIMSTYLE the text style's handle (340) only for a style named exactly
  // "Standard", else an uninitialised value; R12 has no handles and keeps the name it always had.
  dxf.writeStyle(dw, DL_StyleData(drawing.r2000() ? "Standard" : "standard", 0, 2.5, 1.0, 0.0, 0, 2.5, "txt", ""));
  dw.tableEnd();
  dxf.writeView(dw);
  dxf.writeUcs(dw);
  dw.tableAppid(1);
  dxf.writeAppid(dw, "ACAD");
  dw.tableEnd();
  dxf.writeDimStyle(dw, 1, 1, 1, 1, 1);
  if (drawing.r2000()) {
    dxf.writeBlockRecord(dw);
    dw.tableEnd();
  }
  dw.sectionEnd();
}

void write_blocks(DL_Dxf& dxf, DL_WriterA& dw, const DxfDrawing& drawing) {
  dw.sectionBlocks();
  dxf.writeBlock(dw, DL_BlockData("*Model_Space", 0, 0.0, 0.0, 0.0));
  dxf.writeEndBlock(dw, "*Model_Space");
  dxf.writeBlock(dw, DL_BlockData("*Paper_Space", 0, 0.0, 0.0, 0.0));
  dxf.writeEndBlock(dw, "*Paper_Space");
  if (drawing.r2000()) {  // dxflib's block records and layouts name it
    dxf.writeBlock(dw, DL_BlockData("*Paper_Space0", 0, 0.0, 0.0, 0.0));
    dxf.writeEndBlock(dw, "*Paper_Space0");
  }
  dw.sectionEnd();
}

void write_entities(DL_Dxf& dxf, DL_WriterA& dw, const DxfDrawing& drawing) {
  dw.sectionEntities();
  // Points as the file holds them: a ring whose ends meet there is closed, its last point left out.
  const auto in_file = [&](const PlanPoint& p) { return std::pair{p.X, drawing.file_Y(p.Y)}; };
  auto write_polyline = [&](const std::vector<PlanPoint>& points, const DL_Attributes& attributes) {
    const bool closed = points.size() > 3 && in_file(points.front()) == in_file(points.back());
    const std::size_t count = points.size() - (closed ? 1 : 0);
    dxf.writePolyline(dw, DL_PolylineData(static_cast<int>(count), 0, 0, closed ? 1 : 0), attributes);
    for (std::size_t i = 0; i < count; ++i)
      dxf.writeVertex(dw, DL_VertexData(points[i].X, drawing.file_Y(points[i].Y), 0.0, 0.0));
    dxf.writePolylineEnd(dw);
  };
  for (const Layer layer : drawing.layers) {
    const LayerStyle style = layer_style(layer, drawing.options.colours);
    const DL_Attributes attributes(style.name, style.aci, 0, "CONTINUOUS", 1.0);
    for (const DrawnLine& line : drawing.drawn.lines) {
      if (line.layer != layer) continue;
      if (!drawn_in_pieces(line)) {
        if (const std::vector<PlanPoint> points = as_written(line.points, in_file); !points.empty())
          write_polyline(points, attributes);  // one entity per chain
        continue;
      }
      for (const std::vector<PlanPoint>& piece : dash_pieces(line)) {
        const std::vector<PlanPoint> p = as_written(piece, in_file);
        if (p.size() == 2)
          dxf.writeLine(dw, DL_LineData(p[0].X, drawing.file_Y(p[0].Y), 0.0, p[1].X, drawing.file_Y(p[1].Y), 0.0),
                        attributes);
        else if (!p.empty())
          write_polyline(p, attributes);
      }
    }
  }
  dw.sectionEnd();
}

void write_dxf(const std::string& path, const DxfDrawing& drawing) {
  const DL_Codes::version flavour =
      drawing.options.dxf_version == DxfVersion::R12 ? DL_Codes::AC1009 : DL_Codes::AC1015;
  DL_Dxf dxf;
  std::unique_ptr<DL_WriterA> dw(dxf.out(path.c_str(), flavour));
  if (!dw || dw->openFailed()) throw OutputError("DXF: cannot write the temporary file " + path);
  write_comments(*dw, drawing);
  write_header(dxf, *dw, drawing.sheet);
  write_tables(dxf, *dw, drawing);
  write_blocks(dxf, *dw, drawing);
  write_entities(dxf, *dw, drawing);
  if (drawing.r2000()) {
    dxf.writeObjects(*dw);
    dxf.writeObjectsEnd(*dw);
  }
  dw->dxfEOF();
  dw->close();
}

// dxflib writes to a named file only: a private temporary one, removed when done.
struct TemporaryFile {
  std::string path = (std::filesystem::temp_directory_path() / "origamic-dxf-XXXXXX").string();

  TemporaryFile() {
    const int fd = ::mkstemp(path.data());
    if (fd < 0)
      throw OutputError("DXF: cannot create a temporary file in " + std::filesystem::temp_directory_path().string());
    ::close(fd);
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() { std::remove(path.c_str()); }
};

std::string read_back(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) throw OutputError("DXF: cannot read back the temporary file " + path);
  if (bytes.size() < 4 || bytes.compare(bytes.size() - 4, 4, "EOF\n") != 0)
    throw OutputError("DXF: dxflib wrote an incomplete file (disk full?)");
  return bytes;
}

}  // namespace

std::vector<PlanPolyline> plan_dxf_lines(const Plan& plan) {
  const auto in_file = [&](const PlanPoint& p) { return std::pair{p.X, dxf_file_Y(plan.sheet, p.Y)}; };
  std::vector<PlanPolyline> lines;
  for (const PlanPolyline& line : plan.lines) {
    std::vector<PlanPoint> points = as_written(line.points, in_file);
    if (points.empty()) continue;
    for (PlanPoint& p : points) p.Y = dxf_file_Y(plan.sheet, p.Y);
    lines.push_back({line.kind, std::move(points)});
  }
  return lines;
}

std::string plan_dxf(const Plan& plan, const ExportOptions& options) {
  const DrawnPlan drawn = draw_plan(plan, options.folds);
  const DxfDrawing drawing{plan.sheet, options, drawn, used_layers(drawn)};
  const TemporaryFile temp;
  write_dxf(temp.path, drawing);
  const std::string bytes = read_back(temp.path);
  return drawing.r2000() ? with_object_owners(bytes) : bytes;
}

}  // namespace origamic
