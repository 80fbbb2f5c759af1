#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "import_test_util.hpp"
#include "test_scenes.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/node_world.hpp"

namespace tsr::sg {
namespace {

using test::byName;
using test::worldOf;
using ::testing::HasSubstr;

constexpr float kEps = 1e-5f;

void expectNear(const Vec3& a, const Vec3& b, float eps = kEps) {
  EXPECT_NEAR(a.x, b.x, eps);
  EXPECT_NEAR(a.y, b.y, eps);
  EXPECT_NEAR(a.z, b.z, eps);
}

class RichScene : public ::testing::Test {
 protected:
  void SetUp() override {
    path = dir.file("rich.gltf");
    test::richScene(dir).writeGltf(path);
    result = importScene(scene, path);
  }
  test::TempDir dir;
  std::string path;
  Scene scene;
  ImportResult result;
};

TEST_F(RichScene, CreatesOneContainerPerThingItUses) {
  EXPECT_EQ(scene.count(ContainerType::Group), 1u);
  EXPECT_EQ(scene.count(ContainerType::Transform), 9u);
  // quad (shared), triangle, strip, fan, points, loose triangle.
  EXPECT_EQ(scene.count(ContainerType::Geometry), 6u);
  EXPECT_EQ(scene.count(ContainerType::SurfaceMaterial), 3u);  // two + glTF's default
  EXPECT_EQ(scene.count(ContainerType::Image), 2u);
  EXPECT_EQ(scene.count(ContainerType::Light), 3u);
  EXPECT_EQ(scene.count(ContainerType::Camera), 1u);
  EXPECT_EQ(scene.count(ContainerType::Background), 1u);
  EXPECT_EQ(result.counts.nodes, 9u);
  EXPECT_EQ(result.counts.skippedPrimitives, 0u);
  EXPECT_EQ(result.cameras.size(), 1u);
  EXPECT_EQ(result.lights.size(), 3u);
  ASSERT_NE(scene.find<Group>(result.root), nullptr);
  EXPECT_EQ(scene.find<Group>(result.root)->children().size(), 6u);
  EXPECT_NE(scene.find<Background>(result.background), nullptr);
}

TEST_F(RichScene, SharedMeshesShareGeometry) {
  auto* a = byName<Transform>(scene, "childA");
  auto* b = byName<Transform>(scene, "childB");
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->children().size(), 1u);
  EXPECT_EQ(a->children(), b->children());
  const SceneStats stats = computeSceneStats(scene, result.root);
  EXPECT_EQ(stats.geometryInstances, 7u);
  EXPECT_EQ(stats.uniqueTriangles, 2u + 1u + 3u + 3u + 1u);  // the points are no triangles
  EXPECT_EQ(stats.triangles, stats.uniqueTriangles + 2u);
}

TEST_F(RichScene, WorldPositionsFollowTheHierarchy) {
  auto* a = byName<Transform>(scene, "childA");
  auto* b = byName<Transform>(scene, "childB");
  auto* m = byName<Transform>(scene, "matrix");
  ASSERT_TRUE(a && b && m);
  const Geometry* quad = scene.find<Geometry>(a->children()[0]);
  ASSERT_NE(quad, nullptr);
  ASSERT_EQ(quad->positions().size(), 4u);
  const Vec3 corner = quad->positions()[2];  // (1, 1, 0)
  expectNear(corner, Vec3(1, 1, 0));
  expectNear(test::apply(*worldOf(scene, result.root, a->id()), corner), Vec3(11, 6, 0));
  expectNear(test::apply(*worldOf(scene, result.root, b->id()), corner), Vec3(12, 2, 0));
  // The matrix node turns +x into +y and moves down z.
  expectNear(test::apply(*worldOf(scene, result.root, m->id()), Vec3(1, 0, 0)), Vec3(0, 1, -3));

  const SceneStats stats = computeSceneStats(scene, result.root);
  ASSERT_TRUE(stats.hasBounds);
  expectNear(stats.boundsMin, Vec3(-1, 0, -3));
  expectNear(stats.boundsMax, Vec3(12, 6, 5));
}

TEST_F(RichScene, ReadsAttributesOfEveryLayout) {
  auto* a = byName<Transform>(scene, "childA");
  const Geometry* quad = scene.find<Geometry>(a->children()[0]);
  EXPECT_EQ(quad->indices(), (std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3}));
  ASSERT_EQ(quad->uvs().size(), 4u);
  EXPECT_EQ(quad->uvs()[1], Vec2(1, 1));  // from the interleaved view
  EXPECT_TRUE(quad->normals().empty());   // none in the file: shaded flat
  EXPECT_FALSE(quad->invalidReason());

