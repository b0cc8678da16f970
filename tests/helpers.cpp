// SPDX-License-Identifier: GPL-3.0-or-later
#include "helpers.hpp"

#include <sys/wait.h>
#include <zlib.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <glm/geometric.hpp>
#include <iterator>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>
#include <stdexcept>

#include "origamic/raster.hpp"
#include "origamic/segment.hpp"
#include "origamic/slice.hpp"

namespace origamic::test {

TriangleMesh box(const glm::dvec3& lo, const glm::dvec3& hi) {
  TriangleMesh mesh;
  for (int i = 0; i < 8; ++i)
    mesh.positions.emplace_back(i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z);
  // Two triangles a side, counter-clockwise seen from outside.
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                    {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return mesh;
}

TriangleMesh prism(const Floor& floor, double h0, double h1) {
  TriangleMesh mesh;
  const auto n = static_cast<std::uint32_t>(floor.size());
  for (const double h : {h0, h1})
    for (const auto& [x, d] : floor) mesh.positions.emplace_back(x, h, d);
  for (std::uint32_t i = 1; i + 1 < n; ++i) {
    mesh.triangles.push_back({0, i + 1, i});          // bottom, facing down
    mesh.triangles.push_back({n, n + i, n + i + 1});  // top, facing up
  }
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint32_t j = (i + 1) % n;
    mesh.triangles.push_back({i, j, n + j});
    mesh.triangles.push_back({i, n + j, n + i});
  }
  return mesh;
}

std::vector<PlanRegion> box_popup_regions(const Sheet& sheet, double x0, double x1, double h, double d) {
  const double W = sheet.width_mm, half = sheet.half_height_mm();
  std::vector<PlanRegion> regions(4);
  regions[0].orientation = Orientation::V;  // back plane
  regions[0].rings = {{{0, 0}, {x0, 0}, {x0, h}, {x1, h}, {x1, 0}, {W, 0}, {W, half}, {0, half}}};
  regions[1].orientation = Orientation::H;  // floor
  regions[1].rings = {{{0, -half}, {W, -half}, {W, 0}, {x1, 0}, {x1, -d}, {x0, -d}, {x0, 0}, {0, 0}}};
  regions[2].orientation = Orientation::V;  // front
  regions[2].depth_mm = d;
  regions[2].rings = {{{x0, -d}, {x1, -d}, {x1, h - d}, {x0, h - d}}};
  regions[3].orientation = Orientation::H;  // top
  regions[3].depth_mm = h;
  regions[3].rings = {{{x0, h - d}, {x1, h - d}, {x1, h}, {x0, h}}};
  for (PlanRegion& r : regions) r.placed = true;
  return regions;
}

RasterMaps blank_maps(const PixelGrid& grid, HitKind kind) {
  RasterMaps maps;
  maps.grid = grid;
  maps.kind = Grid<HitKind>(grid.cols, grid.rows, kind);
  maps.d_mm = Grid<double>(grid.cols, grid.rows, 0);
  maps.h_mm = Grid<double>(grid.cols, grid.rows, 0);
  maps.normal = Grid<glm::vec3>(grid.cols, grid.rows, glm::vec3(0, 0, 1));
  maps.break_right = Grid<float>(grid.cols, grid.rows, std::numeric_limits<float>::quiet_NaN());
  maps.break_below = Grid<float>(grid.cols, grid.rows, std::numeric_limits<float>::quiet_NaN());
  return maps;
}

double twice_signed_area(const std::vector<PlanPoint>& ring) {
  double twice = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const PlanPoint &p = ring[i], &q = ring[(i + 1) % ring.size()];
    twice += p.X * q.Y - q.X * p.Y;
  }
  return twice;
}

std::string box_obj(const glm::dvec3& size, bool corner_normals, bool inward) {
  std::ostringstream text;
  for (int v = 0; v < 8; ++v)
    text << "v " << size.x * (v & 1) << ' ' << size.y * (v >> 1 & 1) << ' ' << size.z * (v >> 2 & 1) << '\n';
  if (corner_normals)
    for (int v = 0; v < 8; ++v)
      text << "vn " << 2 * (v & 1) - 1 << ' ' << 2 * (v >> 1 & 1) - 1 << ' ' << 2 * (v >> 2 & 1) - 1 << '\n';
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    text << 'f';
    for (int k = 0; k < 4; ++k) {
      const int v = (inward ? q[3 - k] : q[k]) + 1;
      text << ' ' << v;
      if (corner_normals) text << "//" << v;
    }
    text << '\n';
  }
  return text.str();
}

TriangleMesh merged(const TriangleMesh& a, const TriangleMesh& b) {
  TriangleMesh m = a;
  const auto offset = static_cast<std::uint32_t>(a.positions.size());
  m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
  for (auto t : b.triangles) m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  return m;
}

