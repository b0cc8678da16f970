// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/mesh_io.hpp"

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <new>
#include <sstream>
#include <string_view>

#include "mesh_bytes.hpp"
#include "mesh_checks.hpp"
#include "mesh_normals.hpp"
#include "mesh_text.hpp"
#include "origamic/error.hpp"
#include "quiet_openmesh.hpp"

namespace origamic {
namespace {

// An OpenMesh importer that keeps what its readers parse as a plain triangle soup. Building a
// halfedge mesh only to flatten it again cost a third of a large model's load, and the halfedge
// mesh split non-manifold faces off their neighbours' vertices.
class SoupImporter final : public OpenMesh::IO::BaseImporter {
 public:
  std::vector<OpenMesh::Vec3d> points;
  std::vector<OpenMesh::Vec3f> normals;  // per point; zero where the file gave none
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::size_t out_of_range = 0;     // faces refused for naming a vertex the file does not have
  std::size_t repeated_corner = 0;  // faces passed over for a corner repeated (no area)

  using VertexHandle = OpenMesh::VertexHandle;
  using FaceHandle = OpenMesh::FaceHandle;
  using HalfedgeHandle = OpenMesh::HalfedgeHandle;
  using EdgeHandle = OpenMesh::EdgeHandle;

  VertexHandle add_vertex(const OpenMesh::Vec3f& point) override { return add_vertex(OpenMesh::Vec3d(point)); }
  VertexHandle add_vertex(const OpenMesh::Vec3d& point) override {
    points.push_back(point);
    normals.emplace_back(0.f, 0.f, 0.f);
    return VertexHandle(static_cast<int>(points.size() - 1));
  }
  VertexHandle add_vertex() override { return add_vertex(OpenMesh::Vec3d(0, 0, 0)); }
  void set_point(VertexHandle v, const OpenMesh::Vec3f& point) override {
    if (holds(v)) points[static_cast<std::size_t>(v.idx())] = OpenMesh::Vec3d(point);
  }
  void set_normal(VertexHandle v, const OpenMesh::Vec3f& normal) override {
    if (holds(v)) normals[static_cast<std::size_t>(v.idx())] = normal;
  }
  void set_normal(VertexHandle v, const OpenMesh::Vec3d& normal) override { set_normal(v, OpenMesh::Vec3f(normal)); }

  // Like OpenMesh's own importer: a face with a vertex index out of range or a repeated vertex is
  // refused; a polygon becomes a fan of triangles around its first vertex.
  FaceHandle add_face(const VHandles& corners) override {
    if (corners.size() < 3) {  // OpenMesh's OBJ reader passes "f 1 2 2" on as two corners
      ++repeated_corner;
      return FaceHandle();
    }
    for (std::size_t i = 0; i < corners.size(); ++i) {
      if (!holds(corners[i])) {
        ++out_of_range;
        return FaceHandle();
      }
      for (std::size_t j = i + 1; j < corners.size(); ++j)
        if (corners[i] == corners[j]) {
          ++repeated_corner;
          return FaceHandle();
        }
    }
    const auto index = [&](std::size_t i) { return static_cast<std::uint32_t>(corners[i].idx()); };
    for (std::size_t i = 2; i < corners.size(); ++i) triangles.push_back({index(0), index(i - 1), index(i)});
    return FaceHandle(static_cast<int>(faces_++));
  }

  void reserve(unsigned int vertices, unsigned int, unsigned int faces) override {
    points.reserve(vertices);
    normals.reserve(vertices);
    triangles.reserve(faces);
  }
  std::size_t n_vertices() const override { return points.size(); }
  std::size_t n_faces() const override { return faces_; }
  std::size_t n_edges() const override { return 0; }

