// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/raster_images.hpp"

#include <algorithm>
#include <array>
#include <cmath>

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

// A colour per id that neighbours rarely share; -1 black, back and floor as in kind.png.
std::array<std::uint8_t, 3> id_colour(std::int32_t id, bool card_ids) {
  if (id < 0) return {0, 0, 0};
  if (card_ids && id == 0) return {200, 200, 200};
  if (card_ids && id == 1) return {222, 196, 150};
  const std::uint32_t hash = static_cast<std::uint32_t>(id) * 2654435761u;
  return {static_cast<std::uint8_t>(60 + (hash >> 8) % 180), static_cast<std::uint8_t>(60 + (hash >> 16) % 180),
          static_cast<std::uint8_t>(60 + (hash >> 24) % 180)};
}

std::vector<std::uint8_t> id_rgb(const Grid<std::int32_t>& ids, bool card_ids) {
  std::vector<std::uint8_t> pixels(3 * ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) std::ranges::copy(id_colour(ids.values[i], card_ids), &pixels[3 * i]);
  return pixels;
}

// Is the boundary between a pixel (upper) and the one below it (lower) a fold? It is when one is
// V(d) and the other H(h) and the boundary lies within a pixel of the fold line Y = h - d.
bool is_fold(const RasterFace& upper, const RasterFace& lower, double boundary_Y, double pixel_mm) {
  if (upper.orientation == lower.orientation) return false;
  return std::abs(fold_line_Y(upper.orientation, upper.depth_mm, lower.depth_mm) - boundary_Y) <= pixel_mm;
}

std::vector<std::uint8_t> plan_preview_rgb(const RasterMaps& maps, const RasterPlan& raster_plan) {
  const Grid<std::int32_t>& face = raster_plan.face;
  std::vector<std::uint8_t> pixels(3 * face.size(), 255);
  auto paint = [&](int col, int row, std::array<std::uint8_t, 3> rgb) {
    std::ranges::copy(rgb, &pixels[3 * face.index(col, row)]);
  };
  const double pixel_mm = 1 / maps.grid.px_per_mm;
  for (int row = 0; row < face.rows; ++row)
    for (int col = 0; col < face.cols; ++col) {
      const std::int32_t f = face(col, row);
      if (f < 0) continue;
      if (col + 1 < face.cols && face(col + 1, row) >= 0 && face(col + 1, row) != f) paint(col, row, {220, 0, 0});
      if (row + 1 < face.rows && face(col, row + 1) >= 0 && face(col, row + 1) != f) {
        const double boundary_Y = maps.grid.Y(row) - pixel_mm / 2;
        const bool fold =
            is_fold(raster_plan.faces[static_cast<std::size_t>(f)],
                    raster_plan.faces[static_cast<std::size_t>(face(col, row + 1))], boundary_Y, pixel_mm);
        paint(col, row, fold ? std::array<std::uint8_t, 3>{0, 160, 0} : std::array<std::uint8_t, 3>{220, 0, 0});
      }
    }
  return pixels;
}

// Likeness error: black where the card meets the model, white at 2 W and beyond; not model: blue.
std::vector<std::uint8_t> error_rgb(const Grid<float>& error, double W) {
  std::vector<std::uint8_t> pixels(3 * error.size());
  for (std::size_t i = 0; i < error.size(); ++i) {
    const float e = error.values[i];
    if (e < 0) {
      std::ranges::copy(std::array<std::uint8_t, 3>{40, 60, 110}, &pixels[3 * i]);
      continue;
    }
    const auto v = static_cast<std::uint8_t>(std::lround(std::clamp(e / (2 * W), 0.0, 1.0) * 255));
    std::ranges::fill_n(&pixels[3 * i], 3, v);
  }
  return pixels;
}

}  // namespace

std::vector<OutputFile> slice_image_files(const RasterMaps& maps, const Segmentation& segmentation,
                                          const RasterPlan& raster_plan, const CardView& card,
                                          const std::filesystem::path& dir) {
  const int w = maps.grid.cols, h = maps.grid.rows;
  const std::vector<std::pair<std::string, std::vector<std::uint8_t>>> images = {
      {"S.png", id_rgb(segmentation.segment, true)},
      {"SS.png", id_rgb(raster_plan.subsegment, false)},
      {"faces.png", id_rgb(raster_plan.face, true)},
      {"plan_preview.png", plan_preview_rgb(maps, raster_plan)},
      {"E.png", error_rgb(likeness_error_map(maps, card), raster_plan.min_strip_mm)},
  };
  std::vector<OutputFile> files;
  for (const auto& [name, pixels] : images)
    files.push_back({dir / name, encode_png((dir / name).string(), w, h, PngFormat::Rgb8, pixels)});
  return files;
}

std::vector<OutputFile> raster_image_files(const RasterMaps& maps, const std::filesystem::path& dir) {
  const int w = maps.grid.cols, h = maps.grid.rows;
  std::vector<OutputFile> files;
  const NormalisedDepths depths = normalised_depths(maps);
  for (const auto& [name, map] : {std::pair{"D.png", &depths.D}, {"F.png", &depths.F}, {"T.png", &depths.T}})
    files.push_back({dir / name, encode_png((dir / name).string(), w, h, gray16(*map))});
  if (maps.normal.size() > 0)
    files.push_back(
        {dir / "N.png", encode_png((dir / "N.png").string(), w, h, PngFormat::Rgb8, normal_rgb(maps.normal))});
  files.push_back(
      {dir / "kind.png", encode_png((dir / "kind.png").string(), w, h, PngFormat::Rgb8, kind_rgb(maps.kind))});
  return files;
}

}  // namespace origamic
