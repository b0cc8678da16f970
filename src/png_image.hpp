// SPDX-License-Identifier: GPL-3.0-or-later
// PNG encoding through libpng.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

namespace origamic {

enum class PngFormat { Gray8, Rgb8 };

/// PNG bytes of width x height pixels, rows top to bottom: Gray8 takes a byte a pixel, Rgb8 three,
/// the overload with uint16_t one 16-bit grey value. \throws OutputError naming `name` on failure.
std::string encode_png(const std::string& name, int width, int height, PngFormat format,
                       std::span<const std::uint8_t> pixels);
std::string encode_png(const std::string& name, int width, int height, std::span<const std::uint16_t> gray);

}  // namespace origamic
