// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: the text of a mesh file as the loader (mesh_io.cpp) and its checks (mesh_checks.cpp)
// read it, line by line, and the one way both refuse it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <string>
#include <string_view>

#include "origamic/error.hpp"

namespace origamic::mesh_input {

/// \throws InputError "FILE: problem".
[[noreturn]] inline void fail(const std::filesystem::path& file, const std::string& problem) {
  throw InputError(file.string() + ": " + problem);
}

inline bool is_blank_or_comment(std::string_view line) {
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

// Whether the line, past leading blanks, is a statement of the keyword: the keyword alone or before a
// blank ("v 1 2 3", "f 1 2 3"; a bare "v" or "v " is one too, cut short: a truncated file).
inline bool is_statement(std::string_view line, char keyword) {
  line.remove_prefix(std::min(line.find_first_not_of(" \t"), line.size()));
  return !line.empty() && line[0] == keyword &&
         (line.size() == 1 || line[1] == ' ' || line[1] == '\t' || line[1] == '\r');
}

}  // namespace origamic::mesh_input
