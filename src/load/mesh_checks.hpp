// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: what the loader checks of a mesh file's bytes before OpenMesh reads them
// (mesh_checks.cpp). OpenMesh's readers trust their input: these checks stand between it and a
// malformed file.
#pragma once

#include <filesystem>
#include <string>

namespace origamic {

/// Checks the bytes of a mesh file of `format` ("obj", "stl", "ply" or "off"; `binary_stl` for a
/// binary STL) and makes its OBJ material libraries comments, never to be opened.
/// \throws InputError naming the file and the problem, in one line.
void check_before_reading(const std::filesystem::path& file, const std::string& format, bool binary_stl,
                          std::string& bytes);

}  // namespace origamic
