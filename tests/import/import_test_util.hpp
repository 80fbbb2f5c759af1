#pragma once
// Small lookups over an imported scene for the import tests.
#include <optional>
#include <string>

#include "tsr/sg/scene.hpp"

namespace tsr::test {

template <class T>
T* byName(const sg::Scene& scene, const std::string& name) {
  for (sg::ContainerId id : scene.ids())
    if (auto* c = scene.find<T>(id); c && c->name() == name) return c;
  return nullptr;
}

// The world matrix of node `target` on the first path from `root`.
inline std::optional<sg::Mat4> worldOf(const sg::Scene& scene, sg::ContainerId root, sg::ContainerId target,
                                       const sg::Mat4& parent = sg::Mat4(1.0f)) {
  sg::Mat4 world = parent;
  const std::vector<sg::ContainerId>* children = nullptr;
  if (auto* t = scene.find<sg::Transform>(root)) {
    world = parent * t->matrix();
    children = &t->children();
  } else if (auto* g = scene.find<sg::Group>(root)) {
    children = &g->children();
  }
  if (root == target) return world;
  if (children)
    for (sg::ContainerId c : *children)
      if (auto w = worldOf(scene, c, target, world)) return w;
  return std::nullopt;
}

inline sg::Vec3 apply(const sg::Mat4& m, const sg::Vec3& p) { return sg::Vec3(m * sg::Vec4(p, 1.0f)); }

}  // namespace tsr::test
