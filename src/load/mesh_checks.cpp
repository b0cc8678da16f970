// SPDX-License-Identifier: GPL-3.0-or-later
#include "mesh_checks.hpp"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>
#include <vector>

#include "mesh_text.hpp"

namespace origamic {
namespace {

using mesh_input::fail;
using mesh_input::for_each_line;
using mesh_input::is_blank_or_comment;
using mesh_input::is_statement;

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
  std::istringstream rest(binary.empty() ? next_line()
                                         : binary + " " + std::string(std::istreambuf_iterator<char>(first), {}));
  if (!(rest >> counts[0] >> counts[1]))
    fail(file, "OFF header has no vertex and face counts (whole numbers from 0 to 2147483647) after " + keyword);
  if (counts[0] < 0 || counts[1] < 0 || counts[0] > INT32_MAX || counts[1] > INT32_MAX)
    fail(file, "OFF header counts " + std::to_string(counts[0]) + " vertices and " + std::to_string(counts[1]) +
                   " faces; counts are whole numbers from 0 to 2147483647");
  // Each face line starts with its corner count, and OpenMesh reads that many numbers whatever the
  // line holds: a count of 3022407 (a blank lost between "3" and "022407") read past the file's end
  // for minutes. A face must list its corners on its line.
  const auto first_line =
      static_cast<std::size_t>(std::count(bytes.begin(), bytes.begin() + std::min(at, bytes.size()), '\n'));
  long long data = 0;
  for_each_line(bytes, std::min(at, bytes.size()), [&](std::string_view line, std::size_t number) {
    if (is_blank_or_comment(line) || data++ < counts[0] || data > counts[0] + counts[1]) return;
    std::istringstream words{std::string(line.substr(0, line.find('#')))};
    long long corners = -1, listed = 0;
    std::string word;
    if (!(words >> word) || word.find_first_not_of("0123456789") != std::string::npos || word.size() > 10)
      fail(file,
           "line " + std::to_string(first_line + number) + ": a face starts with its corner count, a whole number");
    corners = std::stoll(word);
    while (words >> word) ++listed;
    if (corners > listed)
      fail(file, "truncated or malformed: line " + std::to_string(first_line + number) + ": a face of " +
                     std::to_string(corners) + " corners lists " + std::to_string(listed) + " numbers");
  });
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
  // The words split off by hand, not by a string stream per line: the streams took nearly half of
  // seedlike/torus's load (9,216 triangles: 24 of its 52 ms of samples; its load 59-99 -> 39-47 ms).
  constexpr std::string_view kSpace = " \t\r\v\f";
  std::string word;
  for_each_line(bytes, 0, [&](std::string_view line, std::size_t number) {
    const auto next_word = [&] {
      const std::size_t begin = std::min(line.find_first_not_of(kSpace), line.size());
      line.remove_prefix(begin);
      const std::string_view found = line.substr(0, std::min(line.find_first_of(kSpace), line.size()));
      line.remove_prefix(found.size());
      return found;
    };
    if (next_word() != "vertex") return;
    for (int k = 0; k < 3; ++k) {
      word = next_word();
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
      for (std::size_t k = 0; k < parts.size() && readable; ++k)
        readable = whole(parts[k], k == 1 && parts.size() == 3);
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

}  // namespace

void check_before_reading(const std::filesystem::path& file, const std::string& format, bool binary_stl,
                          std::string& bytes) {
  if (format == "stl") check_stl_numbers(file, bytes, binary_stl);
  if (format == "off") check_off_header(file, bytes);
  if (format == "ply") check_ply_header(file, bytes);
  if (format == "obj") check_obj_faces(file, bytes), drop_material_libraries(bytes);
}

}  // namespace origamic
