// The Vulkan mediator through the real rasterizer: incremental sync gives
// the same pixels as converting the edited scene afresh, and each kind of
// edit costs only what it touches (no geometry upload for a moved object,
// only the edited range for a vertex edit).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "../viewport_rig.hpp"
#include "test_scenes.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "tsr/sg/import/importer.hpp"
#include "vulkan_viewport.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 64;

// The animated Cornell box: a point light and a cube, so material and
// geometry edits show under direct light.
struct Rig : test::ViewportRig {
  Rig() : ViewportRig("vulkan", med::registerVulkan, "builtin:animated", kSize) {}
};

struct Follower : test::Follower {
  med::vulkan_mediator::VulkanContext& context() {
    return const_cast<med::vulkan_mediator::VulkanContext&>(
        dynamic_cast<med::vulkan_mediator::VulkanViewport&>(*viewport).context());
  }
};

med::FrameBuffer fresh(const Rig& rig) { return test::freshRender(rig); }

sg::ContainerId cubeGeometry(const Rig& rig) {
  const auto* t =
      rig.source.find<sg::Transform>(test::findNamed(rig.source, sg::ContainerType::Transform, "moving cube"));
  for (auto child : t->children())
    if (rig.source.find<sg::Geometry>(child)) return child;
  return sg::kNoContainer;
}

class IncrementalSync : public ::testing::Test {
 protected:
  Rig rig;
  Follower follower;
  med::FrameBuffer before;
  std::uint64_t geometryBytes = 0, instanceBytes = 0;
  void SetUp() override {
    follower.replica.apply(rig.source.commit());
    ASSERT_EQ(follower.render(rig).update, med::SceneAdapter::Update::Converted);
    before = follower.image;
    geometryBytes = follower.context().adapter.scene().geometryBytesUploaded();
    instanceBytes = follower.context().adapter.scene().instanceBytesWritten();
  }
  // Publishes the edit, renders incrementally, compares with a fresh conversion.
  // The edit's image against a fresh conversion's: bitwise, or within
  // `tolerance` in every channel.
  void check(const char* what) {
    follower.replica.apply(rig.source.commit());
    auto stats = follower.render(rig);
    EXPECT_EQ(stats.update, med::SceneAdapter::Update::Synced) << what;
    const med::FrameBuffer reference = fresh(rig);
    test::keepImage(std::string("vulkan_incremental_") + what, follower.image);
    EXPECT_EQ(test::differingPixels(follower.image, reference), 0u)
        << what << ": pixels that differ from a fresh conversion";
    EXPECT_EQ(follower.image.depth, reference.depth) << what;
    EXPECT_GT(test::differingPixels(before, follower.image), 0u) << what << ": the edit is visible";
  }
  std::uint64_t geometryUploaded() const {
    return const_cast<Follower&>(follower).context().adapter.scene().geometryBytesUploaded() - geometryBytes;
  }
  std::uint64_t instanceWritten() const {
    return const_cast<Follower&>(follower).context().adapter.scene().instanceBytesWritten() - instanceBytes;
  }
};
}  // namespace

TEST_F(IncrementalSync, TransformEditRewritesOnlyTheInstancesBelow) {
  auto* t = rig.source.find<sg::Transform>(test::findNamed(rig.source, sg::ContainerType::Transform, "moving cube"));
  ASSERT_NE(t, nullptr);
  t->setMatrix(glm::translate(t->matrix(), glm::vec3(150, 60, 100)));
  const auto flattenings = follower.context().adapter.counters().flattenings;
  check("transform");
  EXPECT_EQ(geometryUploaded(), 0u) << "moving an object re-uploads no geometry";
  EXPECT_EQ(follower.context().adapter.counters().instanceTransforms, 1u) << "one instance below the transform";
  EXPECT_EQ(instanceWritten(), 176u) << "one instance record (model and normal matrices, the mesh's boxes)";
  EXPECT_EQ(follower.context().adapter.counters().flattenings, flattenings) << "no re-placement";
}