TriangleMesh sphere(const glm::dvec3& centre, double radius, int segments, int rings) {
  TriangleMesh mesh;
  const double pi = std::numbers::pi;
  const std::uint32_t top = 0;
  mesh.positions.push_back(centre + glm::dvec3(0, radius, 0));
  for (int r = 1; r < rings; ++r) {
    const double polar = pi * r / rings;
    for (int s = 0; s < segments; ++s) {
      const double azimuth = 2 * pi * s / segments;
      mesh.positions.push_back(centre + radius * glm::dvec3(std::sin(polar) * std::cos(azimuth), std::cos(polar),
                                                            std::sin(polar) * std::sin(azimuth)));
    }
  }
  const auto bottom = static_cast<std::uint32_t>(mesh.positions.size());
  mesh.positions.push_back(centre - glm::dvec3(0, radius, 0));
  // Ring r (1 .. rings - 1), segment s.
  auto at = [&](int r, int s) { return static_cast<std::uint32_t>(1 + (r - 1) * segments + (s % segments)); };
  for (int s = 0; s < segments; ++s) {
    mesh.triangles.push_back({top, at(1, s + 1), at(1, s)});
    mesh.triangles.push_back({bottom, at(rings - 1, s), at(rings - 1, s + 1)});
    for (int r = 1; r < rings - 1; ++r) {
      mesh.triangles.push_back({at(r, s), at(r, s + 1), at(r + 1, s)});
      mesh.triangles.push_back({at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)});
    }
  }
  return mesh;
}

TempDir::TempDir() {
  static std::mt19937_64 random{std::random_device{}()};
  path = std::filesystem::temp_directory_path() / ("origamic-test-" + std::to_string(random()));
  std::filesystem::create_directories(path);
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path, ignored);
}

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

std::string read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + file.string());
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

