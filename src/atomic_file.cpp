// SPDX-License-Identifier: GPL-3.0-or-later
#include "atomic_file.hpp"

#include <unistd.h>

#include <fstream>
#include <system_error>

#include "origamic/error.hpp"

namespace origamic {

void write_file_atomically(const std::filesystem::path& file, std::string_view bytes) {
  namespace fs = std::filesystem;
  const fs::path temp = fs::path(file).concat(".part" + std::to_string(::getpid()));
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (out) out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) {
      std::error_code ignored;
      fs::remove(temp, ignored);
      throw OutputError(file.string() + ": cannot write file");
    }
  }
  std::error_code error;
  fs::rename(temp, file, error);
  if (error) {
    std::error_code ignored;
    fs::remove(temp, ignored);
    throw OutputError(file.string() + ": cannot write file (" + error.message() + ")");
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
