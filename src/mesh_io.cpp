// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/mesh_io.hpp"

#include <zlib.h>

#include <OpenMesh/Core/IO/IOManager.hh>
#include <OpenMesh/Core/IO/importer/BaseImporter.hh>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <climits>
#include <cstdint>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>

#include "mesh_normals.hpp"
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

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& problem) {
  throw InputError(file.string() + ": " + problem);
}

std::string lower(std::string s) {
  std::ranges::transform(s, s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool ends_with_gz(const std::filesystem::path& file) { return lower(file.extension().string()) == ".gz"; }

// Larger than any model a card can show (res_dragon_full, 871,414 triangles, is 17 MB unpacked; this
// holds some 5 million triangles of ASCII): beyond it, a file is refused before it is read, and a
// gzip stream once it unpacks to this much (a 5 MB bomb: 0.8 s and 0.55 GB, where 1 GiB took 10 s
// and 2.1 GB).
constexpr std::uintmax_t kLargestMeshBytes = std::uintmax_t{256} << 20;

std::string read_plain(const std::filesystem::path& file) {
  std::error_code error;
  if (const std::uintmax_t size = std::filesystem::file_size(file, error); !error && size > kLargestMeshBytes)
    fail(file, "larger than 256 MiB; no model for a card needs that many triangles");
  std::ifstream in(file, std::ios::binary);
  if (!in) fail(file, "cannot open file");
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) fail(file, "cannot read file");
  return bytes;
}

std::string read_gzipped(const std::filesystem::path& file) {
  gzFile gz = gzopen(file.c_str(), "rb");
  if (!gz) fail(file, "cannot open file");
  std::string bytes;
  char buffer[1 << 16];
  int n = 0;
  while ((n = gzread(gz, buffer, sizeof buffer)) > 0) {
    bytes.append(buffer, static_cast<std::size_t>(n));
    if (bytes.size() > kLargestMeshBytes) {
      gzclose(gz);
      fail(file, "unpacks to more than 256 MiB; no model for a card needs that many triangles");
    }
  }
  int code = Z_OK;
  const std::string message = gzerror(gz, &code);  // a stream cut short ends reading with Z_BUF_ERROR
  gzclose(gz);
  if (n < 0 || (code != Z_OK && code != Z_STREAM_END)) fail(file, "truncated or corrupt gzip data (" + message + ")");
  return bytes;
}

// A binary STL is an 80-byte header, a triangle count and 50 bytes a triangle. Files that begin
// with "solid" are ASCII unless their size matches that layout exactly (some binary writers put
// "solid" in the header).
bool is_binary_stl(const std::filesystem::path& file, const std::string& bytes) {
  const bool sized = bytes.size() >= 84 && [&] {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    return bytes.size() == 84 + 50 * static_cast<std::uint64_t>(count);
  }();
  if (sized) return true;
  std::size_t start = 0;
  while (start < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[start]))) ++start;
  if (bytes.compare(start, 5, "solid") == 0) return false;
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

bool is_blank_or_comment(std::string_view line) {
  const auto first = line.find_first_not_of(" \t\r");
  return first == std::string_view::npos || line[first] == '#';
}

// Calls visit(line, number) for each line of bytes from offset on, without its newline, numbered
// from 1 there.
template <class Visit>
void for_each_line(std::string_view bytes, std::size_t offset, Visit&& visit) {
  for (std::size_t at = offset, number = 1; at < bytes.size(); ++number) {
    const std::size_t end = std::min(bytes.find('\n', at), bytes.size());
    visit(bytes.substr(at, end - at), number);
    at = end + 1;
  }
}

// Whether the line, past leading blanks, starts with the keyword and a blank ("v 1 2 3", "f 1 2 3").
bool is_statement(std::string_view line, char keyword) {
  line.remove_prefix(std::min(line.find_first_not_of(" \t"), line.size()));
  return line.size() > 2 && line[0] == keyword && (line[1] == ' ' || line[1] == '\t');
}

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