namespace {

std::string number(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

std::string xyz(const glm::dvec3& p) { return number(p.x) + " " + number(p.y) + " " + number(p.z); }

glm::dvec3 unit_normal(const TriangleMesh& mesh, const std::array<std::uint32_t, 3>& t) {
  return glm::normalize(glm::cross(mesh.positions[t[1]] - mesh.positions[t[0]],
                                   mesh.positions[t[2]] - mesh.positions[t[0]]));
}

}  // namespace

void write_obj(const std::filesystem::path& file, const TriangleMesh& mesh) {
  std::string text = "# made by origamic's tests\n";
  for (const auto& p : mesh.positions) text += "v " + xyz(p) + "\n";
  for (const auto& t : mesh.triangles)
    text += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " + std::to_string(t[2] + 1) + "\n";
  write_text(file, text);
}

void write_off(const std::filesystem::path& file, const TriangleMesh& mesh) {
  std::string text =
      "OFF\n" + std::to_string(mesh.positions.size()) + " " + std::to_string(mesh.triangles.size()) + " 0\n";
  for (const auto& p : mesh.positions) text += xyz(p) + "\n";
  for (const auto& t : mesh.triangles)
    text += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  write_text(file, text);
}

void write_ply_ascii(const std::filesystem::path& file, const TriangleMesh& mesh) {
  std::string text = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(mesh.positions.size()) +
                     "\nproperty double x\nproperty double y\nproperty double z\nelement face " +
                     std::to_string(mesh.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : mesh.positions) text += xyz(p) + "\n";
  for (const auto& t : mesh.triangles)
    text += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  write_text(file, text);
}

void write_ply_binary(const std::filesystem::path& file, const TriangleMesh& mesh) {
  std::string text = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(mesh.positions.size()) +
                     "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                     std::to_string(mesh.triangles.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : mesh.positions)
    for (int k = 0; k < 3; ++k) {
      const float v = static_cast<float>(p[k]);
      text.append(reinterpret_cast<const char*>(&v), 4);
    }
  for (const auto& t : mesh.triangles) {
    text.push_back(3);
    for (auto i : t) {
      const std::int32_t v = static_cast<std::int32_t>(i);
      text.append(reinterpret_cast<const char*>(&v), 4);
    }
  }
  write_text(file, text);
}

void write_stl_ascii(const std::filesystem::path& file, const TriangleMesh& mesh) {
  std::string text = "solid test\n";
  for (const auto& t : mesh.triangles) {
    text += "facet normal " + xyz(unit_normal(mesh, t)) + "\nouter loop\n";
    for (auto i : t) text += "vertex " + xyz(mesh.positions[i]) + "\n";
    text += "endloop\nendfacet\n";
  }
  write_text(file, text + "endsolid test\n");
}

void write_stl_binary(const std::filesystem::path& file, const TriangleMesh& mesh) {
  std::string bytes(80, ' ');
  bytes.replace(0, 14, "origamic tests");
  const std::uint32_t count = static_cast<std::uint32_t>(mesh.triangles.size());
  bytes.append(reinterpret_cast<const char*>(&count), 4);
  auto put = [&](const glm::dvec3& v) {
    for (int k = 0; k < 3; ++k) {
      const float f = static_cast<float>(v[k]);
      bytes.append(reinterpret_cast<const char*>(&f), 4);
    }
  };
  for (const auto& t : mesh.triangles) {
    put(unit_normal(mesh, t));
    for (auto i : t) put(mesh.positions[i]);
    bytes.append(2, '\0');
  }
  write_text(file, bytes);
}

void gzip_file(const std::filesystem::path& from, const std::filesystem::path& to) {
  const std::string bytes = read_bytes(from);
  gzFile gz = gzopen(to.c_str(), "wb");
  if (!gz || gzwrite(gz, bytes.data(), static_cast<unsigned>(bytes.size())) != static_cast<int>(bytes.size()))
    throw std::runtime_error("cannot gzip to " + to.string());
  gzclose(gz);
}

CommandResult shell(const std::string& command) {
  CommandResult result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 65536> buffer{};
  std::size_t got = 0;
  while ((got = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), got);
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::filesystem::path models_dir() {
  const std::filesystem::path dir = ORIGAMIC_MODELS_DIR;
  return std::filesystem::exists(dir / "MANIFEST.tsv") ? dir : std::filesystem::path();
}

std::vector<ManifestEntry> manifest() {
  std::vector<ManifestEntry> entries;
  std::ifstream in(models_dir() / "MANIFEST.tsv");
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::istringstream cells(line);
    for (std::string cell; std::getline(cells, cell, '\t');) fields.push_back(cell);
    if (fields.size() > 9) entries.push_back({fields[0], std::stoul(fields[4]), fields[9]});
  }
  return entries;
}

CommandRun run_origamic(const std::string& arguments, bool stdout_only) {
  const std::string command = std::string(ORIGAMIC_EXE) + " " + arguments + (stdout_only ? " 2>/dev/null" : " 2>&1");
  CommandRun result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) result.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

std::string quoted(const std::filesystem::path& path) {
  std::string text = path.string();
  text.insert(text.begin(), '\'');
  text.push_back('\'');
  return text;
}

std::vector<PlanPolyline> box_plan(double d, double h, double x0, double x1) {
  const double width = 210, half = 148.5;
  return {{LineKind::Outline, {{0, -half}, {width, -half}, {width, half}, {0, half}, {0, -half}}},
          {LineKind::Valley, {{0, 0}, {x0, 0}}},
          {LineKind::Valley, {{x1, 0}, {width, 0}}},
          {LineKind::Cut, {{x0, -d}, {x0, h}}},
          {LineKind::Cut, {{x1, -d}, {x1, h}}},
          {LineKind::Valley, {{x0, -d}, {x1, -d}}},
          {LineKind::Mountain, {{x0, h - d}, {x1, h - d}}},
          {LineKind::Valley, {{x0, h}, {x1, h}}}};
}

std::string dxf_text(const std::vector<PlanPolyline>& lines, int insunits, const DxfLayers& layers) {
  std::ostringstream out;
  auto pair = [&](int code, const std::string& value) { out << code << "\n" << value << "\n"; };
  auto real = [&](int code, double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.17g", value);
    pair(code, text);
  };
  auto layer = [&](LineKind kind) {
    switch (kind) {
      case LineKind::Cut: return layers.cut;
      case LineKind::Mountain: return layers.mountain;
      case LineKind::Valley: return layers.valley;
      case LineKind::Outline: return layers.outline;
      case LineKind::CutOut: return layers.cut_out;
    }
    return std::string("0");
  };
  pair(999, "written by origamic's tests");
  pair(0, "SECTION"), pair(2, "HEADER"), pair(9, "$INSUNITS"), pair(70, std::to_string(insunits)), pair(0, "ENDSEC");
  pair(0, "SECTION"), pair(2, "ENTITIES");
  for (const PlanPolyline& line : lines) {
    if (line.points.size() == 2) {
      pair(0, "LINE"), pair(8, layer(line.kind));
      real(10, line.points[0].X), real(20, line.points[0].Y), real(11, line.points[1].X), real(21, line.points[1].Y);
      continue;
    }
    const bool closed = line.points.size() > 3 && line.points.front().X == line.points.back().X &&
                        line.points.front().Y == line.points.back().Y;
    pair(0, "POLYLINE"), pair(8, layer(line.kind)), pair(66, "1"), pair(70, closed ? "1" : "0");
    for (std::size_t i = 0; i + (closed ? 1 : 0) < line.points.size(); ++i) {
      pair(0, "VERTEX"), pair(8, layer(line.kind));
      real(10, line.points[i].X), real(20, line.points[i].Y);
    }
    pair(0, "SEQEND"), pair(8, layer(line.kind));
  }
  pair(0, "ENDSEC"), pair(0, "EOF");
  return out.str();
}

namespace {

RasterPlan sliced(const RasterMaps& maps) { return slice(maps, segment(maps, SegmentOptions{}), SliceOptions{}); }

}  // namespace

FloatingBoxPlan::FloatingBoxPlan()
    : maps(raster(RayScene(box({60.2, 41.3, 18.6}, {150.7, 77.9, 47.1})), sheet, RasterOptions{})),
      raster_plan(sliced(maps)),
      exact_plan(maps, raster_plan, sheet, PlanOptions{}) {
  if (raster_plan.faces.size() > 2 && raster_plan.faces[2].orientation == Orientation::H) std::swap(front, top);
}

}  // namespace origamic::test
