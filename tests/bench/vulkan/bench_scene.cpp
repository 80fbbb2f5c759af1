#include "bench_scene.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <numbers>

namespace tsr::vk::bench {

namespace {
constexpr float kPi = std::numbers::pi_v<float>;

// (rings + 1) x (segments + 1) grid of vertices mapped by f(u, v) -> (position, normal).
template <class F>
MeshData grid(int rings, int segments, F f) {
  MeshData m;
  for (int r = 0; r <= rings; ++r)
    for (int s = 0; s <= segments; ++s) {
      glm::vec3 p, n;
      f(float(r) / float(rings), float(s) / float(segments), p, n);
      m.positions.push_back(p);
      m.normals.push_back(n);
      m.uvs.emplace_back(float(s) / float(segments), float(r) / float(rings));
    }
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      std::uint32_t i0 = r * (segments + 1) + s, i1 = i0 + 1, i2 = i0 + segments + 1, i3 = i2 + 1;
      m.indices.insert(m.indices.end(), {i0, i2, i1, i1, i2, i3});
    }
  return m;
}

MeshData sphere() {  // 32 x 32 x 2 = 2048 triangles
  return grid(32, 32, [](float u, float v, glm::vec3& p, glm::vec3& n) {
    float theta = kPi * u, phi = 2.0f * kPi * v;
    n = {std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi)};
    p = 0.5f * n;
  });
}

MeshData torus() {  // 32 x 32 x 2 = 2048 triangles
  return grid(32, 32, [](float u, float v, glm::vec3& p, glm::vec3& n) {
    float a = 2.0f * kPi * u, b = 2.0f * kPi * v;
    glm::vec3 ring(std::cos(b), 0.0f, -std::sin(b));
    n = std::cos(a) * ring + glm::vec3(0, std::sin(a), 0);
    p = 0.35f * ring + 0.15f * n;
  });
}

MeshData cube() {  // 6 faces x 13 x 13 x 2 = 2028 triangles
  MeshData m;
  const int k = 13;
  const glm::vec3 normals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& n : normals) {
    glm::vec3 t = std::abs(n.y) > 0.5f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    glm::vec3 b = glm::cross(n, t);
    MeshData face = grid(k, k, [&](float u, float v, glm::vec3& p, glm::vec3& nn) {
      p = 0.4f * (n + (2.0f * u - 1.0f) * t + (2.0f * v - 1.0f) * b);
      nn = n;
    });
    const std::uint32_t base = std::uint32_t(m.positions.size());
    m.positions.insert(m.positions.end(), face.positions.begin(), face.positions.end());
    m.normals.insert(m.normals.end(), face.normals.begin(), face.normals.end());
    m.uvs.insert(m.uvs.end(), face.uvs.begin(), face.uvs.end());
    for (std::uint32_t i : face.indices) m.indices.push_back(base + i);
  }
  return m;
}
}  // namespace

std::uint64_t BenchScene::trianglesPerFrame() const {
  std::uint64_t t = 0;
  for (std::uint32_t m : instanceMesh) t += meshes[m].indices.size() / 3;
  return t;
}

BenchScene makeBenchScene(std::uint32_t instances, std::uint32_t width, std::uint32_t height) {
  BenchScene s;
  s.meshes = {sphere(), cube(), torus()};
  const std::uint32_t side = std::uint32_t(std::ceil(std::sqrt(float(instances))));
  const float spacing = 1.2f;
  const float half = 0.5f * spacing * float(side - 1);
  for (std::uint32_t i = 0; i < instances; ++i) {
    const float x = float(i % side) * spacing - half, z = float(i / side) * spacing - half;
    glm::mat4 t = glm::translate(glm::mat4(1.0f), {x, 0.0f, z});
    t = glm::rotate(t, 0.37f * float(i), glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f)));
    s.instanceMesh.push_back(i % 3);
    s.instanceTransform.push_back(t);
  }
  s.camera = Camera::lookAt({0.0f, 0.9f * half, 1.5f * half}, {0, 0, -0.1f * half}, {0, 1, 0}, 1.0f,
                            float(width) / float(height), 0.1f, 4.0f * half);
  return s;
}

}  // namespace tsr::vk::bench
