// SPDX-License-Identifier: GPL-3.0-or-later
// Output files that appear all together, complete, or not at all.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace origamic {

struct OutputFile {
  std::filesystem::path path;
  std::string bytes;
};

/// Writes every file: each is first written beside its target under a temporary name, then all are
/// renamed into place. Folders are created as needed. If any file cannot be written, every
/// temporary file is removed and nothing is published.
/// \throws OutputError naming the file and the problem.
void write_files(const std::vector<OutputFile>& files);

}  // namespace origamic