TEST_F(IncrementalSync, MaterialEdit) {
  auto* m =
      rig.source.find<sg::SurfaceMaterial>(test::findNamed(rig.source, sg::ContainerType::SurfaceMaterial, "white"));
  ASSERT_NE(m, nullptr);
  m->setBaseColor({0.1f, 0.2f, 0.9f});
  check("material");
  EXPECT_EQ(follower.context().adapter.counters().materialUpdates, 1u);
  EXPECT_EQ(geometryUploaded(), 0u);
  EXPECT_EQ(instanceWritten(), 0u);
}

TEST_F(IncrementalSync, AlphaModeEdits) {
  auto* m =
      rig.source.find<sg::SurfaceMaterial>(test::findNamed(rig.source, sg::ContainerType::SurfaceMaterial, "white"));
  ASSERT_NE(m, nullptr);
  m->setOpacity(0.3f);
  m->setAlphaMode(sg::AlphaMode::Blend);
  check("alpha-blend");
  before = follower.image;
  m->setAlphaMode(sg::AlphaMode::Mask);  // below the cut-off of 0.5: cut away
  check("alpha-mask");
  before = follower.image;
  m->setAlphaMode(sg::AlphaMode::Opaque);
  check("alpha-opaque");
}

// glTF's texture transform and occlusion reach the rasterizer through
// change lists: a two-colour texture shifted by half a repeat, an
// occlusion texture and its strength.
TEST_F(IncrementalSync, TextureTransformAndOcclusionEdits) {
  auto* m =
      rig.source.find<sg::SurfaceMaterial>(test::findNamed(rig.source, sg::ContainerType::SurfaceMaterial, "white"));
  ASSERT_NE(m, nullptr);
  auto& halves = rig.source.create<sg::Image>("halves");
  halves.setPixels(2, 1, 3, sg::PixelFormat::UInt8, {255, 40, 40, 40, 40, 255});
  m->setBaseColorTexture(halves.id());
  check("texture");
  before = follower.image;
  std::vector<sg::Vec3> rows;
  for (std::size_t slot = 0; slot < std::size_t(sg::TextureSlot::Count); ++slot) {
    const bool base = slot == std::size_t(sg::TextureSlot::BaseColor);
    rows.push_back(sg::Vec3(1, 0, base ? 0.5f : 0.0f));
    rows.push_back(sg::Vec3(0, 1, 0));
  }
  m->setUvTransforms(rows);
  check("uv-transform");
  before = follower.image;
  auto& dark = rig.source.create<sg::Image>("occlusion");
  dark.setPixels(1, 1, 1, sg::PixelFormat::UInt8, {32});
  dark.setColorSpace(sg::ColorSpace::Linear);
  m->setOcclusionTexture(dark.id());
  check("occlusion");
  before = follower.image;
  m->setOcclusionStrength(0.25f);
  check("occlusion-strength");
}

TEST_F(IncrementalSync, GeometryRangeEditUploadsOnlyTheRange) {
  auto* g = rig.source.find<sg::Geometry>(cubeGeometry(rig));
  ASSERT_NE(g, nullptr);
  ASSERT_GT(g->positions().size(), 8u);
  std::vector<sg::Vec3> moved(g->positions().begin() + 4, g->positions().begin() + 8);
  // Halfway to the cube's centre: inside the box its positions are fractions of.
  for (auto& p : moved) p *= 0.5f;
  g->updatePositions(4, moved);
  check("geometry_range");
  EXPECT_EQ(follower.context().adapter.counters().meshRangeUpdates, 1u);
  const std::uint64_t position = follower.context().adapter.scene().device().positionBytes();
  EXPECT_EQ(geometryUploaded(), 4u * position) << "four compact positions, nothing else";

  // Beyond the box: it grows, and every position is stored again as a fraction of the new one.
  const std::uint64_t inside = geometryUploaded();
  before = follower.image;
  for (auto& p : moved) p += sg::Vec3(0, 0, -40);
  g->updatePositions(4, moved);
  // Every position is stored again from the replica's exact ones in the
  // box a fresh conversion makes: the same image, bit for bit.
  check("geometry_range_beyond_the_box");
  EXPECT_EQ(follower.context().adapter.counters().meshRangeUpdates, 2u);
  EXPECT_EQ(geometryUploaded() - inside, g->positions().size() * position);
}

