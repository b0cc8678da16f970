// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/render.hpp"

#include <gif_lib.h>
#include <gtest/gtest.h>
#include <png.h>

#include <cstring>
#include <set>

#include "helpers.hpp"
#include "origamic/error.hpp"

namespace origamic {
namespace {

constexpr double kX0 = 61.3, kX1 = 148.9, kH = 63.7, kD = 41.9;

RenderOptions small_options() {
  RenderOptions options;
  options.width_px = 240;
  options.height_px = 180;
  return options;
}

ColouredMesh box_popup(double angle_deg) {
  return popup_scene(fold_popup(test::box_popup_regions(Sheet{}, kX0, kX1, kH, kD), Sheet{}, {.angle_deg = angle_deg}),
                     true);
}

// The two faces a box pop-up makes of the box: its front and its top.
TriangleMesh open_box() {
  TriangleMesh mesh;
  mesh.positions = {{kX0, 0, kD}, {kX1, 0, kD}, {kX1, kH, kD}, {kX0, kH, kD}, {kX1, kH, 0}, {kX0, kH, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}, {3, 2, 4}, {3, 4, 5}};
  return mesh;
}

struct Overlap {
  int a = 0, b = 0, both = 0;
  double iou() const { return both / double(a + b - both); }
  double a_inside_b() const { return both / double(a); }
};

Overlap overlap(const Image& a, const Image& b) {
  Overlap o;
  for (std::size_t i = 0; i < a.subject.size(); ++i) {
    o.a += a.subject[i];
    o.b += b.subject[i];
    o.both += a.subject[i] & b.subject[i];
  }
  return o;
}

// The popup and the model rendered from one view that frames both.
std::pair<Image, Image> popup_and_model(const TriangleMesh& model, const RenderOptions& options) {
  const ColouredMesh popup = box_popup(90);
  const ColouredMesh standing = model_scene(model, Sheet{});
  const auto [lo, hi] = bounds_of({&popup, &standing});
  const View view = frame_view(lo, hi, options);
  return {render(popup, view, options), render(standing, view, options)};
}

TEST(Render, ImageHasTheRequestedSizeAndShowsTheCardAndTheBox) {
  const ColouredMesh scene = box_popup(90);
  const auto [lo, hi] = bounds_of({&scene});
  const Image image = render(scene, frame_view(lo, hi, small_options()), small_options());
  ASSERT_EQ(image.width, 240);
  ASSERT_EQ(image.height, 180);
  ASSERT_EQ(image.rgb.size(), 240u * 180 * 3);
  ASSERT_EQ(image.subject.size(), 240u * 180);
  std::set<std::array<std::uint8_t, 3>> colours;
  int background = 0, subject = 0;
  for (std::size_t i = 0; i < image.subject.size(); ++i) {
    const std::array<std::uint8_t, 3> c = {image.rgb[3 * i], image.rgb[3 * i + 1], image.rgb[3 * i + 2]};
    colours.insert(c);
    background += c == std::array<std::uint8_t, 3>{205, 212, 222};
    subject += image.subject[i];
  }
  EXPECT_GT(colours.size(), 8u);
  // The fitted card fills much of the frame but not all of it; the box a good part of it.
  EXPECT_GT(background, 0.1 * image.subject.size());
  EXPECT_LT(background, 0.7 * image.subject.size());
  EXPECT_GT(subject, 0.05 * image.subject.size());
}

TEST(Render, PopupOfABoxCoversTheModelOfItsFaces) {
  // The model made of exactly the faces the pop-up should stand up: the silhouettes coincide.
  const auto [popup, faces] = popup_and_model(open_box(), small_options());
  const Overlap o = overlap(popup, faces);
  EXPECT_GT(o.a, 2000);
  EXPECT_GE(o.iou(), 0.98) << o.a << " vs " << o.b << ", both " << o.both;
}

TEST(Render, PopupOfABoxLiesInsideTheBoxAndMatchesItFromTheFront) {
  const TriangleMesh box = test::box({kX0, 0, 0}, {kX1, kH, kD});
  // From the front right the closed box also shows its right side, which a pop-up has not.
  const auto [popup, model] = popup_and_model(box, small_options());
  const Overlap o = overlap(popup, model);
  EXPECT_GE(o.a_inside_b(), 0.98);
  EXPECT_LT(o.a, o.b);
  // From straight in front (and above) only the front and the top show: the same silhouette.
  RenderOptions front = small_options();
  front.azimuth_deg = 0;
  const auto [popup_front, model_front] = popup_and_model(box, front);
  EXPECT_GE(overlap(popup_front, model_front).iou(), 0.98);
}

TEST(Render, ShadowsOnlyDarken) {
  const ColouredMesh scene = box_popup(90);
  const auto [lo, hi] = bounds_of({&scene});
  RenderOptions lit = small_options();
  lit.shadows = false;
  const View view = frame_view(lo, hi, lit);
  const Image with = render(scene, view, small_options()), without = render(scene, view, lit);
  int darker = 0;
  for (std::size_t i = 0; i < with.rgb.size(); ++i) {
    EXPECT_LE(with.rgb[i], without.rgb[i]);
    darker += with.rgb[i] < without.rgb[i];
  }
  EXPECT_GT(darker, 0.01 * with.rgb.size()) << "the box casts a shadow on the card";
}

TEST(Render, OpeningFramesShareTheViewThatFramesThemAll) {
  const std::vector<PlanRegion> regions = test::box_popup_regions(Sheet{}, kX0, kX1, kH, kD);
  const std::vector<double> angles = {45, 90, 180};
  const std::vector<Image> frames = opening_frames(regions, Sheet{}, angles, 0, small_options());
  ASSERT_EQ(frames.size(), 3u);
  std::vector<ColouredMesh> scenes;
  for (const double angle : angles) scenes.push_back(box_popup(angle));
  const auto [lo, hi] = bounds_of({&scenes[0], &scenes[1], &scenes[2]});
  const View view = frame_view(lo, hi, small_options());
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(frames[i].rgb, render(scenes[i], view, small_options()).rgb) << i;
  EXPECT_NE(frames[0].rgb, frames[1].rgb);
  EXPECT_NE(frames[1].rgb, frames[2].rgb);
  // Flat, nothing stands: the box's faces lie in the sheet, seen from above.
  int flat_subject = 0;
  for (const std::uint8_t s : frames[2].subject) flat_subject += s;
  EXPECT_GT(flat_subject, 0);
}

std::vector<std::uint8_t> png_pixels(const std::string& bytes, int& width, int& height) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, bytes.data(), bytes.size())) return {};
  image.format = PNG_FORMAT_RGB;
  std::vector<std::uint8_t> pixels(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, pixels.data(), 0, nullptr)) return {};
  width = static_cast<int>(image.width);
  height = static_cast<int>(image.height);
  return pixels;
}

