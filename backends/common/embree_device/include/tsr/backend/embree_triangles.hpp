#pragma once
// A triangle mesh as the back-ends that trace with Embree hold it: its own
// Embree scene with one geometry (id 0) that has its own copy of the
// positions (Embree's vertex buffers must be padded for 16-byte loads) and
// shares the caller's indices, built for quality when static and for
// refits when animated. Instances of the mesh in a top level point at `scene`.
#include <embree3/rtcore.h>

#include <cstdint>
#include <span>

namespace tsr::backend {

struct EmbreeTriangles {
  RTCScene scene = nullptr;
  RTCGeometry geometry = nullptr;

  EmbreeTriangles() = default;
  EmbreeTriangles(const EmbreeTriangles&) = delete;
  EmbreeTriangles& operator=(const EmbreeTriangles&) = delete;
  ~EmbreeTriangles();

  // Makes the scene (once) and replaces its geometry with these triangles:
  // `positions` holds x, y, z per vertex (copied), `indices` three per
  // triangle (shared: they must stay valid until the next fill or the end).
  // `extraFlags` are added to the scene's own. Returns false when Embree
  // cannot allocate the buffers (the scene then holds no geometry).
  bool fill(RTCDevice device, std::span<const float> positions, std::span<const std::uint32_t> indices, bool animated,
            RTCSceneFlags extraFlags = RTC_SCENE_FLAG_NONE);
};

}  // namespace tsr::backend
