// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/plan_dxf_reader.hpp"

#include <dxflib/dl_creationadapter.h>
#include <dxflib/dl_dxf.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <climits>
#include <cstdint>
#include <cstdlib>
#include <string_view>
#include <vector>
#include <cmath>
#include <fstream>
#include <iterator>
#include <optional>
#include <set>
#include <sstream>

#include "origamic/error.hpp"

namespace origamic {
namespace {

std::string upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// dxflib reads lines into a 1,024-byte buffer and loops forever on a longer one; no DXF writer
// writes lines near this long (text is split into 250-character groups).
constexpr std::size_t kLongestLine = 1000;

bool is_real_code(int code) {
  return (code >= 10 && code <= 59) || (code >= 110 && code <= 149) || (code >= 210 && code <= 239) ||
         (code >= 460 && code <= 469) || (code >= 1010 && code <= 1059);
}
bool is_integer_code(int code) {
  return (code >= 60 && code <= 99) || (code >= 170 && code <= 179) || (code >= 270 && code <= 289) ||
         (code >= 370 && code <= 389) || (code >= 400 && code <= 409) || (code >= 420 && code <= 429) ||
         (code >= 440 && code <= 459) || (code >= 1060 && code <= 1071);
}

// The groups dxflib reads as counts of an entity's parts and allocates as many for, in the ENTITIES
// and BLOCKS sections alike: vertices of an LWPOLYLINE, knots and points of a SPLINE, vertices of a
// LEADER, vertices and elements of an MLINE, paths and edges of a HATCH. (Other groups of these
// codes are flags, indices or colours, which may be large or negative.)
bool counts_parts(std::string_view entity, int code) {
  if (entity == "LWPOLYLINE") return code == 90;
  if (entity == "SPLINE") return code >= 72 && code <= 74;
  if (entity == "LEADER") return code == 76;
  if (entity == "MLINE") return code == 72 || code == 73;
  if (entity == "HATCH") return code == 91 || code == 93;
  return false;
}

// The file's group pairs must start with `0 SECTION` (after comments) and end with `0 EOF`: dxflib
// reads anything without complaint, so a text file or a truncated download is caught here. Every
// pair is checked before dxflib sees it, which trusts them: its code a number, a real a finite number
// (dxflib reads "nan" as 0), an integer one that fits 32 bits, and a count of an entity's vertices or
// other parts no more than the groups left in the file (dxflib allocates what a count says).
void check_structure(const std::string& bytes, const std::string& name) {
  if (bytes.empty()) throw InputError(name + ": empty file");
  if (bytes.rfind("AutoCAD Binary DXF", 0) == 0)
    throw InputError(name + ": binary DXF is not supported; save it as ASCII DXF");
  std::vector<std::string_view> lines;
  for (std::size_t at = 0; at < bytes.size();) {
    std::size_t end = bytes.find('\n', at);
    if (end == std::string::npos) end = bytes.size();
    if (end - at > kLongestLine)
      throw InputError(name + ": line " + std::to_string(lines.size() + 1) + " is longer than " +
                       std::to_string(kLongestLine) + " characters; no DXF line is");
    lines.emplace_back(bytes.data() + at, end - at);
    at = end + 1;
  }
  const auto trim = [](std::string_view text) {
    const auto first = text.find_first_not_of(" \t\r");
    if (first == std::string_view::npos) return std::string_view{};
    return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
  };
  const auto at_line = [&](std::size_t i) { return name + ": line " + std::to_string(i + 1) + ": "; };
  bool started = false;
  std::string_view last_code, last_value, entity;
  for (std::size_t i = 0; i + 1 < lines.size(); i += 2) {
    const std::string_view code_text = trim(lines[i]), value = trim(lines[i + 1]);
    if (code_text.empty() && value.empty()) continue;
    int code = 0;
    if (const auto [end, error] = std::from_chars(code_text.data(), code_text.data() + code_text.size(), code);
        error != std::errc() || end != code_text.data() + code_text.size() || code < 0 || code > 1071) {
      if (!started) throw InputError(name + ": not a DXF file (it does not start with a SECTION)");
      throw InputError(at_line(i) + "a group code must be a number from 0 to 1071");
    }
    if (!started) {
      if (code == 999) continue;
      if (code != 0 || value != "SECTION")
        throw InputError(name + ": not a DXF file (it does not start with a SECTION)");
      started = true;
    }
    if (is_real_code(code)) {
      const std::string text(value);
      char* end = nullptr;
      const double number = std::strtod(text.c_str(), &end);
      if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(number))
        throw InputError(at_line(i + 1) + "group " + std::to_string(code) + " must hold a finite number");
    } else if (is_integer_code(code)) {
      long long number = 0;
      if (const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), number);
          error != std::errc() || end != value.data() + value.size() || number < INT32_MIN || number > INT32_MAX)
        throw InputError(at_line(i + 1) + "group " + std::to_string(code) + " must hold a 32-bit whole number");
      const auto pairs_left = static_cast<long long>((lines.size() - i) / 2);
      if (counts_parts(entity, code) && (number < 0 || number > pairs_left))
        throw InputError(at_line(i + 1) + "group " + std::to_string(code) + " counts " + std::to_string(number) +
                         " parts where the file has " + std::to_string(pairs_left) + " groups left");
    }
    if (code == 0) entity = value;
    last_code = code_text, last_value = value;
  }
  if (!started) throw InputError(name + ": not a DXF file (it does not start with a SECTION)");
  if (last_code != "0" || last_value != "EOF") throw InputError(name + ": truncated DXF (no EOF at its end)");
}

