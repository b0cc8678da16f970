// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: a mesh file's bytes as the loader (mesh_io.cpp) reads them, plain or gzipped, no more
// than 256 MiB either way.
#pragma once

#include <filesystem>
#include <string>

namespace origamic::mesh_input {

/// The file's bytes as they are.
/// \throws InputError naming the file if it cannot be opened or read, or holds more than 256 MiB.
std::string read_plain(const std::filesystem::path& file);

/// The bytes a gzip file unpacks to, all its members one after another: at once by libdeflate where
/// its footer gives their size and it is one member, else by zlib's stream.
/// \throws InputError naming the file if it cannot be opened, is truncated or corrupt, or unpacks to
/// more than 256 MiB.
std::string read_gzipped(const std::filesystem::path& file);

}  // namespace origamic::mesh_input
