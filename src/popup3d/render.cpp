// SPDX-License-Identifier: GPL-3.0-or-later
#include "origamic/render.hpp"

#include <embree3/rtcore.h>
#include <gif_lib.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "origamic/error.hpp"
#include "embree_scene.hpp"
#include "png_image.hpp"

namespace origamic {
namespace {

constexpr Rgb8 kBackground{205, 212, 222};  // darker than paper, so holes in the card show
constexpr Rgb8 kModel{150, 172, 204};
constexpr double kAmbient = 0.55;  // the rest of the light comes from the key light
// Towards the key light: above, in front and to the left, so shadows fall back and to the right,
// where a camera from the front right sees them.
const glm::dvec3 kLight = glm::normalize(glm::dvec3(-0.4, 0.8, 0.65));

// One Embree scene over the coloured mesh, with each triangle's unit normal.
class Tracer {
 public:
  explicit Tracer(const ColouredMesh& scene)
      : scene_(scene), embree_(scene.positions, scene.triangles, RTC_BUILD_QUALITY_MEDIUM), handle_(embree_.handle()) {
    normals_.reserve(scene.triangles.size());
    for (const auto& t : scene.triangles) {
      const glm::dvec3 n =
          glm::cross(scene.positions[t[1]] - scene.positions[t[0]], scene.positions[t[2]] - scene.positions[t[0]]);
      const double length = glm::length(n);
      normals_.push_back(length > 0 ? n / length : glm::dvec3(0, 1, 0));
    }
    lo_ = glm::dvec3(std::numeric_limits<double>::infinity());
    hi_ = -lo_;
    for (const glm::dvec3& p : scene.positions) lo_ = glm::min(lo_, p), hi_ = glm::max(hi_, p);
  }
  Tracer(const Tracer&) = delete;
  Tracer& operator=(const Tracer&) = delete;

  struct Hit {
    std::int32_t triangle = -1;
    float t = 0;
  };

  Hit first_hit(const glm::dvec3& origin, const glm::dvec3& direction) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh{};
    set_ray(rh.ray, origin, direction);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(handle_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
    return {static_cast<std::int32_t>(rh.hit.primID), rh.ray.tfar};
  }

  bool occluded(const glm::dvec3& origin, const glm::dvec3& direction) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    set_ray(ray, origin, direction);
    rtcOccluded1(handle_, &context, &ray);
    return ray.tfar < 0;
  }

  const glm::dvec3& normal(std::int32_t triangle) const { return normals_[static_cast<std::size_t>(triangle)]; }
  double size() const { return scene_.positions.empty() ? 1.0 : glm::length(hi_ - lo_); }

 private:
  static void set_ray(RTCRay& ray, const glm::dvec3& origin, const glm::dvec3& direction) {
    ray.org_x = static_cast<float>(origin.x);
    ray.org_y = static_cast<float>(origin.y);
    ray.org_z = static_cast<float>(origin.z);
    ray.dir_x = static_cast<float>(direction.x);
    ray.dir_y = static_cast<float>(direction.y);
    ray.dir_z = static_cast<float>(direction.z);
    ray.tnear = 0;
    ray.tfar = std::numeric_limits<float>::infinity();
    ray.mask = ~0u;
  }

  const ColouredMesh& scene_;
  EmbreeScene embree_;
  RTCScene handle_;
  std::vector<glm::dvec3> normals_;
  glm::dvec3 lo_, hi_;
};

void check_options(const RenderOptions& options) {
  auto check_side = [](int px, const char* what) {
    if (px < 8 || px > 8192)
      throw InputError(std::string("RenderOptions::") + what + "_px",
                       std::string("the image ") + what + " must be 8 to 8192 pixels, not " +
                       std::to_string(px));
  };
  check_side(options.width_px, "width");
  check_side(options.height_px, "height");
  if (options.samples < 1 || options.samples > 8)
    throw InputError("RenderOptions::samples", "must be 1 to 8 a side, not " + std::to_string(options.samples));
  if (!(std::abs(options.elevation_deg) < 90) || !std::isfinite(options.azimuth_deg))
    throw InputError("RenderOptions::elevation_deg/RenderOptions::azimuth_deg",
                     "the elevation must lie strictly between -90 and 90 degrees, the azimuth be finite");
  if (!(options.fov_deg > 1 && options.fov_deg < 150))
    throw InputError("RenderOptions::fov_deg", "the field of view must lie between 1 and 150 degrees");
}

std::uint8_t to_byte(double value) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(value), 0L, 255L));
}

}  // namespace

