// SPDX-License-Identifier: GPL-3.0-or-later
// Output files that appear complete or not at all.
#pragma once

#include <filesystem>
#include <string_view>

namespace origamic {

/// Writes bytes to a temporary file beside `file`, then renames it into place.
/// \throws OutputError naming the file if it cannot be written; no partial file is left.
void write_file_atomically(const std::filesystem::path& file, std::string_view bytes);

/// Creates dir and its parents if needed. \throws OutputError naming dir if it cannot.
void make_directory(const std::filesystem::path& dir);

}  // namespace origamic
