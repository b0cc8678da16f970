// SPDX-License-Identifier: GPL-3.0-or-later
#include "png_image.hpp"

#include <png.h>

#include <string>

#include "origamic/error.hpp"

namespace origamic {
namespace {

std::string encode(const std::string& file, int width, int height, png_uint_32 format, const void* pixels) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = format;
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&image, nullptr, &size, 0, pixels, 0, nullptr))
    throw OutputError(file + ": cannot encode PNG (" + image.message + ")");
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&image, bytes.data(), &size, 0, pixels, 0, nullptr))
    throw OutputError(file + ": cannot encode PNG (" + image.message + ")");
  bytes.resize(size);
  return bytes;
}

}  // namespace

std::string encode_png(const std::string& file, int width, int height, PngFormat format,
                       std::span<const std::uint8_t> pixels) {
  return encode(file, width, height, format == PngFormat::Rgb8 ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY, pixels.data());
}

std::string encode_png(const std::string& file, int width, int height, std::span<const std::uint16_t> gray) {
  // libpng's simplified API takes 16-bit samples as linear; the file is written with gamma 1.
  return encode(file, width, height, PNG_FORMAT_LINEAR_Y, gray.data());
}

}  // namespace origamic
