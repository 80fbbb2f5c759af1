// What incremental sync does, counted: a moved transform touches only the
// instance matrices below it, a material edit only transparency flags.
#include <gtest/gtest.h>

#include <set>

#include <glm/gtc/matrix_transform.hpp>

#include "coverage_viewport.hpp"
#include "tsr/med/coverage/register.hpp"
#include "tsr/sg/import/importer.hpp"

using namespace tsr;

namespace {
struct Rig {
  sg::Scene source;
  sg::ImportResult imported;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  std::unique_ptr<med::Viewport> viewport;
  Rig() {
    imported = sg::importScene(source, "builtin:instances:200");
    replica.apply(source.commit());
    med::registerCoverage(registry);
    med::ViewportSettings s;
    s.backend = "coverage";
    s.root = imported.root;
    viewport = registry.create(s, contexts);
    EXPECT_EQ(viewport->synchronize(replica), med::SceneAdapter::Update::Converted);
  }
  const med::coverage_mediator::CoverageSceneAdapter& adapter() const {
    return static_cast<const med::coverage_mediator::CoverageViewport&>(*viewport).context().adapter;
  }
  auto counters() const { return adapter().counters(); }
  std::size_t transformCount() const {
    std::size_t n = 0;
    for (auto id : source.ids()) n += source.find<sg::Transform>(id) != nullptr;
    return n;
  }
  std::uint64_t transparencyUpdates() const { return adapter().scene().transparencyUpdates(); }
  void publish() {
    replica.apply(source.commit());
    EXPECT_EQ(viewport->synchronize(replica), med::SceneAdapter::Update::Synced);
  }
};
}  // namespace

TEST(SyncCost, TransformEditMovesOnlyItsInstance) {
  Rig rig;
  const auto before = rig.counters();
  // Each placed geometry is built once, however often it is instanced.
  std::set<sg::ContainerId> placed;
  for (auto id : rig.source.ids())
    if (auto* t = rig.source.find<sg::Transform>(id))
      for (auto child : t->children())
        if (auto* g = rig.source.find<sg::Geometry>(child); g && g->triangleCount() > 0) placed.insert(child);
  ASSERT_GT(rig.transformCount(), placed.size()) << "the scene must instance geometries more than once";
  EXPECT_EQ(before.meshBuilds, placed.size());
  EXPECT_EQ(before.flattenings, 1u);
  sg::Transform* moved = nullptr;
  for (auto id : rig.source.ids())
    if (auto* t = rig.source.find<sg::Transform>(id); t && t->children().size() == 1 && !moved) moved = t;
  ASSERT_NE(moved, nullptr);
  moved->setMatrix(glm::translate(moved->matrix(), glm::vec3(0.1f, 0, 0)));
  rig.publish();
  const auto after = rig.counters();
  EXPECT_EQ(after.instanceTransforms, before.instanceTransforms + 1);
  EXPECT_EQ(after.flattenings, before.flattenings);
  EXPECT_EQ(after.meshBuilds, before.meshBuilds);
}

TEST(SyncCost, MaterialEditFlipsOnlyItsInstances) {
  Rig rig;
  const auto before = rig.counters();
  const auto flipsBefore = rig.transparencyUpdates();
  sg::SurfaceMaterial* material = nullptr;
  for (auto id : rig.source.ids())
    if (auto* m = rig.source.find<sg::SurfaceMaterial>(id); m && !material) material = m;
  ASSERT_NE(material, nullptr);
  std::size_t users = 0;
  for (auto id : rig.source.ids())
    if (auto* t = rig.source.find<sg::Transform>(id); t && t->children().size() == 1)
      if (auto* g = rig.source.find<sg::Geometry>(t->children().front()); g && g->material() == material->id()) ++users;
  ASSERT_GT(users, 0u);
  material->setOpacity(0.25f);
  rig.publish();
  const auto after = rig.counters();
  EXPECT_EQ(rig.transparencyUpdates(), flipsBefore + users);
  EXPECT_EQ(after.materialUpdates, before.materialUpdates + 1) << "one material, however many users";
  EXPECT_EQ(after.flattenings, before.flattenings);
  EXPECT_EQ(after.instanceTransforms, before.instanceTransforms);
}

TEST(SyncCost, PointsRangeEditUpdatesOnlyThatRange) {
  Rig rig;
  const auto before = rig.counters();
  sg::Geometry* geometry = nullptr;
  for (auto id : rig.source.ids())
    if (auto* g = rig.source.find<sg::Geometry>(id); g && !geometry) geometry = g;
  ASSERT_NE(geometry, nullptr);
  ASSERT_GE(geometry->positions().size(), 2u);
  std::vector<sg::Vec3> moved(geometry->positions().begin(), geometry->positions().begin() + 2);
  for (auto& p : moved) p.x += 0.01f;
  geometry->updatePositions(0, moved);
  rig.publish();
  auto after = rig.counters();
  EXPECT_EQ(after.meshRangeUpdates, before.meshRangeUpdates + 1);
  EXPECT_EQ(after.meshBuilds, before.meshBuilds);
  EXPECT_EQ(after.flattenings, before.flattenings);
  EXPECT_EQ(after.instanceTransforms, before.instanceTransforms);

  // The id pass holds no normals: editing them costs nothing here.
  std::vector<sg::Vec3> normals(geometry->positions().size(), sg::Vec3(0, 1, 0));
  geometry->setNormals(normals);
  rig.publish();
  const auto untouched = rig.counters();
  EXPECT_EQ(untouched.meshRangeUpdates, after.meshRangeUpdates);
  EXPECT_EQ(untouched.meshBuilds, after.meshBuilds);
}