// OpenMesh's OFF and PLY readers trust their headers: an unknown keyword or type, a property before
// its element, a missing end_header, or a count the file cannot hold made them loop, print without
// end, allocate without bound or crash. Headers are read here first; OpenMesh reads only files whose
// headers say what they hold and whose counts fit in their bytes.
void check_off_header(const std::filesystem::path& file, const std::string& bytes) {
  std::size_t at = 0;
  const auto next_line = [&] {
    while (at < bytes.size()) {
      std::size_t end = bytes.find('\n', at);
      if (end == std::string::npos) end = bytes.size();
      const std::string_view line(bytes.data() + at, end - at);
      at = end + 1;
      if (!is_blank_or_comment(line)) return std::string(line);
    }
    return std::string();
  };
  std::istringstream first(next_line());
  std::string keyword, binary;
  first >> keyword >> binary;
  static const std::regex off_keyword("(ST)?C?N?4?n?OFF");
  if (!std::regex_match(keyword, off_keyword))
    fail(file, "not an OFF file (its first word is not OFF, COFF, NOFF, STOFF or the like)");
  if (keyword.find('4') != std::string::npos || keyword.find('n') != std::string::npos)
    fail(file, "4D and n-dimensional OFF files are not read; a model is 3D");
  long long counts[3] = {0, 0, 0};
  if (binary == "BINARY") {
    // Three 32-bit counts follow the header line, big-endian by the format's definition.
    if (bytes.size() < at + 12) fail(file, "truncated binary OFF (no counts after its header)");
    for (int k = 0; k < 3; ++k) {
      const auto* b = reinterpret_cast<const unsigned char*>(bytes.data() + at + 4 * k);
      counts[k] = static_cast<std::int32_t>(std::uint32_t{b[0]} << 24 | std::uint32_t{b[1]} << 16 |
                                            std::uint32_t{b[2]} << 8 | b[3]);
    }
    if (counts[0] < 0 || counts[1] < 0 ||
        12 * counts[0] + 16 * counts[1] > static_cast<long long>(bytes.size() - at - 12))
      fail(file, "binary OFF header counts " + std::to_string(counts[0]) + " vertices and " +
                     std::to_string(counts[1]) + " faces, more than its bytes hold");
    return;
  }
  // The counts may follow the keyword on its line or stand on the next.
  std::istringstream rest(binary.empty() ? next_line() : binary + " " + std::string(std::istreambuf_iterator<char>(first), {}));
  if (!(rest >> counts[0] >> counts[1]))
    fail(file, "OFF header has no vertex and face counts (whole numbers from 0 to 2147483647) after " + keyword);
  if (counts[0] < 0 || counts[1] < 0 || counts[0] > INT32_MAX || counts[1] > INT32_MAX)
    fail(file, "OFF header counts " + std::to_string(counts[0]) + " vertices and " + std::to_string(counts[1]) +
                   " faces; counts are whole numbers from 0 to 2147483647");
}

void check_ply_header(const std::filesystem::path& file, const std::string& bytes) {
  // A header longer than this is no header: 64 KiB holds thousands of comment lines.
  constexpr std::size_t kLongestHeader = 1 << 16;
  if (bytes.compare(0, 3, "ply") != 0 || (bytes.size() > 3 && !std::isspace(static_cast<unsigned char>(bytes[3]))))
    fail(file, "not a PLY file (it does not start with 'ply')");
  const std::size_t end = bytes.find("end_header");
  if (end == std::string::npos || end > kLongestHeader) fail(file, "PLY header has no end_header in its first 64 KiB");
  static const std::set<std::string> types = {"char",  "uchar", "short",  "ushort", "int",    "uint",
                                               "float", "double", "int8",  "uint8",  "int16",  "uint16",
                                               "int32", "uint32", "float32", "float64"};
  const auto size_of = [](const std::string& type) -> long long {
    if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
    if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
    if (type == "double" || type == "float64") return 8;
    return 4;
  };
  std::istringstream in(bytes.substr(0, end));
  std::string line, format;
  long long least_bytes = 0, records = 0, count = 0, record_bytes = 0;
  bool in_element = false, has_vertex = false;
  int line_number = 0;
  const auto close_element = [&] { least_bytes += count * record_bytes, records += count; };
  while (std::getline(in, line)) {
    ++line_number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    const std::string where = "PLY header line " + std::to_string(line_number) + ": ";
    if (line_number == 1) {
      if (keyword != "ply") fail(file, "not a PLY file (it does not start with 'ply')");
      continue;
    }
    if (keyword.empty() || keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      words >> format;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
        fail(file, where + "unknown format '" + format + "'");
    } else if (keyword == "element") {
      if (in_element) close_element();
      std::string name;
      if (!(words >> name >> count) || count < 0 || count > INT32_MAX)
        fail(file, where + "an element needs a name and a count from 0 to 2147483647");
      has_vertex |= name == "vertex" && count > 0;
      in_element = true, record_bytes = 0;
    } else if (keyword == "property") {
      if (!in_element) fail(file, where + "a property before any element");
      std::string type, name;
      words >> type;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        if (!types.contains(count_type) || !types.contains(item_type))
          fail(file, where + "unsupported list types '" + count_type + "' and '" + item_type + "'");
        record_bytes += size_of(count_type);
      } else {
        if (!types.contains(type)) fail(file, where + "unsupported property type '" + type + "'");
        record_bytes += size_of(type);
      }
      if (!(words >> name)) fail(file, where + "a property without a name");
    } else {
      fail(file, where + "unknown keyword '" + keyword + "'");
    }
  }
  if (in_element) close_element();
  if (format.empty()) fail(file, "PLY header has no format line");
  if (!has_vertex) fail(file, "PLY header has no vertex element");
  const std::size_t data = bytes.find('\n', end);
  const auto data_bytes = static_cast<long long>(data == std::string::npos ? 0 : bytes.size() - data - 1);
  if (format != "ascii" && least_bytes > data_bytes)
    fail(file, "truncated: the PLY header promises at least " + std::to_string(least_bytes) +
                   " bytes of data, the file has " + std::to_string(data_bytes));
  if (format == "ascii" && 2 * records > data_bytes)  // a record is a line: a number and a newline at least
    fail(file, "truncated: the PLY header promises " + std::to_string(records) + " records, more than its " +
                   std::to_string(data_bytes) + " bytes of data hold");
}

