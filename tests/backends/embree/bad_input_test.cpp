#include "test_scenes.hpp"

#include "tsr/embree/error.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

namespace tsr::embree::test {
namespace {

using ::testing::HasSubstr;

template <class F>
std::string errorOf(F f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "<no exception>";
}

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

TEST(EmbreeBadInput, MeshData) {
  Scene scene(sharedDevice());
  MeshData m = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  m.indices.writable()[4] = 9;
  EXPECT_THAT(errorOf([&] { scene.addMesh(m); }), HasSubstr("index 4 = 9 is out of range"));
  m = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  m.indices = std::vector<std::uint32_t>(m.indices.begin(), m.indices.end() - 1);
  EXPECT_THAT(errorOf([&] { scene.addMesh(m); }), HasSubstr("not a positive multiple of 3"));
  m = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  m.positions.writable()[2].y = kNaN;
  EXPECT_THAT(errorOf([&] { scene.addMesh(m); }), HasSubstr("NaN"));
  m = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  m.normals = std::vector<glm::vec3>(2, glm::vec3(0, 0, 1));
  EXPECT_THAT(errorOf([&] { scene.addMesh(m); }), HasSubstr("2 normals for 4 positions"));
  EXPECT_EQ(scene.meshCount(), 0u);
}

TEST(EmbreeBadInput, IdsTransformsAndEdits) {
  Scene scene(sharedDevice());
  MeshId mesh = scene.addMesh(quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}));
  MaterialId mat = scene.addMaterial({});
  glm::mat4 bad(1.0f);
  bad[3][1] = kNaN;
  EXPECT_THAT(errorOf([&] { scene.addInstance(mesh, mat, bad); }), HasSubstr("NaN"));
  EXPECT_THAT(errorOf([&] { scene.addInstance(mesh, mat, glm::mat4(0.0f)); }), HasSubstr("affine"));
  EXPECT_THAT(errorOf([&] { scene.addInstance(MeshId(7), mat, glm::mat4(1.0f)); }), HasSubstr("unknown mesh id 7"));
  EXPECT_THAT(errorOf([&] { scene.addInstance(mesh, MaterialId(3), glm::mat4(1.0f)); }),
              HasSubstr("unknown material id 3"));
  InstanceId inst = scene.addInstance(mesh, mat, glm::mat4(1.0f));
  EXPECT_THAT(errorOf([&] { scene.setInstanceTransform(inst, bad); }), HasSubstr("NaN"));
  EXPECT_THAT(errorOf([&] { scene.removeMesh(mesh); }), HasSubstr("still used by 1 instance"));
  const std::vector<glm::vec3> v(4, glm::vec3(0.0f));
  EXPECT_THAT(errorOf([&] { scene.updateMeshVertices(mesh, {.positions = v, .first = 2, .count = 3}); }),
              HasSubstr("exceeds the mesh's 4 vertices"));
  EXPECT_THAT(errorOf([&] { scene.updateMeshVertices(mesh, {.positions = std::span(v).first(3), .count = 1}); }),
              HasSubstr("3 positions for a mesh of 4 vertices"));
  scene.removeInstance(inst);
  EXPECT_THAT(errorOf([&] { scene.removeInstance(inst); }), HasSubstr("unknown instance id"));
  scene.removeMesh(mesh);
  Material m;
  m.roughness = 2.0f;
  EXPECT_THAT(errorOf([&] { scene.addMaterial(m); }), HasSubstr("roughness"));
  m = {};
  m.baseColorTexture = TextureId(5);
  EXPECT_THAT(errorOf([&] { scene.addMaterial(m); }), HasSubstr("unknown texture id 5"));
  EXPECT_THAT(errorOf([&] {
                scene.addLight(SpotLight{{0, 0, 0}, {0, -1, 0}, glm::vec3(1), 0.5f, 0.2f});
              }),
              HasSubstr("inner <= outer"));
  EXPECT_THAT(errorOf([] { Texture(2, 2, std::vector<glm::vec4>(3)); }), HasSubstr("3 texels, expected 4"));
  EXPECT_THAT(errorOf([] { Environment::constant({-1, 0, 0}); }), HasSubstr("non-negative"));
}

