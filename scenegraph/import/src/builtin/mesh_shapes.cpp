#include "builtin/mesh_shapes.hpp"

#include <cmath>

#include <glm/gtc/constants.hpp>

namespace tsr::sg::shapes {

parsed::Primitive sphere(const Vec3& center, float radius, int rings) {
  parsed::Primitive m;
  const int segments = 2 * rings;
  const float pi = glm::pi<float>();
  // One extra column so the uv seam gets its own vertices.
  for (int i = 0; i <= rings; ++i) {
    const float theta = pi * static_cast<float>(i) / static_cast<float>(rings);
    for (int j = 0; j <= segments; ++j) {
      const float phi = 2.0f * pi * static_cast<float>(j) / static_cast<float>(segments);
      const Vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      m.positions.push_back(center + radius * n);
      m.normals.push_back(n);
      m.uvs.emplace_back(static_cast<float>(j) / static_cast<float>(segments),
                         static_cast<float>(i) / static_cast<float>(rings));
    }
  }
  const auto row = static_cast<std::uint32_t>(segments + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(rings); ++i)
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(segments); ++j) {
      const std::uint32_t a = i * row + j, b = a + 1, c = a + row, d = c + 1;
      // Outward-facing, counter-clockwise seen from outside.
      if (i > 0) m.indices.insert(m.indices.end(), {a, b, c});
      if (i + 1 < static_cast<std::uint32_t>(rings)) m.indices.insert(m.indices.end(), {b, d, c});
    }
  return m;
}

void appendQuad(parsed::Primitive& m, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const auto base = static_cast<std::uint32_t>(m.positions.size());
  const Vec3 n = glm::normalize(glm::cross(b - a, c - a));
  for (const Vec3& p : {a, b, c, d}) {
    m.positions.push_back(p);
    m.normals.push_back(n);
  }
  m.uvs.insert(m.uvs.end(), {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)});
  m.indices.insert(m.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

parsed::Primitive box(const Vec3& h) {
  parsed::Primitive m;
  const Vec3 p[8] = {{-h.x, -h.y, -h.z}, {h.x, -h.y, -h.z}, {h.x, h.y, -h.z}, {-h.x, h.y, -h.z},
                     {-h.x, -h.y, h.z},  {h.x, -h.y, h.z},  {h.x, h.y, h.z},  {-h.x, h.y, h.z}};
  appendQuad(m, p[4], p[5], p[6], p[7]);  // +z
  appendQuad(m, p[1], p[0], p[3], p[2]);  // -z
  appendQuad(m, p[5], p[1], p[2], p[6]);  // +x
  appendQuad(m, p[0], p[4], p[7], p[3]);  // -x
  appendQuad(m, p[7], p[6], p[2], p[3]);  // +y
  appendQuad(m, p[0], p[1], p[5], p[4]);  // -y
  return m;
}

parsed::Primitive torus(float major, float minor, int majorSegments, int minorSegments, float sweep) {
  parsed::Primitive m;
  const float twoPi = 2.0f * glm::pi<float>();
  for (int i = 0; i <= majorSegments; ++i) {
    const float u = sweep * static_cast<float>(i) / static_cast<float>(majorSegments);
    const Vec3 ring(std::cos(u), 0.0f, std::sin(u));
    for (int j = 0; j <= minorSegments; ++j) {
      const float v = twoPi * static_cast<float>(j) / static_cast<float>(minorSegments);
      const Vec3 n = std::cos(v) * ring + Vec3(0.0f, std::sin(v), 0.0f);
      m.positions.push_back(major * ring + minor * n);
      m.normals.push_back(n);
      m.uvs.emplace_back(static_cast<float>(i) / static_cast<float>(majorSegments),
                         static_cast<float>(j) / static_cast<float>(minorSegments));
    }
  }
  const auto row = static_cast<std::uint32_t>(minorSegments + 1);
  for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(majorSegments); ++i)
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(minorSegments); ++j) {
      const std::uint32_t a = i * row + j, b = a + row, c = a + 1, d = b + 1;
      m.indices.insert(m.indices.end(), {a, c, b, c, d, b});
    }
  return m;
}

std::size_t latheTriangles(std::span<const Vec2> profile, int segments) {
  std::size_t perSegment = 0;
  for (std::size_t k = 1; k < profile.size(); ++k)
    perSegment += (profile[k - 1].x > 0.0f ? 1u : 0u) + (profile[k].x > 0.0f ? 1u : 0u);
  return perSegment * static_cast<std::size_t>(segments);
}

parsed::Primitive lathe(std::span<const Vec2> profile, int segments) {
  parsed::Primitive m;
  const float twoPi = 2.0f * glm::pi<float>();
  const auto columns = static_cast<std::uint32_t>(segments + 1);
  m.positions.reserve(2 * columns * profile.size());
  m.normals.reserve(2 * columns * profile.size());
  m.uvs.reserve(2 * columns * profile.size());
  m.indices.reserve(3 * latheTriangles(profile, segments));
  for (std::size_t k = 1; k < profile.size(); ++k) {
    const Vec2 a = profile[k - 1], b = profile[k];
    // Outward in the (radius, y) plane: the profile's direction turned clockwise.
    const Vec2 d = b - a;
    const Vec2 n = glm::length(d) > 0.0f ? glm::normalize(Vec2(d.y, -d.x)) : Vec2(1, 0);
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (int ring = 0; ring < 2; ++ring)
      for (std::uint32_t j = 0; j < columns; ++j) {
        const Vec2 p = ring == 0 ? a : b;
        const float phi = twoPi * static_cast<float>(j) / static_cast<float>(segments);
        const float c = std::cos(phi), s = std::sin(phi);
        m.positions.emplace_back(p.x * c, p.y, p.x * s);
        m.normals.emplace_back(n.x * c, n.y, n.x * s);
        m.uvs.emplace_back(static_cast<float>(j) / static_cast<float>(segments), static_cast<float>(ring));
      }
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(segments); ++j) {
      const std::uint32_t a0 = base + j, a1 = a0 + 1, b0 = a0 + columns, b1 = b0 + 1;
      // A ring of radius 0 is one point: its half of the quad vanishes.
      if (a.x > 0.0f) m.indices.insert(m.indices.end(), {a0, b0, a1});
      if (b.x > 0.0f) m.indices.insert(m.indices.end(), {a1, b0, b1});
    }
  }
  return m;
}

}  // namespace tsr::sg::shapes
