#pragma once
// Random scenes and random edit sequences for property tests: every kind of
// container, field, range edit, creation and destruction, driven by a seed.
#include <random>
#include <vector>

#include "tsr/sg/scene.hpp"

namespace tsr::sg::test {

class RandomEditor {
 public:
  RandomEditor(Scene& scene, std::uint64_t seed) : scene_(scene), rng_(seed) {}

  float real(float lo = -10.0f, float hi = 10.0f) { return std::uniform_real_distribution<float>(lo, hi)(rng_); }
  std::size_t pick(std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng_); }
  bool chance(double p) { return std::bernoulli_distribution(p)(rng_); }
  Vec3 vec3() { return {real(), real(), real()}; }

  // Creates one container of a random type, wired into the graph.
  void createOne() {
    switch (pick(8)) {
      case 0:
        link(scene_.create<Group>("group").id());
        break;
      case 1: {
        auto& t = scene_.create<Transform>("transform");
        t.setMatrix(randomMatrix());
        link(t.id());
        break;
      }
      case 2: {
        auto& g = scene_.create<Geometry>("mesh");
        std::size_t n = 3 + pick(60);
        std::vector<Vec3> p(n);
        for (auto& v : p) v = vec3();
        g.setPositions(p);
        std::vector<std::uint32_t> idx(3 * (1 + pick(20)));
        for (auto& i : idx) i = static_cast<std::uint32_t>(pick(n));
        g.setIndices(idx);
        if (chance(0.5)) g.setNormals(std::vector<Vec3>(n, Vec3(0, 1, 0)));
        if (chance(0.3)) g.setUvs(std::vector<Vec2>(n, Vec2(real(0, 1), real(0, 1))));
        if (auto m = any(kMaterialTypes)) g.setMaterial(*m);
        link(g.id());
        break;
      }
      case 3: {
        auto& m = scene_.create<SurfaceMaterial>("surface");
        m.setBaseColor({real(0, 1), real(0, 1), real(0, 1)});
        m.setRoughness(real(0, 1));
        if (auto i = any(kImageTypes)) m.setBaseColorTexture(*i);
        m.setAttachment("embree.maxDepth", std::int64_t(pick(16)));
        break;
      }
      case 4:
        scene_.create<SimpleMaterial>("simple").setDiffuse({real(0, 1), 0.5f, 0.25f});
        break;
      case 5: {
        auto& img = scene_.create<Image>("image");
        std::uint32_t w = 1 + static_cast<std::uint32_t>(pick(8)), h = 1 + static_cast<std::uint32_t>(pick(8));
        std::vector<std::uint8_t> px(std::size_t{w} * h * 4);
        for (auto& b : px) b = static_cast<std::uint8_t>(pick(256));
        img.setPixels(w, h, 4, PixelFormat::UInt8, px);
        break;
      }
      case 6: {
        auto& l = scene_.create<Light>("light");
        l.setKind(static_cast<LightKind>(pick(3)));
        l.setIntensity(real(0, 100));
        link(l.id());
        break;
      }
      default:
        scene_.create<Camera>("camera").lookAt(vec3(), vec3() + Vec3(0.5f, 0.25f, 1.0f));
        break;
    }
  }

  // One random edit of an existing container (or a creation/destruction).
  void editOne() {
    auto ids = scene_.ids();
    if (ids.empty() || chance(0.15)) return createOne();
    Container* c = scene_.find(ids[pick(ids.size())]);
    if (chance(0.05)) return scene_.destroy(c->id());
    if (chance(0.1)) return c->setName("renamed" + std::to_string(pick(100)));
    if (chance(0.05)) return c->setAttachment("note", std::string("x") + std::to_string(pick(9)));
    switch (c->type()) {
      case ContainerType::Transform:
        static_cast<Transform*>(c)->setMatrix(randomMatrix());
        break;
      case ContainerType::Group:
        if (auto child = any(kNodeTypes); child && chance(0.5)) {
          try {
            static_cast<Group*>(c)->addChild(*child);
          } catch (const SceneError&) {  // would make a cycle
          }
        } else if (!static_cast<Group*>(c)->children().empty()) {
          static_cast<Group*>(c)->removeChild(static_cast<Group*>(c)->children().front());
        }
        break;
      case ContainerType::Geometry: {
        auto* g = static_cast<Geometry*>(c);
        if (g->positions().empty() || chance(0.2)) {
          g->setMotion(chance(0.5) ? GeometryMotion::Animated : GeometryMotion::Static);
          break;
        }
        std::size_t begin = pick(g->positions().size());
        std::size_t count = 1 + pick(std::min<std::size_t>(5, g->positions().size() - begin));
        std::vector<Vec3> v(count);
        for (auto& p : v) p = vec3();
        g->updatePositions(begin, v);
        if (chance(0.2)) g->setMaterial(any(kMaterialTypes).value_or(kNoContainer));
        break;
      }
      case ContainerType::SurfaceMaterial:
        static_cast<SurfaceMaterial*>(c)->setMetallic(real(0, 1));
        break;
      case ContainerType::SimpleMaterial:
        static_cast<SimpleMaterial*>(c)->setShininess(real(1, 100));
        break;
      case ContainerType::Light:
        static_cast<Light*>(c)->setColor({real(0, 1), real(0, 1), real(0, 1)});
        break;
      case ContainerType::Camera:
        static_cast<Camera*>(c)->setVerticalFov(real(0.2f, 1.5f));
        break;
      case ContainerType::Image:
        static_cast<Image*>(c)->setColorSpace(ColorSpace::Linear);
        break;
      case ContainerType::Background:
        static_cast<Background*>(c)->setIntensity(real(0, 2));
        break;
      case ContainerType::VolumeMaterial:
        static_cast<VolumeMaterial*>(c)->setAbsorption({real(0, 1), real(0, 1), real(0, 1)});
        break;
    }
  }

  Mat4 randomMatrix() {
    Mat4 m(1.0f);
    m[3] = Vec4(vec3(), 1.0f);
    m[0][0] = real(0.5f, 2.0f);
    return m;
  }

 private:
  std::optional<ContainerId> any(TypeSet types) {
    std::vector<ContainerId> candidates;
    for (ContainerId id : scene_.ids())
      if (typeBit(scene_.find(id)->type()) & types) candidates.push_back(id);
    if (candidates.empty()) return std::nullopt;
    return candidates[pick(candidates.size())];
  }
  // Puts a new node under a random parent, if there is one and no cycle forms.
  void link(ContainerId node) {
    std::vector<ContainerId> parents;
    for (ContainerId id : scene_.ids())
      if (isParentType(scene_.find(id)->type()) && id != node) parents.push_back(id);
    if (parents.empty() || chance(0.2)) return;
    Container* p = scene_.find(parents[pick(parents.size())]);
    try {
      if (p->type() == ContainerType::Group)
        static_cast<Group*>(p)->addChild(node);
      else
        static_cast<Transform*>(p)->addChild(node);
    } catch (const SceneError&) {}
  }

  Scene& scene_;
  std::mt19937_64 rng_;
};

}  // namespace tsr::sg::test