class Reader : public DL_CreationAdapter {
 public:
  Reader(const LayerNames& layers, std::string name) : name_(std::move(name)) {
    layers_ = {{upper(layers.cut), LineKind::Cut},
               {upper(layers.mountain), LineKind::Mountain},
               {upper(layers.valley), LineKind::Valley},
               {upper(layers.outline), LineKind::Outline},
               {upper(layers.cut_out), LineKind::CutOut},
               {upper(layers.perforated_mountain), LineKind::Mountain, true},
               {upper(layers.perforated_valley), LineKind::Valley, true}};
  }

  DxfDrawing drawing;

  void setVariableInt(const std::string& key, int value, int) override {
    if (key == "$INSUNITS") insunits_ = value;
  }
  void addBlock(const DL_BlockData&) override { in_block_ = true; }
  void endBlock() override { in_block_ = false; }

  void addLine(const DL_LineData& data) override {
    const auto layer = layer_of_entity("LINE");
    if (!layer) return;
    check_finite({data.x1, data.y1, data.x2, data.y2}, "LINE");
    drawing.lines.push_back({layer->kind, {{data.x1, data.y1}, {data.x2, data.y2}}, layer->perforation});
  }

  void addPolyline(const DL_PolylineData& data) override {
    finish_polyline();
    const auto layer = layer_of_entity("POLYLINE");
    if (!layer) return;
    if (data.flags & (16 | 64))
      throw InputError(name_ + ": a mesh POLYLINE on layer " + getAttributes().getLayer() + "; a plan is drawn in 2D");
    // 2D polylines are in their object coordinate system; 3D ones (flag 8) in world coordinates.
    const bool world = (data.flags & 8) != 0;
    const double* direction = getExtrusion()->getDirection();
    if (!world && (direction[0] != 0 || direction[1] != 0 || direction[2] == 0))
      throw InputError(name_ + ": a POLYLINE on layer " + getAttributes().getLayer() +
                       " is not in the XY plane (extrusion is not +-Z)");
    polyline_ = PlanPolyline{layer->kind, {}, layer->perforation};
    polyline_layer_ = layer->name;
    closed_ = (data.flags & 1) != 0;
    mirrored_ = !world && direction[2] < 0;
  }

  void addVertex(const DL_VertexData& data) override {
    if (!polyline_) return;
    if (data.bulge != 0)
      throw InputError(name_ + ": an arc (bulge) in a polyline on layer " + polyline_layer_ +
                       "; arcs are not supported: flatten them into straight segments");
    check_finite({data.x, data.y}, "VERTEX");
    polyline_->points.push_back({mirrored_ ? -data.x : data.x, data.y});
  }

  void endEntity() override { finish_polyline(); }    // after an LWPOLYLINE
  void endSequence() override { finish_polyline(); }  // SEQEND after a POLYLINE's VERTEXes

  void addArc(const DL_ArcData&) override { reject_curve("ARC"); }
  void addCircle(const DL_CircleData&) override { reject_curve("CIRCLE"); }
  void addEllipse(const DL_EllipseData&) override { reject_curve("ELLIPSE"); }
  void addSpline(const DL_SplineData&) override { reject_curve("SPLINE"); }
  void addInsert(const DL_InsertData&) override {
    if (in_block_ || getAttributes().isInPaperSpace()) return;
    // A block reference may carry lines on any layer: its contents are not read.
    throw InputError(name_ + ": a block reference (INSERT) on layer " + getAttributes().getLayer() +
                     "; explode blocks before validating");
  }
  void addText(const DL_TextData&) override { ignore(); }
  void addMText(const DL_MTextData&) override { ignore(); }
  void addPoint(const DL_PointData&) override { ignore(); }

  // Called once the whole file is read.
  void finish() {
    finish_polyline();
    switch (insunits_) {
      case 0:
      case 4:
        drawing.unit = DrawingUnit::Millimetre;
        break;
      case 1:
        drawing.unit = DrawingUnit::Inch;
        break;
      case 2:
        drawing.unit = DrawingUnit::Foot;
        break;
      case 5:
        drawing.unit = DrawingUnit::Centimetre;
        break;
      case 6:
        drawing.unit = DrawingUnit::Metre;
        break;
      default:
        throw InputError(name_ + ": unsupported drawing unit $INSUNITS = " + std::to_string(insunits_) +
                         " (mm, cm, m, inches and feet are read)");
    }
    drawing.other_layers.assign(other_layers_.begin(), other_layers_.end());
    const bool any =
        std::ranges::any_of(drawing.lines, [](const PlanPolyline& l) { return l.kind != LineKind::Outline; });
    if (!any) {
      std::string found;
      for (const std::string& layer : other_layers_) found += (found.empty() ? "" : ", ") + layer;
      throw InputError(name_ + ": no line on the layers " + layer_name(LineKind::Cut) + ", " +
                       layer_name(LineKind::Mountain) + " or " + layer_name(LineKind::Valley) +
                       (found.empty()
                            ? std::string(" (the file has no other entity)")
                            : " (entities are on: " + found + ": name the layers that hold the plan's lines)"));
    }
  }

