#include "test_scenes.hpp"

#include <cmath>
#include <cstdlib>

#include <glm/gtc/constants.hpp>

#include "tsr/med/image_file.hpp"

namespace tsr::test {

namespace {
sg::Geometry& addMesh(sg::Scene& scene, sg::ContainerId parent, const std::string& name, std::vector<sg::Vec3> p,
                      std::vector<sg::Vec3> n, std::vector<std::uint32_t> i, sg::ContainerId material) {
  auto& g = scene.create<sg::Geometry>(name);
  g.setPositions(std::move(p));
  g.setNormals(std::move(n));
  g.setIndices(std::move(i));
  g.setMaterial(material);
  scene.find<sg::Group>(parent) ? scene.find<sg::Group>(parent)->addChild(g.id())
                                : scene.find<sg::Transform>(parent)->addChild(g.id());
  return g;
}
}  // namespace

sg::Geometry& addQuad(sg::Scene& scene, sg::ContainerId parent, const std::string& name, sg::Vec3 a, sg::Vec3 b,
                      sg::Vec3 c, sg::Vec3 d, sg::ContainerId material) {
  sg::Vec3 n = glm::normalize(glm::cross(b - a, c - a));
  return addMesh(scene, parent, name, {a, b, c, d}, {n, n, n, n}, {0, 1, 2, 0, 2, 3}, material);
}

sg::Geometry& addBox(sg::Scene& scene, sg::ContainerId parent, const std::string& name, sg::Vec3 lo, sg::Vec3 hi,
                     sg::ContainerId material) {
  std::vector<sg::Vec3> p, n;
  std::vector<std::uint32_t> idx;
  auto face = [&](sg::Vec3 a, sg::Vec3 b, sg::Vec3 c, sg::Vec3 d) {
    auto base = static_cast<std::uint32_t>(p.size());
    sg::Vec3 normal = glm::normalize(glm::cross(b - a, c - a));
    for (auto v : {a, b, c, d}) p.push_back(v), n.push_back(normal);
    for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(base + k);
  };
  const sg::Vec3 l = lo, h = hi;
  face({l.x, l.y, h.z}, {h.x, l.y, h.z}, {h.x, h.y, h.z}, {l.x, h.y, h.z});  // +z
  face({h.x, l.y, l.z}, {l.x, l.y, l.z}, {l.x, h.y, l.z}, {h.x, h.y, l.z});  // -z
  face({h.x, l.y, h.z}, {h.x, l.y, l.z}, {h.x, h.y, l.z}, {h.x, h.y, h.z});  // +x
  face({l.x, l.y, l.z}, {l.x, l.y, h.z}, {l.x, h.y, h.z}, {l.x, h.y, l.z});  // -x
  face({l.x, h.y, h.z}, {h.x, h.y, h.z}, {h.x, h.y, l.z}, {l.x, h.y, l.z});  // +y
  face({l.x, l.y, l.z}, {h.x, l.y, l.z}, {h.x, l.y, h.z}, {l.x, l.y, h.z});  // -y
  return addMesh(scene, parent, name, std::move(p), std::move(n), std::move(idx), material);
}

sg::Geometry& addSphere(sg::Scene& scene, sg::ContainerId parent, const std::string& name, sg::Vec3 centre,
                        float radius, int segments, sg::ContainerId material) {
  std::vector<sg::Vec3> p, n;
  std::vector<std::uint32_t> idx;
  const int rings = segments / 2;
  for (int r = 0; r <= rings; ++r) {
    float theta = glm::pi<float>() * static_cast<float>(r) / static_cast<float>(rings);
    for (int s = 0; s <= segments; ++s) {
      float phi = glm::two_pi<float>() * static_cast<float>(s) / static_cast<float>(segments);
      sg::Vec3 d(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      p.push_back(centre + radius * d);
      n.push_back(d);
    }
  }
  auto at = [&](int r, int s) { return static_cast<std::uint32_t>(r * (segments + 1) + s); };
  for (int r = 0; r < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      if (r > 0) idx.insert(idx.end(), {at(r, s), at(r + 1, s), at(r, s + 1)});
      if (r < rings - 1) idx.insert(idx.end(), {at(r, s + 1), at(r + 1, s), at(r + 1, s + 1)});
    }
  return addMesh(scene, parent, name, std::move(p), std::move(n), std::move(idx), material);
}

void keepImage(const std::string& name, const med::FrameBuffer& image) {
  if (const char* dir = std::getenv("TSR_TEST_IMAGE_DIR"))
    med::writeImage(std::string(dir) + "/" + name + ".png", image);
}

}  // namespace tsr::test
