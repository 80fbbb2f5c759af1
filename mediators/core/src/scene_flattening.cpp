#include "tsr/med/scene_flattening.hpp"

#include <unordered_set>

namespace tsr::med {

glm::mat4 worldMatrix(const sg::Scene& scene, const std::vector<sg::ContainerId>& path, sg::FrameTime when) {
  glm::mat4 m(1.0f);
  for (sg::ContainerId id : path)
    if (const auto* t = scene.find<sg::Transform>(id))
      m = m * (when == sg::FrameTime::End ? t->matrixAtEnd() : t->matrix());
  return m;
}

namespace {
bool moves(const sg::Container& c) {
  return c.type() == sg::ContainerType::Transform &&
         static_cast<const sg::Transform&>(c).frameMotion() != glm::mat4(1.0f);
}
}  // namespace

bool pathMoves(const sg::Scene& scene, const std::vector<sg::ContainerId>& path) {
  for (sg::ContainerId id : path)
    if (const auto* c = scene.find(id); c && moves(*c)) return true;
  return false;
}

namespace {
// splitmix64's finaliser: ids are small and dense, the hash must spread them.
std::uint64_t mix(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}

FlatKey pathHash(const std::vector<sg::ContainerId>& path, sg::ContainerId id) {
  std::uint64_t h = mix(path.size());
  for (sg::ContainerId p : path) h = mix(h ^ p);
  return mix(h ^ id);
}

const std::vector<sg::ContainerId>* childrenOf(const sg::Container& c) {
  if (c.type() == sg::ContainerType::Group) return &static_cast<const sg::Group&>(c).children();
  if (c.type() == sg::ContainerType::Transform) return &static_cast<const sg::Transform&>(c).children();
  return nullptr;
}
}  // namespace

FlatScene flatten(const sg::Scene& scene, sg::ContainerId root, std::size_t maxInstances) {
  FlatScene flat;
  std::vector<sg::ContainerId> roots = root ? std::vector<sg::ContainerId>{root} : scene.roots();
  // Depth-first without recursion: the graph is acyclic (the scene
  // guarantees it) but may be deep.
  struct Frame {
    sg::ContainerId id;
    glm::mat4 world;
    bool moves = false;
    std::size_t next = 0;
  };
  std::vector<Frame> stack;
  std::vector<sg::ContainerId> path;
  std::unordered_set<FlatKey> taken;
  auto record = [&](const sg::Container& c, const glm::mat4& world, bool moving) {
    FlatNode node{c.id(), path, pathHash(path, c.id()), world, moving};
    while (!taken.insert(node.key).second) ++node.key;  // the occurrence
    auto& list = c.type() == sg::ContainerType::Geometry ? flat.instances : flat.lights;
    auto& under = c.type() == sg::ContainerType::Geometry ? flat.instancesUnder : flat.lightsUnder;
    if (&list == &flat.instances && list.size() >= maxInstances)
      throw FlatteningError("the scene expands to more than " + std::to_string(maxInstances) + " instances");
    for (sg::ContainerId p : path) under[p].push_back(static_cast<std::uint32_t>(list.size()));
    list.push_back(std::move(node));
  };
  for (sg::ContainerId r : roots) {
    const sg::Container* c = scene.find(r);
    if (!c) continue;
    if (!childrenOf(*c)) {
      if (c->type() == sg::ContainerType::Geometry || c->type() == sg::ContainerType::Light)
        record(*c, glm::mat4(1.0f), false);
      continue;
    }
    glm::mat4 world =
        c->type() == sg::ContainerType::Transform ? static_cast<const sg::Transform*>(c)->matrix() : glm::mat4(1.0f);
    stack.push_back({r, world, moves(*c)});
    path.push_back(r);
    while (!stack.empty()) {
      Frame& top = stack.back();
      const auto& kids = *childrenOf(*scene.find(top.id));
      if (top.next == kids.size()) {
        stack.pop_back();
        path.pop_back();
        continue;
      }
      const sg::Container* child = scene.find(kids[top.next++]);
      if (!child) continue;
      if (const auto* grandKids = childrenOf(*child)) {
        (void)grandKids;
        glm::mat4 world = child->type() == sg::ContainerType::Transform
                              ? top.world * static_cast<const sg::Transform*>(child)->matrix()
                              : top.world;
        stack.push_back({child->id(), world, top.moves || moves(*child)});
        path.push_back(child->id());
      } else if (child->type() == sg::ContainerType::Geometry || child->type() == sg::ContainerType::Light) {
        record(*child, top.world, top.moves);
      }
    }
  }
  return flat;
}

}  // namespace tsr::med
