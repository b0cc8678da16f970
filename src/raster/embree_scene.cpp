// SPDX-License-Identifier: GPL-3.0-or-later
#include "embree_scene.hpp"

#include <stdexcept>

namespace origamic {

EmbreeScene::EmbreeScene(const std::vector<glm::dvec3>& positions,
                         const std::vector<std::array<std::uint32_t, 3>>& triangles, RTCBuildQuality quality) {
  device_ = rtcNewDevice(nullptr);
  if (!device_) throw std::runtime_error("Embree: cannot create a device");
  scene_ = rtcNewScene(device_);
  rtcSetSceneBuildQuality(scene_, quality);
  if (!triangles.empty()) {
    RTCGeometry geometry = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), positions.size()));
    for (std::size_t i = 0; i < positions.size(); ++i)
      for (int k = 0; k < 3; ++k) vertices[3 * i + k] = static_cast<float>(positions[i][k]);
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), triangles.size()));
    for (std::size_t i = 0; i < triangles.size(); ++i)
      for (std::size_t k = 0; k < 3; ++k) indices[3 * i + k] = triangles[i][k];
    rtcSetGeometryBuildQuality(geometry, quality);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene_, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(scene_);
}

EmbreeScene::~EmbreeScene() {
  rtcReleaseScene(scene_);
  rtcReleaseDevice(device_);
}

}  // namespace origamic