ColouredMesh popup_scene(const FoldedPopup& popup, bool mark_unsupported) {
  ColouredMesh scene;
  scene.positions = popup.positions;
  scene.triangles = popup.triangles;
  for (std::size_t i = 0; i < popup.triangles.size(); ++i) {
    const auto region = static_cast<std::size_t>(popup.triangle_region[i]);
    const FoldedRegion& r = popup.regions[region];
    scene.colours.push_back(triangle_colour(popup, i, mark_unsupported));
    scene.subject.push_back(r.depth_mm != 0 ? 1 : 0);
    scene.part.push_back(static_cast<std::int32_t>(3 * region + static_cast<std::size_t>(popup.triangle_surface[i])));
  }
  return scene;
}

ColouredMesh model_scene(const TriangleMesh& oa_mesh, const Sheet& sheet) {
  ColouredMesh scene;
  scene.positions = oa_mesh.positions;
  scene.triangles = oa_mesh.triangles;
  scene.colours.assign(oa_mesh.triangles.size(), kModel);
  scene.subject.assign(oa_mesh.triangles.size(), 1);
  scene.part.assign(oa_mesh.triangles.size(), 0);
  const double W = sheet.width_mm, half = sheet.half_height_mm();
  auto rectangle = [&](const std::array<glm::dvec3, 4>& corners, Orientation orientation, std::int32_t part) {
    const auto first = static_cast<std::uint32_t>(scene.positions.size());
    scene.positions.insert(scene.positions.end(), corners.begin(), corners.end());
    scene.triangles.push_back({first, first + 1, first + 2});
    scene.triangles.push_back({first, first + 2, first + 3});
    const Rgb8 colour = paper_colour({orientation, 0.0, FaceStatus::Valid}, PaperSurface::Printed, false);
    scene.colours.insert(scene.colours.end(), 2, colour);
    scene.subject.insert(scene.subject.end(), 2, 0);
    scene.part.insert(scene.part.end(), 2, part);
  };
  rectangle({glm::dvec3(0, 0, 0), {W, 0, 0}, {W, half, 0}, {0, half, 0}}, Orientation::V, 1);  // back half, z = 0
  rectangle({glm::dvec3(0, 0, half), {W, 0, half}, {W, 0, 0}, {0, 0, 0}}, Orientation::H, 2);  // floor half, y = 0
  return scene;
}

std::array<glm::dvec3, 2> bounds_of(const std::vector<const ColouredMesh*>& meshes) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const ColouredMesh* mesh : meshes)
    for (const glm::dvec3& p : mesh->positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  if (!(lo.x <= hi.x)) lo = hi = glm::dvec3(0);
  return {lo, hi};
}