// OpenMesh's STL readers take "nan" and "inf" for numbers (ASCII: as whatever the stream left;
// binary: as they are): every vertex is checked to hold three finite numbers first.
void check_stl_numbers(const std::filesystem::path& file, const std::string& bytes, bool binary) {
  if (binary) {
    std::uint32_t count = 0;
    std::memcpy(&count, bytes.data() + 80, 4);
    for (std::uint64_t t = 0; t < count; ++t)
      for (int k = 0; k < 12; ++k) {  // the normal and three corners
        float value = 0;
        std::memcpy(&value, bytes.data() + 84 + 50 * t + 4 * k, 4);
        if (!std::isfinite(value))
          fail(file, "triangle " + std::to_string(t + 1) + " holds a number that is not finite");
      }
    return;
  }
  for_each_line(bytes, 0, [&](std::string_view line, std::size_t number) {
    std::istringstream words{std::string(line)};
    std::string keyword;
    words >> keyword;
    if (keyword != "vertex") return;
    for (int k = 0; k < 3; ++k) {
      std::string word;
      words >> word;
      char* stop = nullptr;
      const double value = std::strtod(word.c_str(), &stop);
      if (word.empty() || *stop != '\0' || !std::isfinite(value))
        fail(file, "line " + std::to_string(number) + ": a vertex needs three finite numbers");
    }
  });
}

// OpenMesh's OBJ reader asserts (aborts) on a face whose corners it cannot read, such as
// "14/11/14/8": every face line must be three or more corners v, v/t, v//n or v/t/n, each a
// whole number, before it reads.
void check_obj_faces(const std::filesystem::path& file, const std::string& bytes) {
  const auto whole = [](std::string_view text, bool may_be_empty) {
    if (!text.empty() && text.front() == '-') text.remove_prefix(1);
    if (text.empty()) return may_be_empty;
    return std::ranges::all_of(text, [](char c) { return c >= '0' && c <= '9'; });
  };
  for_each_line(bytes, 0, [&](std::string_view line, std::size_t line_number) {
    if (!is_statement(line, 'f')) return;
    line.remove_prefix(line.find('f') + 1);
    if (const auto comment = line.find('#'); comment != std::string_view::npos) line = line.substr(0, comment);
    int corners = 0;
    bool readable = true;
    for (std::size_t i = 0; i < line.size() && readable;) {
      i = line.find_first_not_of(" \t\r\\", i);
      if (i == std::string_view::npos) break;
      const std::size_t stop = std::min(line.find_first_of(" \t\r\\", i), line.size());
      const std::string_view corner = line.substr(i, stop - i);
      i = stop;
      // v, v/t or v/t/n with t possibly empty: one to three parts, all whole numbers but an empty t.
      std::vector<std::string_view> parts;
      for (std::size_t from = 0;;) {
        const std::size_t slash = corner.find('/', from);
        parts.push_back(corner.substr(from, slash == std::string_view::npos ? slash : slash - from));
        if (slash == std::string_view::npos) break;
        from = slash + 1;
      }
      readable = parts.size() <= 3;
      for (std::size_t k = 0; k < parts.size() && readable; ++k) readable = whole(parts[k], k == 1 && parts.size() == 3);
      ++corners;
    }
    if (!readable || corners < 3)
      fail(file, "line " + std::to_string(line_number) +
                     ": a face needs three or more corners, each v, v/t, v//n or v/t/n in whole numbers");
  });
}

// OpenMesh's OBJ reader opens the material libraries a file names, any path (/dev/zero, a FIFO): the
// plan needs no materials, so `mtllib` lines are made comments before it reads.
void drop_material_libraries(std::string& bytes) {
  for (std::size_t at = 0; at < bytes.size();) {
    std::size_t start = bytes.find_first_not_of(" \t", at);
    if (start == std::string::npos) break;
    if (bytes.compare(start, 6, "mtllib") == 0) bytes[start] = '#';
    const std::size_t end = bytes.find('\n', start);
    if (end == std::string::npos) break;
    at = end + 1;
  }
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
  if (loaded.format == "stl") check_stl_numbers(file, bytes, read_options.check(OpenMesh::IO::Options::Binary));
  if (loaded.format == "off") check_off_header(file, bytes);
  if (loaded.format == "ply") check_ply_header(file, bytes);
  if (loaded.format == "obj") check_obj_faces(file, bytes), drop_material_libraries(bytes);
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
    const glm::dvec3 &a = loaded.mesh.positions[t[0]], &b = loaded.mesh.positions[t[1]], &c = loaded.mesh.positions[t[2]];
    const glm::dvec3 n = glm::cross(b - a, c - a);
    return n.x != 0 || n.y != 0 || n.z != 0;
  });
  if (!any_area) fail(file, "model has no area (every triangle's corners lie on a line)");

  if (loaded.file_normals)
    unit_or_face_normals(loaded.mesh);
  else
    loaded.mesh.corner_normals = feature_corner_normals(loaded.mesh, options.feature_angle_deg);
  return loaded;
}

}  // namespace
}  // namespace origamic
