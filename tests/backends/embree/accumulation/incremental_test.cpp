#include "test_scenes.hpp"

#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

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
  float ballRadius = 0.5f;  // the ball mesh, used once (merged) unless withExtraBall
  int ballTriangles = 600;
};

MeshData sheet(float wave) {
  std::vector<glm::vec3> positions;
  std::vector<std::uint32_t> indices;
  const int n = 8;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      float x = -2.0f + 4.0f * float(i) / n, z = -2.0f + 4.0f * float(j) / n;
      positions.emplace_back(x, wave * std::sin(2.0f * x) * std::cos(1.5f * z), z);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      std::uint32_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      indices.insert(indices.end(), {a, c, d, a, d, b});
    }
  // Held as a scene replica's arrays are: shared, never written by the back-end.
  MeshData m;
  const auto heldPositions = std::make_shared<const std::vector<glm::vec3>>(std::move(positions));
  const auto heldIndices = std::make_shared<const std::vector<std::uint32_t>>(std::move(indices));
  m.positions = backend::SharedElements<glm::vec3>(*heldPositions, heldPositions);
  m.indices = backend::SharedElements<std::uint32_t>(*heldIndices, heldIndices);
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
  b.ball = scene.addMesh(uvSphere({0, 0, 0}, s.ballRadius, s.ballTriangles, true));
  b.ball1 = scene.addInstance(b.ball, b.ballMaterial,
                              glm::translate(glm::mat4(1.0f), glm::vec3(-0.6f, 0.6f, 0) + s.ballOffset));
  Material box;
  box.baseColor = s.boxColour;
  b.boxMaterial = scene.addMaterial(box);
  if (s.withBox) {
    b.box = scene.addInstance(scene.addMesh(uvSphere({0.8f, 0.4f, 0.3f}, 0.4f, 100, false)), b.boxMaterial,
                              glm::mat4(1.0f));
  }
  Material lamp;
  lamp.emission = glm::vec3(s.lampEmission);
  lamp.baseColor = glm::vec3(0.0f);
  b.lampMaterial = scene.addMaterial(lamp);
  scene.addInstance(
      scene.addMesh(quad({-0.5f, 2.5f, -0.5f}, {0.5f, 2.5f, -0.5f}, {0.5f, 2.5f, 0.5f}, {-0.5f, 2.5f, 0.5f})),
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
    const auto n = std::uint32_t(target.positions.size());
    scene.updateMeshVertices(b.sheet, {.positions = target.positions, .count = 40});
    scene.updateMeshVertices(b.sheet, {.positions = target.positions, .first = 40, .count = n - 40});
  });
}

// The back-end holds a mesh's shared arrays without a copy; an edit copies
// them first and never writes into the giver's.
TEST(EmbreeIncremental, AVertexEditLeavesSharedArraysAlone) {
  Scene scene(sharedDevice());
  const MeshData flat = sheet(0.0f);
  ASSERT_TRUE(flat.positions.shared());
  const std::vector<glm::vec3> before(flat.positions.begin(), flat.positions.end());
  const MeshId id = scene.addMesh(flat);
  const MeshData wavy = sheet(0.3f);
  scene.updateMeshVertices(id, {.positions = wavy.positions, .count = std::uint32_t(wavy.positions.size())});
  EXPECT_TRUE(std::equal(before.begin(), before.end(), flat.positions.begin()));
}