TEST_F(IncrementalSync, TopologyEditRebuildsThatMeshOnly) {
  auto* g = rig.source.find<sg::Geometry>(cubeGeometry(rig));
  ASSERT_NE(g, nullptr);
  std::vector<std::uint32_t> fewer(g->indices().begin() + 18, g->indices().end());  // three faces less
  g->setIndices(fewer);
  const auto builds = follower.context().adapter.counters().meshBuilds;
  check("topology");
  EXPECT_EQ(follower.context().adapter.counters().meshBuilds, builds + 1);
}

TEST_F(IncrementalSync, CreateAndDestroy) {
  auto& t = rig.source.create<sg::Transform>("extra");
  t.setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(250, 150, 100)));
  t.addChild(cubeGeometry(rig));
  rig.source.find<sg::Group>(rig.imported.root)->addChild(t.id());
  const auto meshes = follower.context().adapter.scene().meshCount();
  check("create");
  EXPECT_EQ(geometryUploaded(), 0u) << "a new instance of a mesh already there";
  EXPECT_EQ(follower.context().adapter.scene().meshCount(), meshes);
  before = follower.image;
  rig.source.destroy(t.id());
  check("destroy");
}

TEST_F(IncrementalSync, LightEdit) {
  auto* light = rig.source.find<sg::Light>(rig.imported.lights.front());
  ASSERT_NE(light, nullptr);
  light->setColor({0.2f, 1.0f, 0.2f});
  check("light");
}

// A volume attached to the glass sphere, then edited, and fog from the
// background: the incremental render equals a fresh conversion, the change
// shows, and a volume edit updates one material.
namespace {
sg::Geometry* glassGeometry(sg::Scene& scene) {
  for (sg::ContainerId id : scene.ids())
    if (auto* g = scene.find<sg::Geometry>(id))
      if (const auto* m = scene.find<sg::SurfaceMaterial>(g->material()); m && m->transmission() > 0.5f) return g;
  return nullptr;
}
}  // namespace

TEST_F(IncrementalSync, VolumeAttachedAndEdited) {
  sg::Geometry* glass = glassGeometry(rig.source);
  ASSERT_NE(glass, nullptr) << "builtin:animated has a glass sphere";
  auto& jelly = rig.source.create<sg::VolumeMaterial>("jelly");
  jelly.setAbsorption({0.002f, 0.02f, 0.02f});  // per millimetre: the sphere is about 140 wide
  jelly.setScattering(glm::vec3(0.01f));
  glass->setVolume(jelly.id());
  check("volume attached");
  before = follower.image;
  const auto updates = follower.context().adapter.counters().materialUpdates;
  jelly.setScattering(glm::vec3(0.03f));
  check("volume edited");
  EXPECT_EQ(follower.context().adapter.counters().materialUpdates, updates + 1);
  EXPECT_EQ(geometryUploaded(), 0u);
}

TEST_F(IncrementalSync, FogFillsTheSceneFromTheBackground) {
  auto& fog = rig.source.create<sg::VolumeMaterial>("fog");
  fog.setScattering(glm::vec3(0.001f));
  fog.setAbsorption(glm::vec3(0.0005f));
  rig.source.find<sg::Background>(rig.imported.background)->setMedium(fog.id());
  check("fog");
  before = follower.image;
  fog.setAbsorption(glm::vec3(0.002f));
  check("fog edited");
  EXPECT_EQ(geometryUploaded(), 0u);
}

