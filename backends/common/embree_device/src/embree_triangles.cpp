#include "tsr/backend/embree_triangles.hpp"

#include <algorithm>

namespace tsr::backend {

EmbreeTriangles::~EmbreeTriangles() {
  if (geometry) rtcReleaseGeometry(geometry);
  if (scene) rtcReleaseScene(scene);
}

bool EmbreeTriangles::fill(RTCDevice device, std::span<const float> positions, std::span<const std::uint32_t> indices,
                           bool animated, RTCSceneFlags extraFlags) {
  if (!scene) scene = rtcNewScene(device);
  if (geometry) {
    rtcDetachGeometry(scene, 0);
    rtcReleaseGeometry(geometry);
  }
  geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  if (!scene || !geometry) return false;
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), positions.size() / 3));
  if (!v) {
    rtcReleaseGeometry(geometry);
    geometry = nullptr;
    return false;
  }
  std::copy(positions.begin(), positions.end(), v);
  rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices.data(), 0,
                             3 * sizeof(std::uint32_t), indices.size() / 3);
  rtcSetGeometryBuildQuality(geometry, animated ? RTC_BUILD_QUALITY_REFIT : RTC_BUILD_QUALITY_HIGH);
  rtcSetSceneFlags(scene, extraFlags | (animated ? RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_NONE));
  rtcSetSceneBuildQuality(scene, animated ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_HIGH);
  rtcAttachGeometryByID(scene, geometry, 0);
  return true;
}

}  // namespace tsr::backend