  auto* m = byName<Transform>(scene, "matrix");
  const Geometry* tri = scene.find<Geometry>(m->children()[0]);
  ASSERT_EQ(tri->colors().size(), 3u);
  EXPECT_NEAR(tri->colors()[2].w, 0.2f, kEps);  // 51 / 255
  EXPECT_EQ(tri->colors()[0], Vec4(1, 0, 0, 1));
  ASSERT_EQ(tri->uvs().size(), 3u);
  EXPECT_EQ(tri->uvs()[1], Vec2(1, 0));  // 65535 normalized

  auto* s = byName<Transform>(scene, "strips");
  ASSERT_EQ(s->children().size(), 4u);
  const Geometry* strip = scene.find<Geometry>(s->children()[0]);
  const Geometry* fan = scene.find<Geometry>(s->children()[1]);
  const Geometry* points = scene.find<Geometry>(s->children()[2]);
  const Geometry* loose = scene.find<Geometry>(s->children()[3]);
  // Strips alternate winding so every triangle keeps the first one's.
  EXPECT_EQ(strip->indices(), (std::vector<std::uint32_t>{0, 1, 2, 2, 1, 3, 2, 3, 4}));
  EXPECT_EQ(fan->indices(), (std::vector<std::uint32_t>{0, 1, 3, 0, 3, 4, 0, 4, 2}));
  // Points without indices: every vertex once, no normals made for them.
  EXPECT_EQ(points->primitive(), GeometryPrimitive::Points);
  EXPECT_EQ(points->indices(), (std::vector<std::uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(points->primitiveCount(), 5u);
  EXPECT_EQ(points->triangleCount(), 0u);
  EXPECT_TRUE(points->normals().empty());
  EXPECT_EQ(strip->primitive(), GeometryPrimitive::Triangles);
  EXPECT_EQ(loose->indices(), (std::vector<std::uint32_t>{0, 1, 2}));
  ASSERT_EQ(loose->colors().size(), 3u);
  EXPECT_EQ(loose->colors()[1], Vec4(0, 1, 0, 1));
  // No material: glTF's default, white, metallic and rough.
  const auto* def = scene.find<SurfaceMaterial>(loose->material());
  ASSERT_NE(def, nullptr);
  EXPECT_EQ(def->baseColor(), Vec3(1));
  EXPECT_EQ(def->metallic(), 1.0f);
}

TEST_F(RichScene, MaterialsCarryFactorsExtensionsAndTextures) {
  const auto* fancy = byName<SurfaceMaterial>(scene, "fancy");
  const auto* plain = byName<SurfaceMaterial>(scene, "plain");
  ASSERT_TRUE(fancy && plain);
  expectNear(fancy->baseColor(), Vec3(0.5f, 0.25f, 1.0f));
  EXPECT_FLOAT_EQ(fancy->opacity(), 0.5f);
  EXPECT_FLOAT_EQ(fancy->metallic(), 0.3f);
  EXPECT_FLOAT_EQ(fancy->roughness(), 0.7f);
  expectNear(fancy->emission(), Vec3(1.0f, 0.5f, 0.0f));
  EXPECT_FLOAT_EQ(fancy->emissionStrength(), 4.0f);
  EXPECT_FLOAT_EQ(fancy->transmission(), 0.8f);
  EXPECT_FLOAT_EQ(fancy->ior(), 1.33f);
  EXPECT_FLOAT_EQ(fancy->normalScale(), 0.5f);
  EXPECT_FLOAT_EQ(plain->metallic(), 1.0f);
  EXPECT_FLOAT_EQ(plain->opacity(), 1.0f);

  // Images are shared between materials by index.
  EXPECT_EQ(fancy->baseColorTexture(), plain->emissionTexture());
  EXPECT_EQ(fancy->normalTexture(), plain->metallicRoughnessTexture());
  const Image* file = scene.find<Image>(fancy->baseColorTexture());
  const Image* uri = scene.find<Image>(fancy->normalTexture());
  ASSERT_TRUE(file && uri);
  EXPECT_EQ(file->width(), 2u);
  EXPECT_EQ(file->height(), 2u);
  EXPECT_EQ(file->channels(), 4u);
  EXPECT_EQ(file->pixels(), test::kFilePixels);
  EXPECT_EQ(file->colorSpace(), ColorSpace::SRGB);
  EXPECT_EQ(file->uri(), "tex.png");
  EXPECT_EQ(uri->width(), 2u);
  EXPECT_EQ(uri->height(), 1u);
  EXPECT_EQ(uri->channels(), 3u);
  EXPECT_EQ(uri->pixels(), test::kUriPixels);
  EXPECT_EQ(uri->colorSpace(), ColorSpace::Linear);  // normal and metallic-roughness data
}

TEST_F(RichScene, LightsAndCamerasHangUnderTheirNodes) {
  const Light* point = nullptr;
  const Light* spot = nullptr;
  const Light* sun = nullptr;
  for (ContainerId id : result.lights) {
    const Light* l = scene.find<Light>(id);
    ASSERT_NE(l, nullptr);
    (l->kind() == LightKind::Point ? point : l->kind() == LightKind::Spot ? spot : sun) = l;
  }
  ASSERT_TRUE(point && spot && sun);
  expectNear(point->color(), Vec3(1.0f, 0.5f, 0.25f));
  EXPECT_FLOAT_EQ(point->intensity(), 20.0f);
  EXPECT_FLOAT_EQ(spot->innerConeAngle(), 0.2f);
  EXPECT_FLOAT_EQ(spot->outerConeAngle(), 0.6f);
  EXPECT_EQ(sun->kind(), LightKind::Directional);
  EXPECT_FLOAT_EQ(sun->intensity(), 3.0f);
  auto* pointNode = byName<Transform>(scene, "point");
  ASSERT_NE(pointNode, nullptr);
  EXPECT_EQ(pointNode->children(), std::vector<ContainerId>{point->id()});
  expectNear(test::apply(*worldOf(scene, result.root, point->id()), Vec3(0)), Vec3(0, 3, 0));

  const Camera* cam = scene.find<Camera>(result.cameras[0]);
  ASSERT_NE(cam, nullptr);
  expectNear(Vec3(tsr::sg::cameraWorldPose(*cam)[3]), Vec3(10, 0, 10));
  EXPECT_FLOAT_EQ(cam->verticalFov(), 0.8f);
  EXPECT_FLOAT_EQ(cam->nearPlane(), 0.5f);
  EXPECT_FLOAT_EQ(cam->farPlane(), 200.0f);
}

// glTF describes a pinhole; Tessera's TSR_camera_lens adds a thin lens
// (docs/camera.md). A camera without it stays a pinhole.
TEST(GltfImport, TesseraCameraLensExtension) {
  test::TempDir dir;
  test::GltfBuilder b = test::tinyScene();
  b.doc["extensionsUsed"] = {"TSR_camera_lens"};
  b.doc["cameras"] = {{{"type", "perspective"},
                       {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}},
                       {"extensions", {{"TSR_camera_lens", {{"apertureRadius", 0.05}, {"focusDistance", 3.5}}}}}},
                      {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  b.doc["nodes"].push_back({{"camera", 0}});
  b.doc["nodes"].push_back({{"camera", 1}});
  b.doc["scenes"][0]["nodes"].push_back(1);
  b.doc["scenes"][0]["nodes"].push_back(2);
  b.writeGltf(dir.file("lens.gltf"));
  Scene scene;
  const ImportResult result = importScene(scene, dir.file("lens.gltf"));
  ASSERT_EQ(result.cameras.size(), 2u);
  const Camera* lens = scene.find<Camera>(result.cameras[0]);
  const Camera* pinhole = scene.find<Camera>(result.cameras[1]);
  EXPECT_FLOAT_EQ(lens->apertureRadius(), 0.05f);
  EXPECT_FLOAT_EQ(lens->focusDistance(), 3.5f);
  EXPECT_EQ(pinhole->apertureRadius(), 0.0f);

  b.doc["cameras"][0]["extensions"]["TSR_camera_lens"]["apertureRadius"] = -1.0;
  b.writeGltf(dir.file("bad-lens.gltf"));
  Scene refused;
  try {
    importScene(refused, dir.file("bad-lens.gltf"));
    ADD_FAILURE() << "a negative aperture was accepted";
  } catch (const ImportError& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("camera 0 TSR_camera_lens needs apertureRadius >= 0"));
  }
}

TEST(GltfImport, GlbAndDataUriLoadLikeTheGltf) {
  test::TempDir dir;
  test::GltfBuilder b = test::richScene(dir);
  b.writeGltf(dir.file("a.gltf"));
  b.writeGltf(dir.file("b.gltf"), true);
  b.writeGlb(dir.file("c.glb"));
  Scene a, bs, c;
  importScene(a, dir.file("a.gltf"));
  importScene(bs, dir.file("b.gltf"));
  importScene(c, dir.file("c.glb"));
  EXPECT_EQ(a.size(), c.size());
  EXPECT_EQ(a.contentHash(), bs.contentHash());
  EXPECT_EQ(a.contentHash(), c.contentHash());
}

TEST(GltfImport, ImagesInBufferViewsDecodeFromMemory) {
  test::TempDir dir;
  test::GltfBuilder b = test::tinyScene();
  test::writePng(dir.file("p.png"), 2, 2, 4, test::kFilePixels);
  const std::vector<std::uint8_t> png = test::readBytes(dir.file("p.png"));
  const int view = b.addView(png);
  b.doc["images"] = {{{"bufferView", view}, {"mimeType", "image/png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  b.doc["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.writeGlb(dir.file("img.glb"));
  Scene scene;
  importScene(scene, dir.file("img.glb"));
  ASSERT_EQ(scene.count(ContainerType::Image), 1u);
  for (ContainerId id : scene.ids())
    if (const Image* img = scene.find<Image>(id)) {
      EXPECT_EQ(img->pixels(), test::kFilePixels);
    }
}

TEST(GltfImport, MissingNormalsStayFlatUnlessSmoothingIsAsked) {
  test::TempDir dir;
  test::GltfBuilder b;
  // Two triangles folded along x: smooth normals would blend them.
  const int pos = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3");
  const int idx = b.addIndices(std::vector<std::uint16_t>{0, 1, 2, 0, 3, 1});
  b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}}}};
  b.doc["nodes"] = {{{"mesh", 0}}};
  b.writeGltf(dir.file("fold.gltf"));
  Scene flat, smooth;
  const ImportResult rf = importScene(flat, dir.file("fold.gltf"));
  const ImportResult rs = importScene(smooth, dir.file("fold.gltf"), ImportOptions{.smoothNormals = true});
  auto geometry = [](const Scene& s) {
    for (ContainerId id : s.ids())
      if (const Geometry* g = s.find<Geometry>(id)) return g;
    return static_cast<const Geometry*>(nullptr);
  };
  const Geometry* gf = geometry(flat);
  const Geometry* gs = geometry(smooth);
  ASSERT_TRUE(gf && gs);
  // glTF: no normals means flat shading, which back-ends take from the
  // triangle itself; vertices stay shared.
  EXPECT_EQ(gf->positions().size(), 4u);
  EXPECT_TRUE(gf->normals().empty());
  ASSERT_EQ(gs->positions().size(), 4u);
  ASSERT_EQ(gs->normals().size(), 4u);
  expectNear(gs->normals()[0], glm::normalize(Vec3(0, 1, 1)));
  expectNear(gs->normals()[2], Vec3(0, 0, 1));
  expectNear(gs->normals()[3], Vec3(0, 1, 0));
  EXPECT_EQ(rs.counts.uniqueTriangles, rf.counts.uniqueTriangles);
}

// glTF modes 1-3 become segment lists (a loop closed back to its start), a
// stray last index of a list is dropped with a warning; the conversion's
// cache gives the same primitives back.
TEST(GltfImport, LineStripsAndLoopsBecomeSegmentLists) {
  test::TempDir dir;
  test::GltfBuilder b;
  const int pos = b.addFloats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
  const int four = b.addIndices(std::vector<std::uint16_t>{0, 1, 2, 3});
  const int three = b.addIndices(std::vector<std::uint16_t>{0, 1, 2});
  auto prim = [&](int mode, int indices) {
    return nlohmann::json{{"attributes", {{"POSITION", pos}}}, {"indices", indices}, {"mode", mode}};
  };
  b.doc["meshes"] = {{{"name", "lines"}, {"primitives", {prim(3, four), prim(2, four), prim(1, three)}}}};
  b.doc["nodes"] = {{{"mesh", 0}, {"name", "drawing"}}};
  b.writeGlb(dir.file("lines.glb"));  // a .gltf naming a .bin is not cached
  const ImportOptions options{.smoothNormals = true, .cacheDir = dir.file("cache")};
  for (const char* pass : {"stored", "hit"}) {
    SCOPED_TRACE(pass);
    Scene scene;
    const ImportResult r = importScene(scene, dir.file("lines.glb"), options);
    EXPECT_EQ(r.cache, pass);
    const auto* node = byName<Transform>(scene, "drawing");
    ASSERT_TRUE(node);
    ASSERT_EQ(node->children().size(), 3u);
    const Geometry* strip = scene.find<Geometry>(node->children()[0]);
    const Geometry* loop = scene.find<Geometry>(node->children()[1]);
    const Geometry* list = scene.find<Geometry>(node->children()[2]);
    for (const Geometry* g : {strip, loop, list}) {
      EXPECT_EQ(g->primitive(), GeometryPrimitive::Lines);
      EXPECT_TRUE(g->normals().empty());  // smoothing is for surfaces
      EXPECT_FALSE(g->invalidReason());
    }
    EXPECT_EQ(strip->indices(), (std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3}));
    EXPECT_EQ(loop->indices(), (std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3, 3, 0}));
    EXPECT_EQ(list->indices(), (std::vector<std::uint32_t>{0, 1}));
    EXPECT_EQ(loop->primitiveCount(), 4u);
    EXPECT_EQ(r.counts.uniqueTriangles, 0u);
    if (std::string(pass) == "stored") {
      EXPECT_THAT(r.warnings, ::testing::Contains(HasSubstr("3 indices is not a multiple of 2")));
    }
  }
}

// A geometry's index count must fit its primitive.
TEST(GeometryPrimitive, IndexCountsFollowThePrimitive) {
  Scene scene;
  Geometry& g = scene.create<Geometry>();
  g.setPositions({Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  g.setIndices({0, 1, 2});
  EXPECT_FALSE(g.invalidReason());
  EXPECT_EQ(g.triangleCount(), 1u);
  g.setPrimitive(GeometryPrimitive::Lines);
  ASSERT_TRUE(g.invalidReason());
  EXPECT_THAT(*g.invalidReason(), HasSubstr("not a multiple of 2"));
  EXPECT_EQ(g.triangleCount(), 0u);
  g.setIndices({0, 1, 1, 2});
  EXPECT_FALSE(g.invalidReason());
  EXPECT_EQ(g.primitiveCount(), 2u);
  g.setPrimitive(GeometryPrimitive::Points);
  EXPECT_FALSE(g.invalidReason());
  EXPECT_EQ(g.primitiveCount(), 4u);
}

}  // namespace
}  // namespace tsr::sg
