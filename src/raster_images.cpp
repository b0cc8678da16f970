// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/raster_images.hpp"

#include <algorithm>
#include <cmath>

#include "atomic_file.hpp"
#include "png_image.hpp"

namespace origamic {
namespace {

std::vector<std::uint16_t> gray16(const Grid<float>& map) {
  std::vector<std::uint16_t> pixels(map.size());
  std::ranges::transform(map.values, pixels.begin(), [](float v) {
    return static_cast<std::uint16_t>(std::lround(std::clamp(v, 0.0f, 1.0f) * 65535.0f));
  });
  return pixels;
}

std::vector<std::uint8_t> normal_rgb(const Grid<glm::vec3>& normals) {
  std::vector<std::uint8_t> pixels(3 * normals.size());
  for (std::size_t i = 0; i < normals.size(); ++i)
    for (int k = 0; k < 3; ++k)
      pixels[3 * i + k] =
          static_cast<std::uint8_t>(std::lround(std::clamp(normals.values[i][k] * 0.5f + 0.5f, 0.0f, 1.0f) * 255));
  return pixels;
}

std::vector<std::uint8_t> kind_rgb(const Grid<HitKind>& kinds) {
  constexpr std::uint8_t palette[4][3] = {{200, 200, 200}, {222, 196, 150}, {40, 90, 200}, {0, 0, 0}};
  std::vector<std::uint8_t> pixels(3 * kinds.size());
  for (std::size_t i = 0; i < kinds.size(); ++i)
    std::ranges::copy(palette[static_cast<int>(kinds.values[i])], &pixels[3 * i]);
  return pixels;
}

}  // namespace

std::vector<std::filesystem::path> write_raster_images(const RasterMaps& maps, const std::filesystem::path& dir) {
  make_directory(dir);
  const int w = maps.grid.cols, h = maps.grid.rows;
  std::vector<std::filesystem::path> written;
  for (const auto& [name, map] : {std::pair{"D.png", &maps.D}, {"F.png", &maps.F}, {"T.png", &maps.T}}) {
    write_png(dir / name, w, h, gray16(*map));
    written.push_back(dir / name);
  }
  write_png(dir / "N.png", w, h, PngFormat::Rgb8, normal_rgb(maps.normal));
  written.push_back(dir / "N.png");
  write_png(dir / "kind.png", w, h, PngFormat::Rgb8, kind_rgb(maps.kind));
  written.push_back(dir / "kind.png");
  return written;
}

}  // namespace origamic
