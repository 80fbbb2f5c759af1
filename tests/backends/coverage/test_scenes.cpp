#include "test_scenes.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace tsr::cov::test {

MeshData quad(float x0, float x1, float y0, float y1, float z) {
  MeshData m;
  m.positions = {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}};
  m.indices = {0, 1, 2, 0, 2, 3};
  return m;
}

Camera straightCamera() { return Camera{}; }

RandomScene randomScene(std::uint32_t seed, std::uint32_t count, std::uint32_t objects) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  RandomScene s;
  s.meshes.push_back(quad(-0.5f, 0.5f, -0.5f, 0.5f, 0.0f));
  MeshData box;
  for (int i = 0; i < 8; ++i)
    box.positions.emplace_back(i & 1 ? 0.4f : -0.4f, i & 2 ? 0.4f : -0.4f, i & 4 ? 0.4f : -0.4f);
  box.indices = {0, 1, 3, 0, 3, 2, 4, 6, 7, 4, 7, 5, 0, 4, 5, 0, 5, 1,
                 2, 3, 7, 2, 7, 6, 0, 2, 6, 0, 6, 4, 1, 5, 7, 1, 7, 3};
  s.meshes.push_back(box);
  MeshData soup;
  for (int t = 0; t < 30; ++t)
    for (int k = 0; k < 3; ++k) {
      // Drawn one by one: argument order is unspecified, braces' is not.
      const float x = u(rng) * 0.6f, y = u(rng) * 0.6f, z = u(rng) * 0.6f;
      soup.positions.emplace_back(x, y, z);
      soup.indices.push_back(static_cast<std::uint32_t>(soup.positions.size() - 1));
    }
  s.meshes.push_back(soup);
  for (std::uint32_t i = 0; i < count; ++i) {
    Instance inst;
    inst.mesh = MeshId(rng() % s.meshes.size());
    glm::vec3 at(u(rng) * 4.0f, u(rng) * 4.0f, -6.0f + u(rng) * 3.0f);
    inst.transform = glm::rotate(glm::translate(glm::mat4(1.0f), at), u(rng) * 3.0f,
                                 glm::normalize(glm::vec3(u(rng), u(rng), 1.0f)));
    inst.object = 1 + rng() % objects;
    s.instances.push_back(inst);
  }
  return s;
}

std::vector<InstanceId> load(IdRenderer& renderer, const RandomScene& scene) {
  std::vector<MeshId> meshes;
  for (const auto& m : scene.meshes) meshes.push_back(renderer.addMesh(m));
  std::vector<InstanceId> handles;
  for (Instance inst : scene.instances) {
    inst.mesh = meshes[index(inst.mesh)];
    handles.push_back(renderer.addInstance(inst));
  }
  return handles;
}

}  // namespace tsr::cov::test