  // Connectivity, colours, texture coordinates and status: not kept.
  HalfedgeHandle add_edge(VertexHandle, VertexHandle) override { return HalfedgeHandle(); }
  FaceHandle add_face(HalfedgeHandle) override { return FaceHandle(); }
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec2f>&) override {}
  void add_face_texcoords(FaceHandle, VertexHandle, const std::vector<OpenMesh::Vec3f>&) override {}
  void set_face_texindex(FaceHandle, int) override {}
  void set_halfedge(VertexHandle, HalfedgeHandle) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_color(VertexHandle, const OpenMesh::Vec4f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(VertexHandle, const OpenMesh::Vec3f&) override {}
  void set_status(VertexHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_next(HalfedgeHandle, HalfedgeHandle) override {}
  void set_face(HalfedgeHandle, FaceHandle) override {}
  void request_face_texcoords2D() override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec2f&) override {}
  void set_texcoord(HalfedgeHandle, const OpenMesh::Vec3f&) override {}
  void set_status(HalfedgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec3f&) override {}
  void set_color(EdgeHandle, const OpenMesh::Vec4f&) override {}
  void set_status(EdgeHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_normal(FaceHandle, const OpenMesh::Vec3d&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4uc&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec3f&) override {}
  void set_color(FaceHandle, const OpenMesh::Vec4f&) override {}
  void set_status(FaceHandle, const OpenMesh::Attributes::StatusInfo&) override {}
  void add_texture_information(int, std::string) override {}

 private:
  bool holds(VertexHandle v) const { return v.idx() >= 0 && static_cast<std::size_t>(v.idx()) < points.size(); }

  std::size_t faces_ = 0;
};

using mesh_input::fail;
using mesh_input::for_each_line;
using mesh_input::is_blank_or_comment;
using mesh_input::is_statement;
using mesh_input::read_gzipped;
using mesh_input::read_plain;

std::string lower(std::string s) {
  std::ranges::transform(s, s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool ends_with_gz(const std::filesystem::path& file) { return lower(file.extension().string()) == ".gz"; }

// A binary STL is an 80-byte header, a triangle count and 50 bytes a triangle. Files that begin
// with "solid" are ASCII unless their size matches that layout exactly (some binary writers put
// "solid" in the header) or NUL bytes follow the header (such a file cut short).
bool is_binary_stl(const std::filesystem::path& file, const std::string& bytes) {
  const bool sized = bytes.size() >= 84 && [&] {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    return bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count);
  }();
  if (sized) return true;
  std::size_t start = 0;
  while (start < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[start]))) ++start;
  // A binary STL's header may begin with "solid" too: its first triangles (floats, and attribute
  // words mostly 0) hold NUL bytes, which no text has.
  const std::string_view after_header = std::string_view(bytes).substr(std::min<std::size_t>(bytes.size(), 84), 1024);
  if (bytes.compare(start, 5, "solid") == 0 && after_header.find('\0') == std::string_view::npos) return false;
  if (bytes.size() < 84) fail(file, "truncated binary STL (shorter than its 84-byte header)");
  std::uint32_t count = 0;
  std::memcpy(&count, bytes.data() + 80, 4);
  fail(file, "truncated or corrupt binary STL (header says " + std::to_string(count) +
                 " triangles, which need " + std::to_string(84 + 50 * std::uint64_t{count}) +
                 " bytes; the file has " + std::to_string(bytes.size()) + ")");
}

// What a text file promises, to catch files that end early or hold malformed numbers: OpenMesh's
// readers stop quietly at the end of the data and skip vertex lines they cannot parse.
struct Promised {
  long vertices = -1;      // vertex count of an OFF or PLY header, or "v" lines of an OBJ
  long data_needed = -1;   // lines an ASCII OFF or PLY must have after its header: vertices + faces
  long data_found = -1;    // lines it has
  long faces = -1;         // face count of an OFF or PLY header, or "f" lines of an OBJ
};

// Non-blank, non-comment lines from offset on.
long count_data_lines(const std::string& bytes, std::size_t offset) {
  long count = 0;
  for_each_line(bytes, offset, [&](std::string_view line, std::size_t) { count += !is_blank_or_comment(line); });
  return count;
}

Promised promised_counts(const std::string& format, const std::string& bytes) {
  Promised promised;
  if (format == "obj") {
    promised.vertices = 0, promised.faces = 0;
    for_each_line(bytes, 0, [&](std::string_view line, std::size_t) {
      promised.vertices += is_statement(line, 'v');
      promised.faces += is_statement(line, 'f');
    });
  } else if (format == "off") {
    std::istringstream in(bytes.substr(0, std::min<std::size_t>(bytes.size(), 4096)));
    std::string keyword, line;
    in >> keyword;  // OFF, COFF, NOFF, ...
    if (keyword.find("OFF") == std::string::npos || keyword.find("BINARY") != std::string::npos) return promised;
    while (in >> std::ws && in.peek() == '#') std::getline(in, line);
    long faces = 0;
    if (!(in >> promised.vertices >> faces)) return {};
    std::getline(in, line);
    promised.data_needed = promised.vertices + faces;
    promised.faces = faces;
    promised.data_found = count_data_lines(bytes, static_cast<std::size_t>(in.tellg()));
  } else if (format == "ply") {
    const std::size_t header_end = bytes.find("end_header");
    if (header_end == std::string::npos) return promised;
    std::istringstream in(bytes.substr(0, header_end));
    std::string line;
    bool ascii = false;
    long faces = 0;
    while (std::getline(in, line)) {
      std::istringstream words(line);
      std::string keyword, word;
      long count = -1;
      words >> keyword >> word;
      if (keyword == "format") ascii = word == "ascii";
      if (keyword == "element" && words >> count) {
        if (word == "vertex") promised.vertices = count;
        if (word == "face") faces = count;
      }
    }
    promised.faces = faces;
    if (ascii) {
      promised.data_needed = promised.vertices + faces;
      promised.data_found = count_data_lines(bytes, bytes.find('\n', header_end) + 1);
    }
  }
  return promised;
}

// The triangles read, over the vertices they use (unused vertices would otherwise count in the
// model's extent).
TriangleMesh triangle_soup(const SoupImporter& read, bool with_file_normals) {
  constexpr std::uint32_t unused = ~std::uint32_t{0};
  std::vector<std::uint32_t> new_index(read.points.size(), unused);
  TriangleMesh mesh;
  mesh.triangles.reserve(read.triangles.size());
  if (with_file_normals) mesh.corner_normals.reserve(3 * read.triangles.size());
  for (const auto& corners : read.triangles) {
    std::array<std::uint32_t, 3> triangle{};
    for (std::size_t corner = 0; corner < 3; ++corner) {
      const std::uint32_t v = corners[corner];
      std::uint32_t& index = new_index[v];
      if (index == unused) {
        index = static_cast<std::uint32_t>(mesh.positions.size());
        const auto& p = read.points[v];
        mesh.positions.emplace_back(p[0], p[1], p[2]);
      }
      triangle[corner] = index;
      if (with_file_normals) {
        const auto& n = read.normals[v];
        mesh.corner_normals.emplace_back(n[0], n[1], n[2]);
      }
    }
    mesh.triangles.push_back(triangle);
  }
  return mesh;
}

LoadedMesh load_mesh_unguarded(const std::filesystem::path& file, const LoadOptions& options);

}  // namespace

std::string mesh_format_of(const std::filesystem::path& file) {
  std::filesystem::path name = file.filename();
  if (ends_with_gz(name)) name = name.stem();
  const std::string extension = lower(name.extension().string());
  for (const char* format : {"obj", "stl", "ply", "off"})
    if (extension == std::string(".") + format) return format;
  return "";
}

LoadedMesh load_mesh(const std::filesystem::path& file, const LoadOptions& options) {
  try {
    return load_mesh_unguarded(file, options);
  } catch (const std::bad_alloc&) {
    fail(file, "out of memory while reading (a header may promise absurd element counts)");
  } catch (const std::length_error&) {
    fail(file, "out of memory while reading (a header may promise absurd element counts)");
  }
}

namespace {

LoadedMesh load_mesh_unguarded(const std::filesystem::path& file, const LoadOptions& options) {
  LoadedMesh loaded;
  loaded.format = mesh_format_of(file);
  loaded.gzipped = ends_with_gz(file);
  std::error_code error;
  if (!std::filesystem::exists(file, error)) fail(file, "no such file");
  if (std::filesystem::is_directory(file, error)) fail(file, "is a folder, not a mesh file");
  if (!std::filesystem::is_regular_file(file, error)) fail(file, "is not a regular file");
  if (loaded.format.empty())
    fail(file, "unknown mesh format '" + file.extension().string() +
                   "' (expected .obj, .stl, .ply or .off, optionally gzipped as .gz)");

  std::string bytes = loaded.gzipped ? read_gzipped(file) : read_plain(file);
  if (bytes.empty()) fail(file, "empty file");

  OpenMesh::IO::Options read_options;
  // STL stores only facet normals, which OpenMesh would smear onto shared vertices.
  if (loaded.format != "stl") read_options += OpenMesh::IO::Options::VertexNormal;
  if (loaded.format == "stl" && is_binary_stl(file, bytes)) read_options += OpenMesh::IO::Options::Binary;
  check_before_reading(file, loaded.format, read_options.check(OpenMesh::IO::Options::Binary), bytes);
  const Promised promised = promised_counts(loaded.format, bytes);
  if (promised.data_found < promised.data_needed)
    fail(file, "truncated: the header promises " + std::to_string(promised.data_needed) +
                   " vertex and face lines, the file has " + std::to_string(promised.data_found));
  if (loaded.format == "stl" && !read_options.check(OpenMesh::IO::Options::Binary) &&
      bytes.find("endsolid", bytes.size() > 512 ? bytes.size() - 512 : 0) == std::string::npos)
    fail(file, "truncated ASCII STL (no 'endsolid' at the end)");

  SoupImporter read;
  bool read_ok = false;
  {
    const QuietOpenMesh quiet;
    std::istringstream in(std::move(bytes));
    read_ok = OpenMesh::IO::IOManager().read(in, "." + loaded.format, read, read_options);
  }
  if (!read_ok) fail(file, "cannot parse as " + lower(loaded.format) + " (unreadable or corrupt data)");
  if (promised.vertices >= 0 && static_cast<long>(read.points.size()) < promised.vertices)
    fail(file, "truncated or malformed: " + std::to_string(promised.vertices) + " vertices promised, " +
                   std::to_string(read.points.size()) +
                   " readable (a coordinate may be missing or not a finite number)");
  if (read.out_of_range > 0)
    fail(file, std::to_string(read.out_of_range) + " faces name a vertex the file does not have (it has " +
                   std::to_string(read.points.size()) + ")");
  if (read.triangles.empty()) fail(file, "no faces");

  loaded.file_normals = read_options.check(OpenMesh::IO::Options::VertexNormal);
  // Faces the file has that were not kept: OpenMesh's readers pass over some (a corner repeated)
  // without a word.
  loaded.faces_dropped = promised.faces >= 0 ? static_cast<std::size_t>(std::max<long>(
                                                   0, promised.faces - static_cast<long>(read.n_faces())))
                                             : read.repeated_corner;
  loaded.mesh = triangle_soup(read, loaded.file_normals);

  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const auto& p : loaded.mesh.positions) {
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      fail(file, "non-finite vertex coordinate");
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  if (lo == hi) fail(file, "model has zero extent (all vertices at one point)");
  const bool any_area = std::ranges::any_of(loaded.mesh.triangles, [&](const std::array<std::uint32_t, 3>& t) {
    const glm::dvec3 &a = loaded.mesh.positions[t[0]], &b = loaded.mesh.positions[t[1]],
                     &c = loaded.mesh.positions[t[2]];
    const glm::dvec3 n = glm::cross(b - a, c - a);
    return n.x != 0 || n.y != 0 || n.z != 0;
  });
  if (!any_area) fail(file, "model has no area (every triangle's corners lie on a line)");

  if (loaded.file_normals) {
    unit_or_face_normals(loaded.mesh);
    sharpen_file_normals(loaded.mesh, options.feature_angle_deg);
  } else
    loaded.mesh.corner_normals = feature_corner_normals(loaded.mesh, options.feature_angle_deg);
  return loaded;
}

}  // namespace
}  // namespace origamic
