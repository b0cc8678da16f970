// SPDX-License-Identifier: GPL-3.0-or-later
// PNG encoding through libpng.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace origamic {

enum class PngFormat { Gray8, Rgb8 };

/// PNG bytes of width x height pixels, rows top to bottom: Gray8 takes a byte a pixel, Rgb8 three,
/// the overload with uint16_t one 16-bit grey value. \throws OutputError naming `name` on failure.
std::string encode_png(const std::string& name, int width, int height, PngFormat format,
                       std::span<const std::uint8_t> pixels);
std::string encode_png(const std::string& name, int width, int height, std::span<const std::uint16_t> gray);

/// A tEXt chunk: a PNG keyword ("Title", "Description", "Software", ...) and Latin-1 text.
struct PngText {
  std::string keyword;
  std::string text;
};

/// What a PNG says besides its pixels: text chunks, and its resolution in a pHYs chunk.
struct PngMetadata {
  std::vector<PngText> texts;
  double px_per_mm = 0;  // so viewers know the picture's size in mm
};

/// PNG bytes of an Rgb8 image with the metadata's tEXt and pHYs chunks, through libpng's full API
/// (the simplified one writes no text). \throws OutputError naming `name` on failure.
std::string encode_png(const std::string& name, int width, int height, std::span<const std::uint8_t> rgb,
                       const PngMetadata& metadata);

}  // namespace origamic
