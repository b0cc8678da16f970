// SPDX-License-Identifier: GPL-3.0-or-later
// Pictures of the pop-up: ray-traced views (Embree) of the folded card and of the placed model from
// one viewpoint, and the card opening as an animated GIF. Lambert shading with an ambient term and
// a shadow from one key light above the front left; outlines where one face meets another.
// Everything is in the world frame of fold3d.hpp (OA space at 90 degrees: x right, y = h up,
// z = d towards the viewer, mm).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "origamic/fold3d.hpp"
#include "origamic/mesh_io.hpp"
#include "origamic/oa.hpp"

namespace origamic {

/// Triangles to draw, each with its colour.
struct ColouredMesh {
  std::vector<glm::dvec3> positions;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<Rgb8> colours;          // per triangle
  std::vector<std::uint8_t> subject;  // per triangle: 1 for the pop-up's faces or the model, 0 for the card
  std::vector<std::int32_t> part;     // per triangle: outlines are drawn where it changes
};

/// The folded pop-up in its paper colours (paper_colour); the card is its regions at depth 0.
ColouredMesh popup_scene(const FoldedPopup& popup, bool mark_unsupported);

/// The model in OA mm (placed, as origamic::apply gives it) standing in the card opened to 90
/// degrees: the back half and the floor half as two rectangles in the card's colours.
ColouredMesh model_scene(const TriangleMesh& oa_mesh, const Sheet& sheet);

struct RenderOptions {
  int width_px = 1200;          // image size
  int height_px = 900;
  double azimuth_deg = 35;      // camera turned this far right of straight ahead (+z), about the vertical
  double elevation_deg = 28;    // and raised this far above the floor plane
  double fov_deg = 35;          // strength of the perspective; the view is fitted to what it frames
  int samples = 2;              // rays per pixel along each side (samples² a pixel)
  bool shadows = true;          // a shadow ray to the key light from every visible point
  bool outlines = true;         // a dark line where one part (region, or model and card) meets another
};

/// A perspective camera. The pixel (col, row) covers, on the plane one unit in front of the eye,
/// u in u_min + [col, col + 1) pixel, v in v_max - [row, row + 1) pixel along right and up.
struct View {
  glm::dvec3 eye{0, 0, 1};
  glm::dvec3 forward{0, 0, -1}, right{1, 0, 0}, up{0, 1, 0};
  double u_min = -1, v_max = 1, pixel = 0.01;
  int width_px = 200, height_px = 200;
};

/// The view from the options' direction that frames the box lo..hi (world mm) with a 3% margin.
/// \throws InputError naming the option for an image smaller than 8 or larger than 8192 pixels a
///         side, fewer than 1 or more than 8 samples, or an elevation outside (-90, 90) degrees.
View frame_view(const glm::dvec3& lo, const glm::dvec3& hi, const RenderOptions& options);

/// The corners of the box around every position of the meshes.
std::array<glm::dvec3, 2> bounds_of(const std::vector<const ColouredMesh*>& meshes);

/// A picture, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;      // 3 bytes a pixel
  std::vector<std::uint8_t> subject;  // 1 where at least half the pixel's rays hit a subject triangle
};

/// Ray-traces the scene through the view (size from the view, samples, shadows and outlines from
/// the options). Rows are traced in parallel; every pixel depends only on its own rays.
Image render(const ColouredMesh& scene, const View& view, const RenderOptions& options);

/// PNG bytes of the image. \throws OutputError naming `name` on failure.
std::string image_png(const Image& image, const std::string& name);

/// A looping animated GIF of frames of one size, frame i shown delays_cs[i] hundredths of a second;
/// one palette of 256 colours for all frames (giflib's median cut), so nothing flickers.
/// \pre frames non-empty, all of one size, as many delays as frames.
/// \throws OutputError naming `name` if giflib fails.
std::string animated_gif(const std::vector<Image>& frames, const std::vector<int>& delays_cs, const std::string& name);

/// The card opening: the regions folded at each angle, rendered from the options' direction in one
/// view that frames every frame. \throws InputError as fold_popup and frame_view do.
std::vector<Image> opening_frames(const std::vector<PlanRegion>& regions, const Sheet& sheet,
                                  const std::vector<double>& angles_deg, double thickness_mm,
                                  const RenderOptions& options);

}  // namespace origamic