// New data (another topology) for a mesh whose one instance is merged:
// its world-space copy shared the old indices and is made again; then the
// same with a second instance added after, which needs the mesh's own BVH.
TEST(EmbreeIncremental, NewDataForAMergedMesh) {
  State s;
  s.ballRadius = 0.35f;
  s.ballTriangles = 200;
  expectEditEqualsFresh(s, [&](Scene& scene, const Built& b) {
    scene.setMeshData(b.ball, uvSphere({0, 0, 0}, s.ballRadius, s.ballTriangles, true));
  });
  s.withExtraBall = true;
  expectEditEqualsFresh(s, [&](Scene& scene, const Built& b) {
    scene.setMeshData(b.ball, uvSphere({0, 0, 0}, s.ballRadius, s.ballTriangles, true));
    scene.addInstance(b.ball, b.boxMaterial, glm::translate(glm::mat4(1.0f), glm::vec3(0.5f, 0.5f, -1.0f)));
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

// A crowd of instances of two shared meshes, one animated, on a merged
// floor, edited many times: moves of many different instances (each leaves
// a ghost in the top level, and the ghosts fold back into it when they grow
// past the limit or when the top level rebuilds anyway), moves again of
// moved ones, vertex edits of the animated mesh (under ghosts, inside its
// bounds, and back out after a level rebuilt around it), a removal and an
// addition. After each round the render equals a scene built fresh
// in that state.
struct Crowd {
  std::vector<glm::vec3> at;  // per instance, in id order
  std::vector<bool> present;
  float blobScale = 1.0f;  // vertices of the animated mesh
};

Crowd crowd() {
  Crowd c;
  for (int i = 0; i < 100; ++i) c.at.emplace_back(-1.8f + 0.4f * float(i % 10), 0.15f, -1.8f + 0.4f * float(i / 10));
  c.present.assign(c.at.size(), true);
  return c;
}

MeshData blob(float scale) {
  MeshData m = uvSphere({0, 0, 0}, 0.12f, 80, true);
  for (auto& p : m.positions.writable()) p = glm::vec3(p.x * scale, p.y, p.z);
  m.usage = MeshUsage::Animated;
  return m;
}

struct CrowdIds {
  MeshId ball, blob;  // odd crowd indices are blobs
  MeshId mesh(std::size_t i) const { return i % 2 ? blob : ball; }
  MaterialId material;
  std::vector<InstanceId> instances;  // by crowd index
};

CrowdIds buildCrowd(Scene& scene, const Crowd& c) {
  CrowdIds ids;
  Material lamp;
  lamp.emission = glm::vec3(8.0f);
  lamp.baseColor = glm::vec3(0.0f);
  scene.addInstance(scene.addMesh(quad({-1, 3, -1}, {1, 3, -1}, {1, 3, 1}, {-1, 3, 1})), scene.addMaterial(lamp),
                    glm::mat4(1.0f));
  Material grey;
  grey.baseColor = glm::vec3(0.6f);
  scene.addInstance(scene.addMesh(quad({-3, 0, 3}, {3, 0, 3}, {3, 0, -3}, {-3, 0, -3})), scene.addMaterial(grey),
                    glm::mat4(1.0f));
  Material paint;
  paint.baseColor = glm::vec3(0.8f, 0.3f, 0.2f);
  ids.material = scene.addMaterial(paint);
  ids.ball = scene.addMesh(uvSphere({0, 0, 0}, 0.15f, 60, false));
  ids.blob = scene.addMesh(blob(c.blobScale));
  for (std::size_t i = 0; i < c.at.size(); ++i) {
    if (!c.present[i]) {
      ids.instances.emplace_back();
      continue;
    }
    ids.instances.push_back(scene.addInstance(ids.mesh(i), ids.material, glm::translate(glm::mat4(1.0f), c.at[i])));
  }
  scene.setEnvironment(Environment::constant(glm::vec3(0.1f)));
  return ids;
}

TEST(EmbreeIncremental, ManyMovesEqualAFreshScene) {
  const Camera camera = Camera::lookAt({0, 4, 3}, {0, 0, 0}, {0, 1, 0}, glm::radians(55.0f), 1.0f);
  auto renderCrowd = [&](Scene& scene, FrameBuffer& fb) {
    RenderSettings s;
    s.seed = 5;
    s.maxDepth = 4;
    Renderer renderer(s);
    render(renderer, scene, camera, Region::full(fb.width(), fb.height()), fb, 2);
  };
  Crowd state = crowd();
  Scene scene(sharedDevice());
  CrowdIds ids = buildCrowd(scene, state);
  FrameBuffer commits(4, 4);
  renderCrowd(scene, commits);
  auto move = [&](std::size_t i, glm::vec3 by) {
    state.at[i] += by;
    scene.setInstanceTransform(ids.instances[i], glm::translate(glm::mat4(1.0f), state.at[i]));
    renderCrowd(scene, commits);  // one commit per edit, as a viewer dragging objects does
  };
  auto expectFresh = [&](const char* round) {
    FrameBuffer edited(48, 48);
    renderCrowd(scene, edited);
    Scene fresh(sharedDevice());
    buildCrowd(fresh, state);
    FrameBuffer direct(48, 48);
    renderCrowd(fresh, direct);
    EXPECT_TRUE(identical(edited, direct)) << round;
  };

  for (std::size_t i = 0; i < 10; ++i) move(i, {0.1f, 0.0f, 0.15f});
  expectFresh("ten instances moved once: ghosts in the top level");
  for (std::size_t i = 10; i < 45; ++i) move(i, {-0.1f, 0.05f * float(i % 3), 0.1f});
  expectFresh("past the ghost limit: folded back into the top level");
  move(5, {0.0f, 0.3f, 0.0f});
  move(60, {0.2f, 0.0f, 0.0f});
  move(61, {0.0f, 0.0f, -0.2f});
  move(62, {-0.2f, 0.0f, 0.0f});
  move(60, {0.0f, 0.2f, 0.0f});
  expectFresh("moved again, in the moving level");
  state.blobScale = 1.6f;
  MeshData b = blob(state.blobScale);
  scene.updateMeshVertices(
      ids.blob, {.positions = b.positions,
                 .count = std::uint32_t(b.positions.size())});  // 61 is a ghost of the blob: it leaves the top level
  move(63, {0.1f, 0.0f, 0.1f});
  state.present[62] = false;  // a ghost goes
  scene.removeInstance(ids.instances[62]);
  expectFresh("a vertex edit under ghosts, a ghost removed");
  auto reshapeBlob = [&](float scale) {
    state.blobScale = scale;
    const MeshData reshaped = blob(scale);
    scene.updateMeshVertices(ids.blob,
                             {.positions = reshaped.positions, .count = std::uint32_t(reshaped.positions.size())});
    renderCrowd(scene, commits);
  };
  reshapeBlob(0.8f);  // inside the bounds its instances' levels hold: only the blob's own BVH rebuilds
  expectFresh("a vertex edit inside the mesh's bounds");
  move(64, {0.0f, 0.0f, 0.1f});  // the moving level, which holds the blobs, rebuilds around the smaller blob
  reshapeBlob(1.6f);             // so growing back must move them again
  expectFresh("a vertex edit back out of bounds a level rebuild shrank");
  move(70, {0.0f, 0.2f, 0.0f});
  move(72, {0.0f, 0.2f, 0.0f});
  for (glm::vec3 at : {glm::vec3(0.0f, 1.0f, 0.0f), glm::vec3(0.5f, 1.0f, 0.0f)}) {
    ids.instances.push_back(
        scene.addInstance(ids.mesh(state.at.size()), ids.material, glm::translate(glm::mat4(1.0f), at)));
    state.at.push_back(at);
    state.present.push_back(true);
  }
  expectFresh("an addition rebuilds the top level and folds the ghosts");
}

}  // namespace
}  // namespace tsr::embree::test
