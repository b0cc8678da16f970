// SPDX-License-Identifier: GPL-3.0-or-later
// Folders for output files (write_files, in origamic/output.hpp, is implemented here).
#pragma once

#include <filesystem>

namespace origamic {

/// Creates dir and its parents if needed. \throws OutputError naming dir if it cannot.
void make_directory(const std::filesystem::path& dir);

}  // namespace origamic