struct Reader {
  const std::string& bytes;
  std::size_t at = 0;
};

int read_bytes(GifFileType* gif, GifByteType* out, int length) {
  auto& r = *static_cast<Reader*>(gif->UserData);
  const std::size_t n = std::min(static_cast<std::size_t>(length), r.bytes.size() - r.at);
  std::memcpy(out, r.bytes.data() + r.at, n);
  r.at += n;
  return static_cast<int>(n);
}

TEST(Render, PngAndGifReadBackWithTheirPixels) {
  const std::vector<Image> frames =
      opening_frames(test::box_popup_regions(Sheet{}, kX0, kX1, kH, kD), Sheet{}, {45, 90, 135}, 0, small_options());
  int width = 0, height = 0;
  EXPECT_EQ(png_pixels(image_png(frames[1], "x.png"), width, height), frames[1].rgb);
  EXPECT_EQ(width, 240);
  EXPECT_EQ(height, 180);

  const std::string gif_bytes = animated_gif(frames, {10, 100, 10}, "x.gif");
  EXPECT_EQ(gif_bytes.substr(0, 6), "GIF89a");
  Reader reader{gif_bytes};
  int error = 0;
  GifFileType* gif = DGifOpen(&reader, read_bytes, &error);
  ASSERT_NE(gif, nullptr);
  ASSERT_EQ(DGifSlurp(gif), GIF_OK);
  EXPECT_EQ(gif->SWidth, 240);
  EXPECT_EQ(gif->SHeight, 180);
  ASSERT_EQ(gif->ImageCount, 3);
  bool loops = false;
  for (int k = 0; k < gif->SavedImages[0].ExtensionBlockCount; ++k) {
    const ExtensionBlock& block = gif->SavedImages[0].ExtensionBlocks[k];
    loops = loops || (block.Function == APPLICATION_EXT_FUNC_CODE && block.ByteCount == 11 &&
                      std::memcmp(block.Bytes, "NETSCAPE2.0", 11) == 0);
  }
  EXPECT_TRUE(loops);
  const int delays[] = {10, 100, 10};
  for (int f = 0; f < 3; ++f) {
    GraphicsControlBlock control{};
    ASSERT_EQ(DGifSavedExtensionToGCB(gif, f, &control), GIF_OK);
    EXPECT_EQ(control.DelayTime, delays[f]);
    // 256 colours for three frames of paper shades, on giflib's grid of 8 levels a channel rounded
    // to its nearest: on average within half a cell of the rendered colour.
    const SavedImage& image = gif->SavedImages[f];
    const ColorMapObject* map = image.ImageDesc.ColorMap ? image.ImageDesc.ColorMap : gif->SColorMap;
    ASSERT_NE(map, nullptr);
    double error_sum = 0;
    for (int i = 0; i < 240 * 180; ++i) {
      const GifColorType c = map->Colors[image.RasterBits[i]];
      const std::uint8_t* want = &frames[static_cast<std::size_t>(f)].rgb[3 * static_cast<std::size_t>(i)];
      error_sum += std::abs(c.Red - want[0]) + std::abs(c.Green - want[1]) + std::abs(c.Blue - want[2]);
    }
    EXPECT_LT(error_sum / (3 * 240 * 180), 4.0) << "mean error per channel, frame " << f;
  }
  DGifCloseFile(gif, &error);
}

TEST(Render, OptionsOutOfRangeAreRejected) {
  RenderOptions tiny = small_options();
  tiny.width_px = 4;
  EXPECT_THROW(frame_view({0, 0, 0}, {1, 1, 1}, tiny), InputError);
  RenderOptions no_samples = small_options();
  no_samples.samples = 0;
  EXPECT_THROW(frame_view({0, 0, 0}, {1, 1, 1}, no_samples), InputError);
  RenderOptions overhead = small_options();
  overhead.elevation_deg = 90;
  EXPECT_THROW(frame_view({0, 0, 0}, {1, 1, 1}, overhead), InputError);
}

}  // namespace
}  // namespace origamic