View frame_view(const glm::dvec3& lo, const glm::dvec3& hi, const RenderOptions& options) {
  check_options(options);
  constexpr double degree = 3.14159265358979323846 / 180;
  const double az = options.azimuth_deg * degree, el = options.elevation_deg * degree;
  const glm::dvec3 towards_eye(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
  const glm::dvec3 centre = (lo + hi) / 2.0;
  const double radius = std::max(glm::length(hi - lo) / 2, 1e-3);
  View view;
  view.width_px = options.width_px;
  view.height_px = options.height_px;
  view.eye = centre + towards_eye * (radius / std::sin(options.fov_deg * degree / 2));
  view.forward = -towards_eye;
  view.right = glm::normalize(glm::cross(view.forward, glm::dvec3(0, 1, 0)));
  view.up = glm::cross(view.right, view.forward);
  double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::dvec3 c((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
    const glm::dvec3 q = c - view.eye;
    const double z = glm::dot(q, view.forward), u = glm::dot(q, view.right) / z, v = glm::dot(q, view.up) / z;
    u0 = std::min(u0, u), u1 = std::max(u1, u), v0 = std::min(v0, v), v1 = std::max(v1, v);
  }
  constexpr double margin = 1.06;  // 3% each side
  view.pixel = margin * std::max((u1 - u0) / view.width_px, (v1 - v0) / view.height_px);
  view.u_min = (u0 + u1) / 2 - view.pixel * view.width_px / 2;
  view.v_max = (v0 + v1) / 2 + view.pixel * view.height_px / 2;
  return view;
}

Image render(const ColouredMesh& scene, const View& view, const RenderOptions& options) {
  check_options({.width_px = view.width_px, .height_px = view.height_px, .samples = options.samples});
  const Tracer tracer(scene);
  const int s = options.samples, sw = view.width_px * s, sh = view.height_px * s;
  auto direction = [&](int sx, int sy) {
    const double u = view.u_min + (sx + 0.5) / s * view.pixel, v = view.v_max - (sy + 0.5) / s * view.pixel;
    return view.forward + u * view.right + v * view.up;
  };
  // First pass: what every sample sees; second: its shade, outlined where its part changes.
  std::vector<Tracer::Hit> hits(static_cast<std::size_t>(sw) * sh);
  tbb::parallel_for(tbb::blocked_range<int>(0, sh), [&](const tbb::blocked_range<int>& rows) {
    for (int sy = rows.begin(); sy != rows.end(); ++sy)
      for (int sx = 0; sx < sw; ++sx)
        hits[static_cast<std::size_t>(sy) * sw + sx] = tracer.first_hit(view.eye, direction(sx, sy));
  });
  auto part_at = [&](int sx, int sy) {
    if (sx < 0 || sy < 0 || sx >= sw || sy >= sh) return std::numeric_limits<std::int32_t>::min();
    const std::int32_t t = hits[static_cast<std::size_t>(sy) * sw + sx].triangle;
    return t < 0 ? -1 : scene.part[static_cast<std::size_t>(t)];
  };
  const double offset = 1e-4 * tracer.size();  // shadow rays start this far off the surface
  Image image;
  image.width = view.width_px;
  image.height = view.height_px;
  image.rgb.resize(static_cast<std::size_t>(image.width) * image.height * 3);
  image.subject.resize(static_cast<std::size_t>(image.width) * image.height);
  tbb::parallel_for(tbb::blocked_range<int>(0, view.height_px), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row != rows.end(); ++row)
      for (int col = 0; col < view.width_px; ++col) {
        glm::dvec3 sum(0.0);
        int subject = 0;
        for (int sy = row * s; sy < (row + 1) * s; ++sy)
          for (int sx = col * s; sx < (col + 1) * s; ++sx) {
            const Tracer::Hit hit = hits[static_cast<std::size_t>(sy) * sw + sx];
            if (hit.triangle < 0) {
              sum += glm::dvec3(kBackground.r, kBackground.g, kBackground.b);
              continue;
            }
            const auto t = static_cast<std::size_t>(hit.triangle);
            subject += scene.subject[t];
            const glm::dvec3 ray = direction(sx, sy);
            glm::dvec3 n = tracer.normal(hit.triangle);
            if (glm::dot(n, ray) > 0) n = -n;  // paper is lit and seen on either side
            double light = std::max(0.0, glm::dot(n, kLight));
            if (light > 0 && options.shadows && tracer.occluded(view.eye + double(hit.t) * ray + offset * n, kLight))
              light = 0;
            double shade = kAmbient + (1 - kAmbient) * light;
            if (options.outlines) {  // samples beside another part (or the background) are drawn dark
              const std::int32_t p = part_at(sx, sy);
              bool edge = false;
              for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
                const std::int32_t q = part_at(sx + dx, sy + dy);
                edge = edge || (q != p && q != std::numeric_limits<std::int32_t>::min());
              }
              if (edge) shade *= 0.4;
            }
            const Rgb8 c = scene.colours[t];
            sum += shade * glm::dvec3(c.r, c.g, c.b);
          }
        const std::size_t pixel = static_cast<std::size_t>(row) * image.width + col;
        for (int k = 0; k < 3; ++k) image.rgb[3 * pixel + k] = to_byte(sum[k] / (s * s));
        image.subject[pixel] = 2 * subject >= s * s ? 1 : 0;
      }
  });
  return image;
}

std::string image_png(const Image& image, const std::string& name) {
  return encode_png(name, image.width, image.height, PngFormat::Rgb8, image.rgb);
}

