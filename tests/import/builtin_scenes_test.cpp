#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "import_test_util.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/node_world.hpp"

namespace tsr::sg {
namespace {

using ::testing::HasSubstr;

TEST(BuiltinScenes, CornellBoxMatchesTheReferenceSetup) {
  Scene scene;
  const ImportResult r = importScene(scene, "builtin:cornell");
  const SceneStats s = computeSceneStats(scene, r.root);
  ASSERT_TRUE(s.hasBounds);
  EXPECT_NEAR(glm::distance(s.boundsMin, Vec3(0, 0, 0)), 0.0f, 1e-3f);
  EXPECT_NEAR(glm::distance(s.boundsMax, Vec3(556, 548.8f, 559.2f)), 0.0f, 1e-3f);
  EXPECT_GT(s.triangles, 30u);
  EXPECT_EQ(s.emissiveGeometries, 1u);
  EXPECT_EQ(scene.count(ContainerType::Geometry), 6u);  // white, red, green, light, two spheres

  ASSERT_EQ(r.cameras.size(), 1u);
  const Camera* cam = scene.find<Camera>(r.cameras[0]);
  EXPECT_NEAR(glm::distance(Vec3(tsr::sg::cameraWorldPose(*cam)[3]), Vec3(278, 273, -800)), 0.0f, 1e-3f);
  EXPECT_NEAR(glm::distance(-Vec3(tsr::sg::cameraWorldPose(*cam)[2]), Vec3(0, 0, 1)), 0.0f, 1e-5f);  // looks down +z
  EXPECT_NEAR(cam->verticalFov(), 37.0f * 3.14159265f / 180.0f, 1e-5f);

  const auto* mirror = test::byName<SurfaceMaterial>(scene, "mirror");
  const auto* glass = test::byName<SurfaceMaterial>(scene, "glass");
  const auto* light = test::byName<SurfaceMaterial>(scene, "light");
  ASSERT_TRUE(mirror && glass && light);
  EXPECT_EQ(mirror->metallic(), 1.0f);
  EXPECT_EQ(mirror->roughness(), 0.0f);
  EXPECT_EQ(mirror->baseColor(), Vec3(1));
  EXPECT_EQ(glass->transmission(), 1.0f);
  EXPECT_EQ(glass->ior(), 1.5f);
  EXPECT_EQ(glass->roughness(), 0.0f);
  EXPECT_GT(light->emittedRadiance().x, 10.0f);

  // Every geometry is valid and the spheres sit inside the box.
  for (ContainerId id : scene.ids())
    if (const Geometry* g = scene.find<Geometry>(id)) {
      EXPECT_FALSE(g->invalidReason()) << *g->invalidReason();
      EXPECT_EQ(g->normals().size(), g->positions().size());
    }
}

TEST(BuiltinScenes, InstancesShareAFewMeshes) {
  Scene scene;
  const ImportResult r = importScene(scene, "builtin:instances:100");
  const SceneStats s = computeSceneStats(scene, r.root);
  std::size_t instances = 0;
  for (ContainerId id : scene.ids())
    if (const Transform* t = scene.find<Transform>(id))
      for (ContainerId c : t->children())
        if (scene.find<Geometry>(c)) {
          ++instances;
          break;
        }
  EXPECT_EQ(instances, 100u);
  EXPECT_EQ(s.geometryInstances, 100u);
  EXPECT_LE(scene.count(ContainerType::Geometry), 12u);
  EXPECT_GE(scene.count(ContainerType::Geometry), 3u);
  EXPECT_GE(scene.count(ContainerType::SurfaceMaterial), 3u);
  EXPECT_GT(s.triangles, s.uniqueTriangles);
  EXPECT_EQ(s.lights, 1u);
  EXPECT_EQ(scene.find<Light>(r.lights.at(0))->kind(), LightKind::Directional);
  // A 10 x 10 grid with unit spacing around the origin.
  EXPECT_GT(s.boundsMin.x, -6.0f);
  EXPECT_LT(s.boundsMax.x, 6.0f);
  EXPECT_GT(s.boundsMax.x - s.boundsMin.x, 9.0f);

  // The camera sees every instance: each centre projects inside the frustum.
  const Camera* cam = scene.find<Camera>(r.cameras.at(0));
  const Mat4 view = glm::inverse(tsr::sg::cameraWorldPose(*cam));
  const float tanHalf = std::tan(cam->verticalFov() / 2);
  for (ContainerId id : scene.ids())
    if (const Transform* t = scene.find<Transform>(id);
        t && !t->children().empty() && scene.find<Geometry>(t->children()[0])) {
      const Vec3 p = Vec3(view * t->matrix()[3]);
      ASSERT_LT(p.z, 0.0f);
      EXPECT_LT(std::abs(p.y / -p.z), tanHalf);
      EXPECT_LT(std::abs(p.x / -p.z), tanHalf * 16.0f / 9.0f);
    }
}

TEST(BuiltinScenes, AnimatedMovesAnObjectAndALight) {
  Scene scene;
  const ImportResult r = importScene(scene, "builtin:animated");
  ASSERT_EQ(r.animations.size(), 1u);
  const Animation& a = r.animations[0];
  EXPECT_FLOAT_EQ(a.duration(), 4.0f);
  EXPECT_TRUE(a.looping());
  EXPECT_EQ(a.targets().size(), 2u);
  EXPECT_EQ(r.lights.size(), 1u);
  const Transform* cube = test::byName<Transform>(scene, "moving cube");
  const Transform* light = test::byName<Transform>(scene, "moving light");
  ASSERT_TRUE(cube && light);
  scene.commit();
  a.apply(scene, 1.0f);
  const Vec3 cubeAt1 = Vec3(cube->matrix()[3]);
  const Vec3 lightAt1 = Vec3(light->matrix()[3]);
  EXPECT_NEAR(cubeAt1.x, 280.0f, 1e-3f);
  const ChangeListPtr changes = scene.commit();
  EXPECT_EQ(changes->changes().size(), 2u);
  a.apply(scene, 5.0f);  // loops back to t = 1
  EXPECT_NEAR(glm::distance(Vec3(cube->matrix()[3]), cubeAt1), 0.0f, 1e-3f);
  a.apply(scene, 2.0f);
  EXPECT_GT(glm::distance(Vec3(light->matrix()[3]), lightAt1), 100.0f);
}

TEST(BuiltinScenes, BadNamesAndCountsAreImportErrors) {
  Scene scene;
  scene.create<Group>("kept");
  scene.commit();
  const std::uint64_t hash = scene.contentHash();
  for (const char* source : {"builtin:instances:0", "builtin:instances:abc", "builtin:instances:-3",
                             "builtin:instances:", "builtin:instances:10000001", "builtin:instances:5x",
                             "builtin:instances:99999999999999999999999"}) {
    try {
      importScene(scene, source);
      ADD_FAILURE() << source << " was accepted";
    } catch (const ImportError& e) {
      EXPECT_THAT(e.what(), HasSubstr(source));
      EXPECT_THAT(e.what(), HasSubstr("instance count"));
    }
  }
  try {
    importScene(scene, "builtin:nope");
    ADD_FAILURE() << "builtin:nope was accepted";
  } catch (const ImportError& e) {
    EXPECT_THAT(e.what(), HasSubstr("builtin:nope: unknown built-in scene"));
    EXPECT_THAT(e.what(), HasSubstr("builtin:cornell"));
    EXPECT_THAT(e.what(), HasSubstr("builtin:instances:N"));
  }
  EXPECT_EQ(scene.contentHash(), hash);
  EXPECT_FALSE(scene.hasPendingChanges());
}

}  // namespace
}  // namespace tsr::sg
