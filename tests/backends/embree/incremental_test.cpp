#include "test_scenes.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

namespace tsr::embree::test {
namespace {

// The scene's edits are described by a state; a scene can be built
// directly in a state or reach it by edits, and both must render the same.
struct State {
  glm::vec3 ballOffset{0.0f};
  glm::vec3 boxColour{0.2f, 0.7f, 0.3f};
  float waveHeight = 0.0f;  // vertices of the animated sheet
  bool withExtraBall = false;
  bool withBox = true;
  float lampEmission = 6.0f;
};

MeshData sheet(float wave) {
  MeshData m;
  const int n = 8;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      float x = -2.0f + 4.0f * float(i) / n, z = -2.0f + 4.0f * float(j) / n;
      m.positions.push_back({x, wave * std::sin(2.0f * x) * std::cos(1.5f * z), z});
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      m.indices.insert(m.indices.end(), {a, c, d, a, d, b});
    }
  m.usage = MeshUsage::Animated;
  return m;
}

struct Built {
  MeshId sheet, ball;
  MaterialId boxMaterial, ballMaterial, lampMaterial;
  InstanceId ball1, box, extra;
};

Built build(Scene& scene, const State& s) {
  Built b;
  Material floor;
  floor.baseColor = glm::vec3(0.7f);
  b.sheet = scene.addMesh(sheet(s.waveHeight));
  scene.addInstance(b.sheet, scene.addMaterial(floor), glm::mat4(1.0f));
  Material ball;
  ball.type = MaterialType::Dielectric;
  ball.roughness = 0.2f;
  b.ballMaterial = scene.addMaterial(ball);
  b.ball = scene.addMesh(uvSphere({0, 0, 0}, 0.5f, 600, true));
  b.ball1 = scene.addInstance(b.ball, b.ballMaterial, glm::translate(glm::mat4(1.0f), glm::vec3(-0.6f, 0.6f, 0) + s.ballOffset));
  Material box;
  box.baseColor = s.boxColour;
  b.boxMaterial = scene.addMaterial(box);
  if (s.withBox) {
    b.box = scene.addInstance(scene.addMesh(uvSphere({0.8f, 0.4f, 0.3f}, 0.4f, 100, false)), b.boxMaterial, glm::mat4(1.0f));
  }
  Material lamp;
  lamp.emission = glm::vec3(s.lampEmission);
  lamp.baseColor = glm::vec3(0.0f);
  b.lampMaterial = scene.addMaterial(lamp);
  scene.addInstance(scene.addMesh(quad({-0.5f, 2.5f, -0.5f}, {0.5f, 2.5f, -0.5f}, {0.5f, 2.5f, 0.5f}, {-0.5f, 2.5f, 0.5f})),
                    b.lampMaterial, glm::mat4(1.0f));
  if (s.withExtraBall) {
    b.extra = scene.addInstance(b.ball, b.boxMaterial, glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.5f, -1.0f)));
  }
  scene.setEnvironment(Environment::constant(glm::vec3(0.2f)));
  return b;
}

const Camera kCamera = Camera::lookAt({0, 3, 4}, {0, 0, 0}, {0, 1, 0}, glm::radians(50.0f), 1.0f);

void renderInto(Scene& scene, FrameBuffer& fb) {
  RenderSettings s;
  s.seed = 11;
  s.maxDepth = 5;
  Renderer renderer(s);
  render(renderer, scene, kCamera, Region::full(fb.width(), fb.height()), fb, 2);
}

void expectEditEqualsFresh(const State& edited, const std::function<void(Scene&, const Built&)>& edit,
                           const State& start = State{}) {
  Scene scene(sharedDevice());
  Built b = build(scene, start);
  FrameBuffer before(32, 32);
  renderInto(scene, before);  // commits the unedited state first
  std::uint64_t v = scene.version();
  edit(scene, b);
  EXPECT_GT(scene.version(), v);
  FrameBuffer afterEdit(32, 32);
  renderInto(scene, afterEdit);

  Scene fresh(sharedDevice());
  build(fresh, edited);
  FrameBuffer direct(32, 32);
  renderInto(fresh, direct);
  EXPECT_TRUE(identical(afterEdit, direct));
  EXPECT_FALSE(identical(before, direct)) << "the edit must be visible";
}

TEST(EmbreeIncremental, InstanceTransform) {
  State s;
  s.ballOffset = {0.3f, 0.2f, 0.1f};
  expectEditEqualsFresh(s, [&](Scene& scene, const Built& b) {
    scene.setInstanceTransform(b.ball1, glm::translate(glm::mat4(1.0f), glm::vec3(-0.6f, 0.6f, 0) + s.ballOffset));
  });
}