std::string animated_gif(const std::vector<Image>& frames, const std::vector<int>& delays_cs, const std::string& name) {
  if (frames.empty() || delays_cs.size() != frames.size())
    throw std::invalid_argument("animated_gif: frames and delays");
  const int width = frames[0].width, height = frames[0].height;
  const std::size_t per_frame = static_cast<std::size_t>(width) * height;
  // One palette for every frame: quantize them all as one tall picture. giflib sorts colours into
  // cells of 8 levels a channel and gives each the low end of its cell: half a cell added first
  // makes that a rounding (mean error per channel 4.7 -> 2.9 levels on the test's box frames).
  std::vector<GifByteType> red(per_frame * frames.size()), green(red.size()), blue(red.size()), indices(red.size());
  auto rounded = [](std::uint8_t c) { return static_cast<GifByteType>(std::min(255, c + 4)); };
  for (std::size_t f = 0; f < frames.size(); ++f) {
    if (frames[f].width != width || frames[f].height != height)
      throw std::invalid_argument("animated_gif: frame sizes");
    for (std::size_t i = 0; i < per_frame; ++i) {
      red[f * per_frame + i] = rounded(frames[f].rgb[3 * i]);
      green[f * per_frame + i] = rounded(frames[f].rgb[3 * i + 1]);
      blue[f * per_frame + i] = rounded(frames[f].rgb[3 * i + 2]);
    }
  }
  int colours = 256;
  std::vector<GifColorType> palette(256);
  if (GifQuantizeBuffer(static_cast<unsigned>(width), static_cast<unsigned>(height * frames.size()), &colours,
                        red.data(), green.data(), blue.data(), indices.data(), palette.data()) == GIF_ERROR)
    throw OutputError(name + ": cannot reduce the frames to 256 colours");

  std::string bytes;
  auto append = [](GifFileType* gif, const GifByteType* data, int length) {
    static_cast<std::string*>(gif->UserData)
        ->append(reinterpret_cast<const char*>(data), static_cast<std::size_t>(length));
    return length;
  };
  int error = 0;
  GifFileType* gif = EGifOpen(&bytes, append, &error);
  if (!gif) throw OutputError(name + ": cannot encode GIF (" + GifErrorString(error) + ")");
  auto fail = [&] {
    const std::string message = GifErrorString(gif->Error);
    EGifCloseFile(gif, &error);
    throw OutputError(name + ": cannot encode GIF (" + message + ")");
  };
  ColorMapObject* map = GifMakeMapObject(256, palette.data());
  EGifSetGifVersion(gif, true);
  const bool screen_ok = EGifPutScreenDesc(gif, width, height, 8, 0, map) != GIF_ERROR;
  GifFreeMapObject(map);
  if (!screen_ok) fail();
  // Loop forever (the Netscape application extension).
  const GifByteType netscape[] = {'N', 'E', 'T', 'S', 'C', 'A', 'P', 'E', '2', '.', '0'};
  const GifByteType loop[] = {1, 0, 0};
  if (EGifPutExtensionLeader(gif, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
      EGifPutExtensionBlock(gif, sizeof netscape, netscape) == GIF_ERROR ||
      EGifPutExtensionBlock(gif, sizeof loop, loop) == GIF_ERROR || EGifPutExtensionTrailer(gif) == GIF_ERROR)
    fail();
  for (std::size_t f = 0; f < frames.size(); ++f) {
    GraphicsControlBlock control{};
    control.DisposalMode = DISPOSE_DO_NOT;
    control.DelayTime = delays_cs[f];
    control.TransparentColor = NO_TRANSPARENT_COLOR;
    GifByteType extension[4];
    const std::size_t length = EGifGCBToExtension(&control, extension);
    if (EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(length), extension) == GIF_ERROR ||
        EGifPutImageDesc(gif, 0, 0, width, height, false, nullptr) == GIF_ERROR)
      fail();
    for (int row = 0; row < height; ++row)
      if (EGifPutLine(gif, indices.data() + f * per_frame + static_cast<std::size_t>(row) * width, width) == GIF_ERROR)
        fail();
  }
  if (EGifCloseFile(gif, &error) == GIF_ERROR)
    throw OutputError(name + ": cannot encode GIF (" + GifErrorString(error) + ")");
  return bytes;
}

std::vector<Image> opening_frames(const std::vector<PlanRegion>& regions, const Sheet& sheet,
                                  const std::vector<double>& angles_deg, double thickness_mm,
                                  const RenderOptions& options) {
  std::vector<ColouredMesh> scenes;
  for (const double angle : angles_deg)
    scenes.push_back(popup_scene(fold_popup(regions, sheet, {.angle_deg = angle, .thickness_mm = thickness_mm}), true));
  std::vector<const ColouredMesh*> all;
  for (const ColouredMesh& scene : scenes) all.push_back(&scene);
  const auto [lo, hi] = bounds_of(all);
  const View view = frame_view(lo, hi, options);
  std::vector<Image> frames;
  for (const ColouredMesh& scene : scenes) frames.push_back(render(scene, view, options));
  return frames;
}

}  // namespace origamic
