#pragma once

#include "tsr/vk/device.hpp"
#include "tsr/vk/error.hpp"
#include "tsr/vk/framebuffer.hpp"
#include "tsr/vk/material.hpp"
#include "tsr/vk/mesh.hpp"
#include "tsr/vk/vocabulary.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace tsr::vk::test {

// One device for the whole test binary: creating one per test costs time on lavapipe.
inline std::shared_ptr<Device> device() {
  static std::shared_ptr<Device> d = Device::create();
  return d;
}

// A black surface giving off `emission` from its front: its colour is that,
// whatever the lights.
inline Material glowing(glm::vec3 emission) {
  Material m;
  m.baseColor = glm::vec3(0.0f);
  m.emission = emission;
  return m;
}

// A quad with corners a, b, c, d counter-clockwise as seen from the front
// (bottom-left, bottom-right, top-right, top-left); uv (0, 0) is the top-left
// corner d, as in glTF.
inline MeshData quad(glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d, bool withNormals = true) {
  MeshData m;
  m.positions = {a, b, c, d};
  if (withNormals) {
    glm::vec3 n = glm::normalize(glm::cross(b - a, d - a));
    m.normals = {n, n, n, n};
  }
  m.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

// Axis-aligned square in the plane y = height, facing +Y, of half-size s around (cx, cz).
inline MeshData groundQuad(float cx, float cz, float s, float height = 0.0f) {
  return quad({cx - s, height, cz + s}, {cx + s, height, cz + s}, {cx + s, height, cz - s}, {cx - s, height, cz - s});
}

inline MeshData uvSphere(int rings, int segments, float radius = 1.0f) {
  MeshData m;
  for (int r = 0; r <= rings; ++r) {
    float theta = float(M_PI) * float(r) / float(rings);
    for (int s = 0; s <= segments; ++s) {
      float phi = 2.0f * float(M_PI) * float(s) / float(segments);
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      m.positions.push_back(radius * n);
      m.normals.push_back(n);
      m.uvs.emplace_back(float(s) / float(segments), float(r) / float(rings));
    }
  }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      std::uint32_t i0 = r * (segments + 1) + s, i1 = i0 + 1, i2 = i0 + segments + 1, i3 = i2 + 1;
      m.indices.insert(m.indices.end(), {i0, i2, i1, i1, i2, i3});
    }
  return m;
}

// Pixel (fractional, full-image coordinates) where world point p lands.
inline glm::vec2 project(const Camera& c, const Region& full, const glm::vec3& p) {
  glm::vec3 q(c.worldToCamera() * glm::vec4(p, 1.0f));
  float x = -c.near * q.x / q.z, y = -c.near * q.y / q.z;
  return {(x - c.left) / (c.right - c.left) * float(full.width), (c.top - y) / (c.top - c.bottom) * float(full.height)};
}

// World point where the centre of pixel (px, py) sees the plane dot(n, x) = d.
inline glm::vec3 pixelOnPlane(const Camera& c, const Region& full, int px, int py, glm::vec3 n, float d) {
  float x = c.left + (c.right - c.left) * (float(px) + 0.5f) / float(full.width);
  float y = c.top - (c.top - c.bottom) * (float(py) + 0.5f) / float(full.height);
  glm::vec3 org(c.cameraToWorld[3]);
  glm::vec3 dir = glm::normalize(glm::vec3(c.cameraToWorld * glm::vec4(x, y, -c.near, 0.0f)));
  float t = (d - glm::dot(n, org)) / glm::dot(n, dir);
  return org + t * dir;
}

// Writes an sRGB-encoded, clamped PNG for looking at results (test_util.cpp).
void writePng(const std::string& path, const FrameBuffer& fb, float exposure = 1.0f);

inline float maxAbsDiff(const FrameBuffer& a, const FrameBuffer& b) {
  float m = 0.0f;
  for (std::size_t i = 0; i < a.colourImage().size(); ++i)
    for (int c = 0; c < 4; ++c) m = std::max(m, std::abs(a.colourImage()[i][c] - b.colourImage()[i][c]));
  return m;
}

}  // namespace tsr::vk::test