TEST(EmbreeBadInput, ImagesCamerasAndSettings) {
  Scene scene(sharedDevice());
  Renderer renderer;
  Camera camera;
  EXPECT_THAT(errorOf([] { FrameBuffer(0, 4); }), HasSubstr("non-zero"));
  FrameBuffer fb(8, 8);
  EXPECT_THAT(errorOf([&] { renderer.renderPass(scene, camera, Region::full(0, 0), fb); }), HasSubstr("non-zero"));
  EXPECT_THAT(errorOf([&] {
                renderer.renderPass(scene, camera, Region{8, 8, 4, 0, 12, 8}, fb);
              }),
              HasSubstr("exceeds image 8x8"));
  EXPECT_THAT(errorOf([&] { renderer.renderPass(scene, camera, Region::full(16, 8), fb); }),
              HasSubstr("frame buffer is 8x8 but the region is 16x8"));
  Camera flat = camera;
  flat.left = flat.right;
  EXPECT_THAT(errorOf([&] { renderer.renderPass(scene, flat, Region::full(8, 8), fb); }), HasSubstr("window is empty"));
  Camera nan = camera;
  nan.cameraToWorld[0][0] = kNaN;
  EXPECT_THAT(errorOf([&] { renderer.renderPass(scene, nan, Region::full(8, 8), fb); }), HasSubstr("NaN"));
  RenderSettings s;
  s.tileSize = 0;
  EXPECT_THAT(errorOf([&] { renderer.setSettings(s); }), HasSubstr("tileSize"));
  EXPECT_TRUE(renderer.renderPass(scene, camera, Region::full(8, 8), fb).completed);  // still usable
}

// Found by mutating real files: a camera at z = -1e20 is finite, yet Embree
// aborted the process on its rays ("Assertion 'ray.valid()' failed").
TEST(EmbreeBadInput, CoordinatesBeyondWhatEmbreeTraces) {
  Scene scene(sharedDevice());
  Camera camera = cornellBox(scene, 0);
  Renderer renderer;
  FrameBuffer fb(8, 8);
  for (float eye : {-1e20f, -2.7e38f, 2e12f}) {
    Camera far = camera;
    far.cameraToWorld[3][2] = eye;
    EXPECT_THAT(errorOf([&] { renderer.renderPass(scene, far, Region::full(8, 8), fb); }),
                HasSubstr("the eye cannot be traced"))
        << eye;
  }
  Camera wide = camera;
  wide.right = 3e38f;
  wide.left = -3e38f;
  EXPECT_THAT(errorOf([&] { renderer.renderPass(scene, wide, Region::full(8, 8), fb); }), HasSubstr("beyond 1e12"));

  MeshId mesh = scene.addMesh(quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}));
  MeshData m = quad({0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0});
  m.positions.writable()[1].x = 5e12f;
  EXPECT_THAT(errorOf([&] { scene.addMesh(m); }), HasSubstr("beyond 1e12"));
  std::vector<glm::vec3> v(m.positions.begin(), m.positions.end());
  v[0] = glm::vec3(0, 0, -1e20f);
  EXPECT_THAT(errorOf([&] { scene.updateMeshVertices(mesh, {.positions = v, .count = 1}); }), HasSubstr("beyond 1e12"));
  glm::mat4 far(1.0f);
  far[3][0] = 1e20f;
  EXPECT_THAT(errorOf([&] { scene.addInstance(mesh, scene.addMaterial({}), far); }), HasSubstr("beyond 1e12"));

  // Rays that still cannot be traced (here: a frustum so small its ray
  // directions underflow to NaN) are dropped, never handed to Embree.
  Camera tiny = camera;
  tiny.near = tiny.right = tiny.top = 1e-30f;
  tiny.left = tiny.bottom = -1e-30f;
  PassResult r = renderer.renderPass(scene, tiny, Region::full(8, 8), fb);
  EXPECT_TRUE(r.completed);
  EXPECT_GT(r.refusedRays, 0u);
  EXPECT_TRUE(renderer.renderPass(scene, camera, Region::full(8, 8), fb).completed);  // still usable
}

}  // namespace
}  // namespace tsr::embree::test
