// SPDX-License-Identifier: GPL-3.0-or-later
#include "atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <system_error>

#include "origamic/error.hpp"
#include "origamic/output.hpp"

namespace origamic {

void write_files(const std::vector<OutputFile>& files) {
  namespace fs = std::filesystem;
  std::vector<fs::path> staged;
  auto discard = [&] {
    std::error_code ignored;
    for (const fs::path& temp : staged) fs::remove(temp, ignored);
  };
  for (const OutputFile& file : files) {
    const fs::path dir = file.path.parent_path().empty() ? fs::path(".") : file.path.parent_path();
    try {
      make_directory(dir);
    } catch (...) {
      discard();
      throw;
    }
    std::error_code error;
    if (fs::is_directory(file.path, error)) {
      discard();
      throw OutputError(file.path.string() + ": cannot write file (a folder is in the way)");
    }
    const fs::path temp = fs::path(file.path).concat(".part" + std::to_string(::getpid()));
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (out) out.write(file.bytes.data(), static_cast<std::streamsize>(file.bytes.size()));
    out.close();
    staged.push_back(temp);
    if (!out) {
      discard();
      throw OutputError(file.path.string() + ": cannot write file");
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code error;
    fs::rename(staged[i], files[i].path, error);
    if (error) {
      staged.erase(staged.begin(), staged.begin() + static_cast<std::ptrdiff_t>(i));
      discard();
      throw OutputError(files[i].path.string() + ": cannot write file (" + error.message() + ")");
    }
  }
}

void make_directory(const std::filesystem::path& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir))
    throw OutputError(dir.string() + ": cannot create folder" +
                      (error ? " (" + error.message() + ")" : std::string(" (a file is in the way)")));
}

}  // namespace origamic
