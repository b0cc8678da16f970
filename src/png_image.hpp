// SPDX-License-Identifier: GPL-3.0-or-later
// PNG encoding through libpng.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>

namespace origamic {

enum class PngFormat { Gray8, Rgb8 };

/// Writes width x height pixels, rows top to bottom: Gray8 takes a byte a pixel, Rgb8 three, the
/// overload with uint16_t one 16-bit grey value. The file appears complete or not at all.
/// \throws OutputError naming the file if it cannot be written.
void write_png(const std::filesystem::path& file, int width, int height, PngFormat format,
               std::span<const std::uint8_t> pixels);
void write_png(const std::filesystem::path& file, int width, int height, std::span<const std::uint16_t> gray);

}  // namespace origamic
