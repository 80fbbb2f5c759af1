#include <cmath>
#include <map>
#include <set>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "builtin/builtin_scenes.hpp"
#include "cache/parsed_scene_codec.hpp"
#include "cache/scene_cache.hpp"
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

// The plant's objects: top-level Transforms holding one Geometry each.
struct PlantObject {
  const Transform* node;
  const Geometry* geometry;
};

std::vector<PlantObject> plantObjects(const Scene& scene, ContainerId root) {
  std::vector<PlantObject> out;
  for (ContainerId id : scene.find<Group>(root)->children())
    if (const Transform* t = scene.find<Transform>(id); t && t->children().size() == 1)
      if (const Geometry* g = scene.find<Geometry>(t->children()[0])) out.push_back({t, g});
  return out;
}

struct Box3 {
  Vec3 lo{INFINITY}, hi{-INFINITY};
  bool contains(const Box3& o, float tolerance) const {
    return glm::all(glm::lessThanEqual(lo - tolerance, o.lo)) && glm::all(glm::lessThanEqual(o.hi, hi + tolerance));
  }
};

Box3 worldBox(const PlantObject& o) {
  Box3 b;
  for (const Vec3& p : o.geometry->positions()) {
    const Vec3 w = test::apply(o.node->matrix(), p);  // top-level: the node's matrix is its world matrix
    b.lo = glm::min(b.lo, w);
    b.hi = glm::max(b.hi, w);
  }
  return b;
}

TEST(BuiltinScenes, PlantMeetsItsTriangleBudgetWithManyNamedObjects) {
  std::size_t previousObjects = 0;
  for (std::uint64_t budget : {20'000u, 200'000u, 2'000'000u}) {
    SCOPED_TRACE(budget);
    Scene scene;
    const ImportResult r = importScene(scene, "builtin:plant:" + std::to_string(budget));
    const SceneStats s = computeSceneStats(scene, r.root);
    EXPECT_NEAR(static_cast<double>(s.triangles), static_cast<double>(budget), 0.1 * static_cast<double>(budget));
    EXPECT_EQ(s.triangles, s.uniqueTriangles);  // CAD-like: no instancing

    const std::vector<PlantObject> objects = plantObjects(scene, r.root);
    EXPECT_GT(objects.size(), previousObjects);
    previousObjects = objects.size();
    std::set<std::string> names;
    for (const PlantObject& o : objects) {
      EXPECT_FALSE(o.node->name().empty());
      EXPECT_TRUE(names.insert(o.node->name()).second) << "duplicate name " << o.node->name();
    }
    for (const char* kind : {"tank-1", "pipe-1-1", "housing-1", "pump-1 (in housing-1)", "slab-1"})
      EXPECT_TRUE(names.contains(kind)) << kind;
    EXPECT_GE(scene.count(ContainerType::SurfaceMaterial), 8u);
    EXPECT_EQ(r.cameras.size(), 1u);
    EXPECT_EQ(s.lights, 1u);
  }
  EXPECT_GT(previousObjects, 2000u);  // thousands of objects at 2 M triangles
}

TEST(BuiltinScenes, PlantIsTheSameSceneEveryTime) {
  Scene a, b;
  importScene(a, "builtin:plant:50000");
  importScene(b, "builtin:plant:50000");
  a.commit();
  b.commit();
  EXPECT_EQ(a.contentHash(), b.contentHash());
  Scene c;
  importScene(c, "builtin:plant:60000");
  c.commit();
  EXPECT_NE(a.contentHash(), c.contentHash());
}

TEST(BuiltinScenes, PlantHidesObjectsInsideOthers) {
  Scene scene;
  const ImportResult r = importScene(scene, "builtin:plant:100000");
  const std::vector<PlantObject> objects = plantObjects(scene, r.root);
  std::map<std::string, Box3> boxes;
  for (const PlantObject& o : objects) boxes[o.node->name()] = worldBox(o);
  std::size_t enclosed = 0;
  std::set<std::string> kinds;
  for (const auto& [name, box] : boxes) {
    const std::size_t in = name.find(" (in ");
    if (in == std::string::npos) continue;
    const std::string outer = name.substr(in + 5, name.size() - in - 6);
    ASSERT_TRUE(boxes.contains(outer)) << name;
    EXPECT_TRUE(boxes[outer].contains(box, 1e-3f)) << name << " sticks out of " << outer;
    kinds.insert(name.substr(0, name.find('-')));
    ++enclosed;
  }
  EXPECT_GT(enclosed, 20u);
  for (const char* kind : {"pump", "motor", "baseplate", "agitator", "impeller", "terminal"})
    EXPECT_TRUE(kinds.contains(kind)) << kind;

  // Sizes differ by orders of magnitude: a slab against a terminal block.
  auto extent = [&](const std::string& name) { return glm::length(boxes.at(name).hi - boxes.at(name).lo); };
  EXPECT_GT(extent("slab-1") / extent("terminal-block-1 (in junction-box-1)"), 30.0f);
}