// A shared mesh is instanced: its moved instance leaves the top level for
// the moving level, and moves again there; a fresh scene keeps it in the top.
TEST(EmbreeIncremental, SharedInstanceMovesTwice) {
  State start;
  start.withExtraBall = true;
  State s = start;
  s.ballOffset = {0.3f, 0.2f, 0.1f};
  expectEditEqualsFresh(
      s,
      [&](Scene& scene, const Built& b) {
        const glm::vec3 at = glm::vec3(-0.6f, 0.6f, 0);
        scene.setInstanceTransform(b.ball1, glm::translate(glm::mat4(1.0f), at - s.ballOffset));
        FrameBuffer between(8, 8);
        renderInto(scene, between);  // commits the first move
        scene.setInstanceTransform(b.ball1, glm::translate(glm::mat4(1.0f), at + s.ballOffset));
      },
      start);
}

// The moved instance goes when its second user goes: from the moving level to the merged scene.
TEST(EmbreeIncremental, MovedInstanceOutlivesTheOtherUser) {
  State start;
  start.withExtraBall = true;
  State s;
  s.ballOffset = {0.3f, 0.2f, 0.1f};
  expectEditEqualsFresh(
      s,
      [&](Scene& scene, const Built& b) {
        scene.setInstanceTransform(b.ball1, glm::translate(glm::mat4(1.0f), glm::vec3(-0.6f, 0.6f, 0) + s.ballOffset));
        FrameBuffer between(8, 8);
        renderInto(scene, between);
        scene.removeInstance(b.extra);
      },
      start);
}

// Three instances of an animated mesh stay instanced: when the first of two
// moved ones goes, the other takes its id in the moving level.
TEST(EmbreeIncremental, MovingLevelKeepsTheOthersWhenOneGoes) {
  auto at = [](float x) { return glm::translate(glm::mat4(1.0f), glm::vec3(x, 0.5f, 0)); };
  auto build3 = [&](Scene& scene, bool withFirst, float secondX) {
    MeshData ball = uvSphere({0, 0, 0}, 0.4f, 100, true);
    ball.usage = MeshUsage::Animated;
    const MeshId mesh = scene.addMesh(ball);
    Material grey;
    grey.baseColor = glm::vec3(0.6f);
    const MaterialId m = scene.addMaterial(grey);
    std::vector<InstanceId> ids;
    if (withFirst) ids.push_back(scene.addInstance(mesh, m, at(-1.0f)));
    ids.push_back(scene.addInstance(mesh, m, at(secondX)));
    scene.addInstance(mesh, m, at(1.0f));
    scene.setEnvironment(Environment::constant(glm::vec3(0.5f)));
    return ids;
  };
  Scene scene(sharedDevice());
  auto ids = build3(scene, true, 0.0f);
  FrameBuffer frame(32, 32);
  renderInto(scene, frame);
  scene.setInstanceTransform(ids[0], at(-1.2f));
  scene.setInstanceTransform(ids[1], at(0.2f));
  renderInto(scene, frame);
  scene.removeInstance(ids[0]);
  FrameBuffer afterEdit(32, 32);
  renderInto(scene, afterEdit);

  Scene fresh(sharedDevice());
  build3(fresh, false, 0.2f);
  FrameBuffer direct(32, 32);
  renderInto(fresh, direct);
  EXPECT_TRUE(identical(afterEdit, direct));
}

TEST(EmbreeIncremental, Material) {
  State s;
  s.boxColour = {0.9f, 0.1f, 0.1f};
  expectEditEqualsFresh(s, [&](Scene& scene, const Built& b) {
    Material m;
    m.baseColor = s.boxColour;
    scene.setMaterial(b.boxMaterial, m);
  });
}

// Emission feeds the emitter distribution, which a material edit must refresh.
TEST(EmbreeIncremental, EmissiveMaterial) {
  State s;
  s.lampEmission = 2.0f;
  expectEditEqualsFresh(s, [&](Scene& scene, const Built& b) {
    Material m;
    m.emission = glm::vec3(s.lampEmission);
    m.baseColor = glm::vec3(0.0f);
    scene.setMaterial(b.lampMaterial, m);
  });
}

TEST(EmbreeIncremental, VertexRangeRefit) {
  State s;
  s.waveHeight = 0.3f;
  expectEditEqualsFresh(s, [&](Scene& scene, const Built& b) {
    MeshData target = sheet(s.waveHeight);
    // Two ranges, to exercise partial updates.
    std::span<const glm::vec3> all(target.positions);
    scene.updateMeshVertices(b.sheet, 0, all.first(40));
    scene.updateMeshVertices(b.sheet, 40, all.subspan(40));
  });
}

TEST(EmbreeIncremental, AddInstance) {
  State s;
  s.withExtraBall = true;
  expectEditEqualsFresh(s, [&](Scene& scene, const Built& b) {
    scene.addInstance(b.ball, b.boxMaterial, glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.5f, -1.0f)));
  });
}

TEST(EmbreeIncremental, RemoveInstance) {
  State s;
  s.withBox = false;
  expectEditEqualsFresh(s, [&](Scene& scene, const Built& b) { scene.removeInstance(b.box); });
}

}  // namespace
}  // namespace tsr::embree::test
