// The catch-up rules every back-end's adapter inherits, through a small
// adapter that mirrors the replica's containers into a map.
#include "tsr/med/scene_adapter.hpp"

#include <gtest/gtest.h>

#include "tsr/med/context_pool.hpp"
#include "tsr/med/scene_flattening.hpp"
#include "tsr/med/viewport_registry.hpp"

using namespace tsr;

namespace {
class CountingAdapter : public med::SceneAdapter {
 public:
  int converts = 0, syncs = 0;
  std::size_t lastSyncEntries = 0;
  std::map<sg::ContainerId, std::string> names;  // the "back-end scene"

 protected:
  void convert(const sg::Scene& scene) override {
    ++converts;
    names.clear();
    for (auto id : scene.ids()) names[id] = scene.find(id)->name();
  }
  void sync(const sg::Scene& scene, const sg::MergedChanges& changes) override {
    ++syncs;
    lastSyncEntries = changes.entries().size();
    for (const auto& [id, e] : changes.entries()) {
      if (e.destroyed)
        names.erase(id);
      else
        names[id] = scene.find(id)->name();
    }
  }
};

std::map<sg::ContainerId, std::string> namesOf(const sg::Scene& s) {
  std::map<sg::ContainerId, std::string> m;
  for (auto id : s.ids()) m[id] = s.find(id)->name();
  return m;
}
}  // namespace

TEST(SceneAdapter, ConvertsOnceThenSyncsAndCatchesUpAfterAPause) {
  sg::Scene source;
  sg::Replica replica(8);
  source.create<sg::Group>("a");
  replica.apply(source.commit());
  CountingAdapter adapter;
  EXPECT_EQ(adapter.catchUp(replica), med::SceneAdapter::Update::Converted);
  EXPECT_EQ(adapter.catchUp(replica), med::SceneAdapter::Update::None);

  // Paused for five frames of edits, then one sync covering all of them.
  for (int f = 0; f < 5; ++f) {
    source.create<sg::Transform>("t" + std::to_string(f));
    source.find(1)->setName("a" + std::to_string(f));
    replica.apply(source.commit());
  }
  EXPECT_EQ(adapter.catchUp(replica), med::SceneAdapter::Update::Synced);
  EXPECT_EQ(adapter.syncs, 1);
  EXPECT_EQ(adapter.lastSyncEntries, 6u);
  EXPECT_EQ(adapter.names, namesOf(replica.scene()));

  // Fell out of the log's window: converts again.
  for (int f = 0; f < 20; ++f) {
    source.find(1)->setName("b" + std::to_string(f));
    replica.apply(source.commit());
  }
  EXPECT_EQ(adapter.catchUp(replica), med::SceneAdapter::Update::Converted);
  EXPECT_EQ(adapter.converts, 2);
  EXPECT_EQ(adapter.names, namesOf(replica.scene()));
}

TEST(ContextPool, SharesByKeyAndFreesWithTheLastUser) {
  med::ContextPool pool;
  int made = 0;
  auto make = [&] {
    ++made;
    return std::make_shared<int>(42);
  };
  auto a = pool.acquire<int>("embree", make);
  auto b = pool.acquire<int>("embree", make);
  EXPECT_EQ(a.get(), b.get());
  EXPECT_EQ(made, 1);
  auto c = pool.acquire<int>("vulkan", make);
  EXPECT_EQ(pool.live(), 2u);
  a.reset();
  b.reset();
  EXPECT_EQ(pool.live(), 1u);
}

TEST(ViewportRegistry, UnknownBackendListsTheKnownOnes) {
  med::ViewportRegistry registry;
  static const med::BackendCapabilities alpha;
  registry.add("alpha", alpha, [](const med::ViewportSettings&, med::ContextPool&) -> std::unique_ptr<med::Viewport> {
    return nullptr;
  });
  med::ContextPool pool;
  try {
    med::ViewportSettings settings;
    settings.backend = "beta";
    registry.create(settings, pool);
    FAIL();
  } catch (const med::UnknownBackend& e) {
    EXPECT_NE(std::string(e.what()).find("known: alpha"), std::string::npos) << e.what();
  }
}

TEST(SceneFlattening, InstancesCarryTheProductOfTheirTransforms) {
  sg::Scene s;
  auto& root = s.create<sg::Group>();
  auto& a = s.create<sg::Transform>();
  auto& b = s.create<sg::Transform>();
  auto& mesh = s.create<sg::Geometry>();
  auto& light = s.create<sg::Light>();
  glm::mat4 ta(1.0f), tb(1.0f);
  ta[3] = glm::vec4(1, 0, 0, 1);
  tb[0][0] = 2.0f;
  a.setMatrix(ta);
  b.setMatrix(tb);
  root.addChild(a.id());
  root.addChild(b.id());
  a.addChild(b.id());     // b under root and under a
  b.addChild(mesh.id());  // so the mesh appears twice
  a.addChild(light.id());
  auto flat = med::flatten(s, root.id());
  ASSERT_EQ(flat.instances.size(), 2u);
  EXPECT_EQ(flat.instances[0].world, ta * tb);
  EXPECT_EQ(flat.instances[1].world, tb);
  EXPECT_NE(flat.instances[0].key, flat.instances[1].key);
  EXPECT_EQ(med::flatten(s, root.id()).instances[1].key, flat.instances[1].key) << "keys are stable";
  EXPECT_EQ(flat.instancesUnder.at(b.id()).size(), 2u);
  EXPECT_EQ(flat.instancesUnder.at(a.id()).size(), 1u);
  ASSERT_EQ(flat.lights.size(), 1u);
  EXPECT_EQ(flat.lights[0].world, ta);
  EXPECT_EQ(med::worldMatrix(s, flat.instances[0].path), ta * tb);
  EXPECT_THROW(med::flatten(s, root.id(), 1), med::FlatteningError);
  EXPECT_EQ(med::flatten(s, 0).instances.size(), 2u) << "no root: every root";
}