TEST(VulkanMediator, TilesAreCropsAndViewportsShareOneScene) {
  Rig rig;
  sg::Replica replica;
  replica.apply(rig.source.commit());
  med::ContextPool contexts;
  auto full = rig.registry.create(rig.settings(), contexts);
  auto view = rig.view(replica.scene());
  med::FrameBuffer whole, tile;
  full->render(replica, view, whole);
  auto tiled = rig.registry.create(rig.settings(), contexts);
  med::PixelRect rect{10, 20, 30, 41};
  EXPECT_EQ(tiled->render(replica, view.cropped(rect), tile).update, med::SceneAdapter::Update::None)
      << "the second viewport finds the scene converted";
  ASSERT_EQ(tile.width, rect.width());
  ASSERT_EQ(tile.height, rect.height());
  // Rasterization rounding at triangle edges may differ; most pixels match.
  std::size_t same = 0;
  for (std::uint32_t y = 0; y < tile.height; ++y)
    for (std::uint32_t x = 0; x < tile.width; ++x)
      same += glm::all(
          glm::lessThan(glm::abs(tile.colour[tile.index(x, y)] - whole.colour[whole.index(x + rect.x0, y + rect.y0)]),
                        glm::vec4(1e-3f)));
  EXPECT_GE(same, tile.colour.size() * 95 / 100);
  EXPECT_EQ(contexts.live(), 1u);
}

TEST(VulkanMediator, OneDevicePerProcess) {
  Rig rig;
  sg::Replica replica;
  replica.apply(rig.source.commit());
  med::ContextPool a, b;
  auto first = rig.registry.create(rig.settings(), a);
  auto second = rig.registry.create(rig.settings(), b);  // another pool: another scene
  auto& ca = dynamic_cast<med::vulkan_mediator::VulkanViewport&>(*first).context();
  auto& cb = dynamic_cast<med::vulkan_mediator::VulkanViewport&>(*second).context();
  EXPECT_NE(&ca, &cb);
  EXPECT_EQ(ca.shared->device.get(), cb.shared->device.get());
}

TEST(VulkanMediator, AlphaIsCoverageAndDepthIsInfiniteWhereNothingWasDrawn) {
  sg::Scene source;
  auto& root = source.create<sg::Group>("root");
  auto& material = source.create<sg::SurfaceMaterial>("m");
  test::addQuad(source, root.id(), "small", {-0.2f, -0.2f, -5}, {0.2f, -0.2f, -5}, {0.2f, 0.2f, -5}, {-0.2f, 0.2f, -5},
                material.id());
  sg::Replica replica;
  replica.apply(source.commit());
  med::ViewportRegistry registry;
  med::registerVulkan(registry);
  med::ContextPool contexts;
  med::ViewportSettings settings;
  settings.backend = "vulkan";
  settings.root = root.id();
  auto viewport = registry.create(settings, contexts);
  med::View view;
  view.width = view.height = 32;
  view.region = {0, 0, 32, 32};
  view.left = view.bottom = -0.1f, view.right = view.top = 0.1f;
  view.nearPlane = 1.0f;
  med::FrameBuffer image;
  viewport->render(replica, view, image);
  EXPECT_EQ(image.colour[image.index(16, 16)].a, 1.0f);
  EXPECT_NEAR(image.depth[image.index(16, 16)], 5.0f, 1e-3f);
  EXPECT_EQ(image.colour[image.index(1, 1)].a, 0.0f);
  EXPECT_EQ(image.depth[image.index(1, 1)], med::kNoDepth);
}

TEST(VulkanMediator, BadParametersAreTypedErrors) {
  Rig rig;
  sg::Replica replica;
  replica.apply(rig.source.commit());
  med::ContextPool contexts;
  med::FrameBuffer image;
  for (auto [name, value] : {std::pair<std::string, med::ParameterValue>{"msaa", std::int64_t{3}},
                             {"msaa", std::string("lots")},
                             {"shadows", std::int64_t{2}},
                             {"shadowMapSize", std::int64_t{1} << 20}}) {
    auto settings = rig.settings();
    settings.parameters.set(name, value);
    // Refused when the viewport is made (type, range) or when it renders (msaa 3).
    EXPECT_THROW(rig.registry.create(settings, contexts)->render(replica, rig.view(replica.scene()), image),
                 med::ParameterError)
        << name;
  }
}
