// SPDX-License-Identifier: GPL-3.0-or-later
#include "png_image.hpp"

#include <png.h>

#include <algorithm>
#include <cmath>
#include <csetjmp>
#include <string>
#include <vector>

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

namespace {

void append(png_structp png, png_bytep data, png_size_t length) {
  try {
    static_cast<std::string*>(png_get_io_ptr(png))->append(reinterpret_cast<const char*>(data), length);
  } catch (...) {  // no exception may cross libpng's C frames
    png_error(png, "out of memory");
  }
}

// An RGB image as libpng writes it: its rows, its text chunks and its resolution.
struct RgbRows {
  int width = 0, height = 0;
  png_bytepp rows = nullptr;  // height rows of 3 * width bytes, top to bottom
  png_textp texts = nullptr;
  int text_count = 0;
  png_uint_32 px_per_metre = 0;
};

// libpng reports errors by longjmp: this frame holds no object with a destructor.
bool write_rgb(png_structp png, png_infop info, const RgbRows& image, std::string* out) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_set_write_fn(png, out, append, nullptr);
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width), static_cast<png_uint_32>(image.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_text(png, info, image.texts, image.text_count);
  png_set_pHYs(png, info, image.px_per_metre, image.px_per_metre, PNG_RESOLUTION_METER);
  // One filter and zlib's fastest level, where libpng tries five filters a row at level 6: the plan
  // pictures (MODEL.png, narrow.png) keep their pixels; seedlike/torus's plan (840 x 1188,
  // mostly paper) 106 -> 116 KB, its encoding 1.8 -> 0.5 % of the design's samples.
  png_set_filter(png, 0, PNG_FILTER_UP);
  png_set_compression_level(png, 1);
  png_set_rows(png, info, image.rows);
  png_write_png(png, info, PNG_TRANSFORM_IDENTITY, nullptr);
  return true;
}

// libpng's text chunks of the texts, pointing into them.
std::vector<png_text> text_chunks(const std::vector<PngText>& texts) {
  std::vector<png_text> chunks(texts.size());
  for (std::size_t i = 0; i < texts.size(); ++i) {
    // tEXt is Latin-1: text with other bytes (UTF-8 model names) goes in an iTXt chunk instead.
    const bool ascii = std::ranges::all_of(texts[i].text, [](char c) { return static_cast<unsigned char>(c) < 0x80; });
    chunks[i].compression = ascii ? PNG_TEXT_COMPRESSION_NONE : PNG_ITXT_COMPRESSION_NONE;
    chunks[i].key = const_cast<char*>(texts[i].keyword.c_str());
    chunks[i].text = const_cast<char*>(texts[i].text.c_str());
    if (ascii)
      chunks[i].text_length = texts[i].text.size();
    else
      chunks[i].itxt_length = texts[i].text.size();
  }
  return chunks;
}

}  // namespace

std::string encode_png(const std::string& name, int width, int height, std::span<const std::uint8_t> rgb,
                       const PngMetadata& metadata) {
  std::vector<png_text> chunks = text_chunks(metadata.texts);
  std::vector<png_bytep> rows(static_cast<std::size_t>(height));
  for (std::size_t y = 0; y < rows.size(); ++y)
    rows[y] = const_cast<png_bytep>(rgb.data() + y * 3 * static_cast<std::size_t>(width));
  const RgbRows image{.width = width,
                      .height = height,
                      .rows = rows.data(),
                      .texts = chunks.data(),
                      .text_count = static_cast<int>(chunks.size()),
                      .px_per_metre = static_cast<png_uint_32>(std::lround(metadata.px_per_mm * 1000))};
  std::string bytes;
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png ? png_create_info_struct(png) : nullptr;
  const bool ok = info && write_rgb(png, info, image, &bytes);
  png_destroy_write_struct(&png, &info);
  if (!ok) throw OutputError(name + ": cannot encode PNG");
  return bytes;
}

std::string encode_png(const std::string& file, int width, int height, PngFormat format,
                       std::span<const std::uint8_t> pixels) {
  return encode(file, width, height, format == PngFormat::Rgb8 ? PNG_FORMAT_RGB : PNG_FORMAT_GRAY, pixels.data());
}

std::string encode_png(const std::string& file, int width, int height, std::span<const std::uint16_t> gray) {
  // libpng's simplified API takes 16-bit samples as linear; the file is written with gamma 1.
  return encode(file, width, height, PNG_FORMAT_LINEAR_Y, gray.data());
}

}  // namespace origamic
