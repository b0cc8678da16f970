// SPDX-License-Identifier: GPL-3.0-or-later
// Internal: one Embree device and scene over one triangle mesh, the setup the depth maps
// (raster.cpp) and the pictures (popup3d/render.cpp) share. Positions go to Embree as floats.
#pragma once

#include <embree3/rtcore.h>

#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace origamic {

class EmbreeScene {
 public:
  /// The scene of the triangles (indices into positions), its BVH built at `quality` (the depth maps
  /// trace each ray once, so LOW; pictures trace many, so the default MEDIUM).
  /// \throws std::runtime_error if Embree cannot make a device.
  EmbreeScene(const std::vector<glm::dvec3>& positions, const std::vector<std::array<std::uint32_t, 3>>& triangles,
              RTCBuildQuality quality);
  ~EmbreeScene();
  EmbreeScene(const EmbreeScene&) = delete;
  EmbreeScene& operator=(const EmbreeScene&) = delete;

  RTCScene handle() const { return scene_; }

 private:
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace origamic