TEST(BuiltinScenes, PlantCameraStandsInsideLookingAlongTheAisle) {
  Scene scene;
  const ImportResult r = importScene(scene, "builtin:plant:200000");
  const SceneStats s = computeSceneStats(scene, r.root);
  const Mat4 pose = tsr::sg::cameraWorldPose(*scene.find<Camera>(r.cameras.at(0)));
  const Vec3 eye(pose[3]), forward = -Vec3(pose[2]);
  EXPECT_TRUE(glm::all(glm::greaterThan(eye, s.boundsMin)) && glm::all(glm::lessThan(eye, s.boundsMax)));
  EXPECT_GT(forward.z, 0.95f);
  // Many objects lie ahead of the camera, at very different distances.
  std::size_t ahead = 0;
  for (const PlantObject& o : plantObjects(scene, r.root))
    if (glm::dot(Vec3(o.node->matrix()[3]) - eye, forward) > 0.0f) ++ahead;
  EXPECT_GT(ahead, 100u);
}

TEST(BuiltinScenes, PlantMeshesAreValidAndFaceOutwards) {
  Scene scene;
  const ImportResult r = importScene(scene, "builtin:plant:20000");
  for (const PlantObject& o : plantObjects(scene, r.root)) {
    const Geometry& g = *o.geometry;
    ASSERT_FALSE(g.invalidReason()) << o.node->name() << ": " << *g.invalidReason();
    ASSERT_EQ(g.normals().size(), g.positions().size());
    const auto& p = g.positions();
    const auto& n = g.normals();
    const auto& idx = g.indices();
    for (std::size_t t = 0; t + 2 < idx.size(); t += 3) {
      const Vec3 face = glm::cross(p[idx[t + 1]] - p[idx[t]], p[idx[t + 2]] - p[idx[t]]);
      const Vec3 normal = n[idx[t]] + n[idx[t + 1]] + n[idx[t + 2]];
      ASSERT_GT(glm::dot(face, normal), 0.0f) << o.node->name() << " triangle " << t / 3 << " faces inwards";
    }
  }
}

TEST(BuiltinScenes, PlantBudgetOutOfRangeIsAnImportError) {
  Scene scene;
  for (const char* source : {"builtin:plant:999", "builtin:plant:1000000001", "builtin:plant:0",
                             "builtin:plant:", "builtin:plant:2M", "builtin:plant:-5000"}) {
    try {
      importScene(scene, source);
      ADD_FAILURE() << source << " was accepted";
    } catch (const ImportError& e) {
      EXPECT_THAT(e.what(), HasSubstr(source));
      EXPECT_THAT(e.what(), HasSubstr("triangle budget must be a whole number from 1000 to 1000000000"));
    }
  }
  EXPECT_EQ(scene.count(ContainerType::Transform), 0u);
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
    EXPECT_THAT(e.what(), HasSubstr("builtin:plant:TRIANGLES"));
  }
  EXPECT_EQ(scene.contentHash(), hash);
  EXPECT_FALSE(scene.hasPendingChanges());
}

// With --import-cache a built-in scene's conversion is kept under its name
// (import_scene.cpp), so what a name makes may change only with the
// importer version, which every cache entry carries: else a cache would
// hand out the scene the generator made before.
TEST(BuiltinScenes, ImporterVersionPinsWhatTheyMake) {
  std::vector<std::uint8_t> made;
  // The plant at a million triangles: its parts have 24 segments, above the
  // floors that smaller budgets sit at.
  for (const parsed::Scene& s : {builtin::cornell(), builtin::cornellFog(), builtin::animated(), builtin::instances(50),
                                 builtin::plant(20'000), builtin::plant(1'000'000)}) {
    const std::vector<std::uint8_t> bytes = parsed::encodeScene(s);
    made.insert(made.end(), bytes.begin(), bytes.end());
  }
  const std::string digest = cache::key(made, ImportOptions{}).substr(0, 32);
  constexpr std::uint32_t kPinnedVersion = 7;
  const std::string pinned = "2eb177d622919d2ad64e3407a1f5206e";
  EXPECT_EQ(cache::kImporterVersion, kPinnedVersion) << "the importer version changed: pin its built-in scenes' digest";
  EXPECT_EQ(digest, pinned) << "a built-in scene changed: raise cache::kImporterVersion, then pin the new version and "
                               "digest here";
}

}  // namespace
}  // namespace tsr::sg