 private:
  std::string name_;
  struct Layer {
    std::string name;
    LineKind kind = LineKind::Cut;
    bool perforation = false;
  };
  std::vector<Layer> layers_;
  std::set<std::string> other_layers_;
  std::optional<PlanPolyline> polyline_;
  std::string polyline_layer_;  // the current polyline's layer, as the reader names it
  bool closed_ = false, mirrored_ = false, in_block_ = false;
  int insunits_ = 4;

  std::string layer_name(LineKind kind) const {
    for (const Layer& layer : layers_)
      if (layer.kind == kind) return layer.name;
    return "?";
  }

  // The kind of the current entity, or nothing for entities that are not part of the plan.
  std::optional<Layer> layer_of_entity(const char*) {
    if (in_block_ || getAttributes().isInPaperSpace()) return std::nullopt;
    const std::string name = upper(getAttributes().getLayer());
    for (const Layer& layer : layers_)
      if (layer.name == name) return layer;
    ignore();
    return std::nullopt;
  }

  void ignore() {
    if (in_block_ || getAttributes().isInPaperSpace()) return;
    ++drawing.ignored_entities;
    other_layers_.insert(getAttributes().getLayer());
  }

  void reject_curve(const char* entity) {
    if (!layer_of_entity(entity)) return;
    throw InputError(name_ + ": " + entity + " on layer " + getAttributes().getLayer() +
                     "; curves are not supported: flatten them into straight segments");
  }

  // A card is well under a metre; a coordinate beyond 10 km in any unit is no plan (and would take
  // the validator's arithmetic far from the sheet).
  void check_finite(std::initializer_list<double> values, const char* entity) {
    for (const double v : values)
      if (!std::isfinite(v))
        throw InputError(name_ + ": a " + std::string(entity) + " on layer " + getAttributes().getLayer() +
                         " has a coordinate that is not a finite number");
      else if (std::abs(v) > 1e7)
        throw InputError(name_ + ": a " + std::string(entity) + " on layer " + getAttributes().getLayer() +
                         " has a coordinate beyond 10,000,000 drawing units");
  }

  void finish_polyline() {
    if (!polyline_) return;
    PlanPolyline line = std::move(*polyline_);
    polyline_.reset();
    if (closed_ && line.points.size() >= 2 &&
        (line.points.front().X != line.points.back().X || line.points.front().Y != line.points.back().Y))
      line.points.push_back(line.points.front());
    if (!line.points.empty()) drawing.lines.push_back(std::move(line));
  }
};

}  // namespace

double mm_per_unit(DrawingUnit unit) {
  switch (unit) {
    case DrawingUnit::Millimetre:
      return 1;
    case DrawingUnit::Centimetre:
      return 10;
    case DrawingUnit::Metre:
      return 1000;
    case DrawingUnit::Inch:
      return 25.4;
    case DrawingUnit::Foot:
      return 304.8;
  }
  return 1;
}

const char* to_string(DrawingUnit unit) {
  switch (unit) {
    case DrawingUnit::Millimetre:
      return "mm";
    case DrawingUnit::Centimetre:
      return "cm";
    case DrawingUnit::Metre:
      return "m";
    case DrawingUnit::Inch:
      return "in";
    case DrawingUnit::Foot:
      return "ft";
  }
  return "?";
}

DxfDrawing read_dxf_drawing(const std::filesystem::path& file, const LayerNames& layers) {
  const std::string name = file.string();
  std::error_code error;
  if (!std::filesystem::exists(file, error)) throw InputError(name + ": no such file");
  if (std::filesystem::is_directory(file, error)) throw InputError(name + ": is a folder, not a DXF file");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(name + ": cannot open for reading");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(name + ": read error");
  check_structure(bytes, name);

  Reader reader(layers, name);
  std::istringstream stream(bytes);
  DL_Dxf dxf;
  if (!dxf.in(stream, &reader)) throw InputError(name + ": cannot read");
  reader.finish();
  return std::move(reader.drawing);
}

std::vector<PlanPolyline> read_plan_dxf(const std::filesystem::path& file, const LayerNames& layers) {
  DxfDrawing drawing = read_dxf_drawing(file, layers);
  const double scale = mm_per_unit(drawing.unit);
  if (scale != 1)
    for (PlanPolyline& line : drawing.lines)
      for (PlanPoint& p : line.points) p = {p.X * scale, p.Y * scale};
  return std::move(drawing.lines);
}

}  // namespace origamic
