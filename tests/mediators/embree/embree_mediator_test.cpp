// The Embree mediator through the real path tracer: incremental sync gives
// the same bits as converting the edited scene afresh, tiles are crops,
// contexts are shared.
#include <gtest/gtest.h>

#include <atomic>

#include <glm/gtc/matrix_transform.hpp>

#include "../viewport_rig.hpp"
#include "tsr/embree/render_settings.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/sg/import/importer.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 48;

struct Rig : test::ViewportRig {
  explicit Rig(const std::string& scene = "builtin:cornell")
      : ViewportRig("embree", med::registerEmbree, scene, kSize) {
    parameters.set("spp", std::int64_t{4});
    parameters.set("seed", std::int64_t{7});
    parameters.set("maxDepth", std::int64_t{4});
  }
  med::ViewportSettings settings(int spp = 4) const {
    med::ViewportSettings s = ViewportRig::settings();
    s.parameters.set("spp", std::int64_t{spp});
    return s;
  }
};

using test::Follower;

med::FrameBuffer fresh(const Rig& rig) { return test::freshRender(rig); }

void expectSameBits(const med::FrameBuffer& a, const med::FrameBuffer& b, const char* what) {
  EXPECT_EQ(test::differingPixels(a, b), 0u) << what << ": pixels that differ";
}

using test::findNamed;

class IncrementalSync : public ::testing::Test {
 protected:
  Rig rig;
  Follower follower;
  med::FrameBuffer before;
  void SetUp() override {
    follower.replica.apply(rig.source.commit());
    ASSERT_EQ(follower.render(rig).update, med::SceneAdapter::Update::Converted);
    before = follower.image;
  }
  // Publishes the edit, renders incrementally, compares with a fresh conversion.
  void check(const char* what) {
    follower.replica.apply(rig.source.commit());
    auto stats = follower.render(rig);
    EXPECT_EQ(stats.update, med::SceneAdapter::Update::Synced) << what;
    expectSameBits(follower.image, fresh(rig), what);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < before.colour.size(); ++i) changed += before.colour[i] != follower.image.colour[i];
    EXPECT_GT(changed, 0u) << what << ": the edit is visible";
  }
};
}  // namespace

TEST_F(IncrementalSync, TransformEdit) {
  auto* t = rig.source.find<sg::Transform>(findNamed(rig.source, sg::ContainerType::Transform, "tall"));
  if (!t) t = rig.source.find<sg::Transform>(findNamed(rig.source, sg::ContainerType::Transform));
  ASSERT_NE(t, nullptr);
  t->setMatrix(glm::translate(t->matrix(), glm::vec3(30, 0, 10)));
  check("transform");
}

TEST_F(IncrementalSync, MaterialEdit) {
  auto* m = rig.source.find<sg::SurfaceMaterial>(findNamed(rig.source, sg::ContainerType::SurfaceMaterial));
  ASSERT_NE(m, nullptr);
  m->setBaseColor({0.1f, 0.2f, 0.9f});
  check("material");
}

TEST_F(IncrementalSync, AlphaModeEdits) {
  auto* m = rig.source.find<sg::SurfaceMaterial>(findNamed(rig.source, sg::ContainerType::SurfaceMaterial));
  ASSERT_NE(m, nullptr);
  m->setOpacity(0.3f);
  m->setAlphaMode(sg::AlphaMode::Blend);  // imported as glTF's OPAQUE: now see-through in part
  check("blended");
  before = follower.image;
  m->setAlphaMode(sg::AlphaMode::Mask);  // below the cut-off of 0.5: gone
  check("masked");
  before = follower.image;
  m->setAlphaMode(sg::AlphaMode::Opaque);
  check("opaque");
}

TEST_F(IncrementalSync, GeometryRangeEdit) {
  auto* g = rig.source.find<sg::Geometry>(findNamed(rig.source, sg::ContainerType::Geometry));
  ASSERT_NE(g, nullptr);
  std::vector<sg::Vec3> moved(g->positions().begin(), g->positions().begin() + 3);
  for (auto& p : moved) p += sg::Vec3(0, 40, 0);
  g->updatePositions(0, moved);
  check("geometry range");
}

TEST_F(IncrementalSync, CreateAndDestroy) {
  // A new instance of an existing mesh under the root...
  auto& t = rig.source.create<sg::Transform>("extra");
  t.setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(-60, 0, -40)));
  t.addChild(findNamed(rig.source, sg::ContainerType::Geometry));
  rig.source.find<sg::Group>(rig.imported.root)->addChild(t.id());
  check("create");
  // ...and then one removed.
  before = follower.image;
  rig.source.destroy(t.id());
  check("destroy");
}

TEST_F(IncrementalSync, AttachmentsItUnderstandsAndOnesItIgnores) {
  auto* g = rig.source.find<sg::Geometry>(findNamed(rig.source, sg::ContainerType::Geometry));
  g->setAttachment("someone.else", std::string("ignored"));
  rig.source.find(rig.imported.root)->setAttachment("viewer.note", std::int64_t{1});
  follower.replica.apply(rig.source.commit());
  follower.render(rig);
  expectSameBits(follower.image, before, "attachments the mediator does not know change nothing");
  g->setAttachment("embree.hidden", std::int64_t{1});
  check("hidden geometry");
}

// A replica of the built-in Cornell box and a pool of contexts for the
// viewports a test creates.
class EmbreeMediator : public ::testing::Test {
 protected:
  void SetUp() override { replica.apply(rig.source.commit()); }
  Rig rig;
  sg::Replica replica;
  med::ContextPool contexts;
};

// A viewer dragging many objects, one frame per edit: each moved instance
// leaves a ghost in the top level until they fold back into it (past
// 2 sqrt(400) = 40 of them); moved again, they stay in the moving level.
TEST(EmbreeMediatorManyMoves, RenderAfterManyMovesEqualsAFreshConversion) {
  Rig rig("builtin:instances:400");
  std::vector<sg::Transform*>
      carriers;  // the unnamed transforms that each carry one object (not the camera's, the sun's)
  for (auto id : rig.source.ids())
    if (auto* t = rig.source.find<sg::Transform>(id); t && t->children().size() == 1 && t->name().empty())
      carriers.push_back(t);
  ASSERT_EQ(carriers.size(), 400u);
  Follower follower;
  follower.replica.apply(rig.source.commit());
  ASSERT_EQ(follower.render(rig).update, med::SceneAdapter::Update::Converted);
  const med::FrameBuffer before = follower.image;
  auto move = [&](std::size_t i, float dz) {
    sg::Transform& t = *carriers[i * 37 % carriers.size()];  // spread over the grid
    t.setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, dz)) * t.matrix());
    follower.replica.apply(rig.source.commit());
    EXPECT_EQ(follower.render(rig).update, med::SceneAdapter::Update::Synced);
  };
  for (std::size_t i = 0; i < 30; ++i) move(i, 0.3f);
  expectSameBits(follower.image, fresh(rig), "30 instances moved: ghosts");
  for (std::size_t i = 30; i < 60; ++i) move(i, -0.3f);
  for (std::size_t i = 50; i < 60; ++i) move(i, 0.2f);
  expectSameBits(follower.image, fresh(rig), "60 moved (a fold at 41), the last 10 moved again");
  EXPECT_GT(test::differingPixels(before, follower.image), 0u) << "the moves are visible";
}

TEST_F(EmbreeMediator, TilesAreCropsAndThreadsDoNotMatter) {
  auto full = rig.registry.create(rig.settings(), contexts);
  auto view = rig.view(replica.scene());
  med::FrameBuffer whole, tile;
  full->render(replica, view, whole);
  auto tiled = rig.registry.create(rig.settings(), contexts);
  tiled->setParameter("threads", std::int64_t{1});
  med::PixelRect rect{10, 20, 30, 41};
  tiled->render(replica, view.cropped(rect), tile);
  ASSERT_EQ(tile.width, rect.width());
  for (std::uint32_t y = 0; y < tile.height; ++y)
    for (std::uint32_t x = 0; x < tile.width; ++x) {
      ASSERT_EQ(tile.colour[tile.index(x, y)], whole.colour[whole.index(x + rect.x0, y + rect.y0)]) << x << "," << y;
      ASSERT_EQ(tile.depth[tile.index(x, y)], whole.depth[whole.index(x + rect.x0, y + rect.y0)]);
    }
  EXPECT_EQ(contexts.live(), 1u) << "both viewports share one converted scene";
}

TEST(EmbreeMediatorCatchUp, ReactivatedViewportCatchesUpWithoutReconverting) {
  Rig rig;
  sg::Replica replica(512);
  replica.apply(rig.source.commit());
  med::ContextPool contexts;
  auto viewport = rig.registry.create(rig.settings(1), contexts);
  med::FrameBuffer image;
  EXPECT_EQ(viewport->render(replica, rig.view(replica.scene()), image).update, med::SceneAdapter::Update::Converted);
  auto* t = rig.source.find<sg::Transform>(findNamed(rig.source, sg::ContainerType::Transform));
  for (int frame = 0; frame < 100; ++frame) {  // the viewport is switched off meanwhile
    t->setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(frame * 0.1f, 0, 0)));
    replica.apply(rig.source.commit());
  }
  EXPECT_EQ(viewport->render(replica, rig.view(replica.scene()), image).update, med::SceneAdapter::Update::Synced);
}

TEST_F(EmbreeMediator, ConvergedImagesAreReusedUntilSomethingChanges) {
  auto viewport = rig.registry.create(rig.settings(2), contexts);
  med::FrameBuffer image;
  auto view = rig.view(replica.scene());
  EXPECT_GT(viewport->render(replica, view, image).rays, 0u);
  EXPECT_EQ(viewport->render(replica, view, image).rays, 0u) << "nothing changed: no work";
  viewport->setParameter("spp", std::int64_t{3});
  auto more = viewport->render(replica, view, image);
  EXPECT_GT(more.rays, 0u);
  EXPECT_EQ(more.samples, 3u) << "continues from 2 samples";
  viewport->setParameter("seed", std::int64_t{99});
  EXPECT_EQ(viewport->render(replica, view, image).samples, 3u) << "restarted and reconverged";
  EXPECT_EQ(viewport->render(replica, view, image).rays, 0u);
  viewport->setParameter("filter", std::string("radiance"));
  EXPECT_GT(viewport->render(replica, view, image).rays, 0u) << "radiance samples do not reuse path samples";
  EXPECT_EQ(viewport->render(replica, view, image).rays, 0u);
  viewport->setParameter("filter", std::string("none"));
  EXPECT_GT(viewport->render(replica, view, image).rays, 0u);
}

// A denoiser setting changed on a converged image denoises the samples held
// again, with no new samples: the image a viewer shows follows the control.
TEST_F(EmbreeMediator, DenoiserSettingsApplyToTheSamplesHeld) {
  auto viewport = rig.registry.create(rig.settings(8), contexts);
  viewport->setParameter("filter", std::string("denoise"));
  const auto view = rig.view(replica.scene());
  med::FrameBuffer regression, atrous, again;
  viewport->render(replica, view, regression);
  viewport->setParameter("denoiseMethod", std::string("atrous"));
  EXPECT_EQ(viewport->render(replica, view, atrous).rays, 0u) << "the samples held are reused";
  EXPECT_GT(test::differingPixels(regression, atrous), 0u) << "the other method's image";
  auto fresh = rig.registry.create(rig.settings(8), contexts);
  fresh->setParameter("filter", std::string("denoise"));
  fresh->setParameter("denoiseMethod", std::string("atrous"));
  fresh->render(replica, view, again);
  expectSameBits(atrous, again, "as if set before rendering");
}

// The sampling parameters reach the path tracer (through
// embree::describeSettings): each restarts the samples held and gives
// another image, and setting it back gives the first again.
TEST_F(EmbreeMediator, SamplingParametersRestartAndChangeTheImage) {
  auto viewport = rig.registry.create(rig.settings(2), contexts);
  const auto view = rig.view(replica.scene());
  med::FrameBuffer first;
  viewport->render(replica, view, first);
  for (const auto& [name, value] :
       std::vector<std::pair<std::string, med::ParameterValue>>{{"sampler", std::string("independent")},
                                                                {"lightChoice", std::string("power")},
                                                                {"rouletteDepth", std::int64_t{1}}}) {
    auto other = rig.registry.create(rig.settings(2), contexts);
    other->setParameter(name, value);
    med::FrameBuffer image;
    EXPECT_EQ(other->render(replica, view, image).samples, 2u) << name;
    EXPECT_GT(test::differingPixels(first, image), 0u) << name << " changes which samples are taken";
    viewport->setParameter(name, value);
    med::FrameBuffer again;
    EXPECT_GT(viewport->render(replica, view, again).rays, 0u) << name << " restarts the samples held";
    expectSameBits(again, image, name.c_str());
    viewport->setParameter("sampler", std::string("sobol"));
    viewport->setParameter("lightChoice", std::string("tree"));
    viewport->setParameter("rouletteDepth", std::int64_t{tsr::embree::RenderSettings{}.rouletteDepth});
    med::FrameBuffer back;
    viewport->render(replica, view, back);
    expectSameBits(back, first, "the defaults again");
  }
}

TEST_F(EmbreeMediator, GrowingPassesGiveTheSameImageAsSingleSamplePasses) {
  auto view = rig.view(replica.scene());
  std::vector<double> progress;
  med::RenderControl control;
  control.progress = [&](double f) { progress.push_back(f); };
  auto grown = rig.registry.create(rig.settings(11), contexts);  // passes of 1, 2, 4, 4 samples
  med::FrameBuffer a, b;
  EXPECT_EQ(grown->render(replica, view, a, control).samples, 11u);
  EXPECT_EQ(progress.size(), 4u) << "one progress report per pass";
  auto single = rig.registry.create(rig.settings(11), contexts);
  single->setParameter("samplesPerPass", std::int64_t{1});
  EXPECT_EQ(single->render(replica, view, b).samples, 11u);
  expectSameBits(a, b, "grown passes");
}

TEST_F(EmbreeMediator, FillsOnlyTheOutputsTheCallerReads) {
  auto view = rig.view(replica.scene());
  med::FrameBuffer all, some;
  rig.registry.create(rig.settings(), contexts)->render(replica, view, all);
  EXPECT_EQ(all.outputs.size(), 6u) << "albedo, normal, direct, indirect, variance, samples";
  med::RenderControl control;
  control.outputs = std::vector<std::string>{"normal", "no-such-output"};
  rig.registry.create(rig.settings(), contexts)->render(replica, view, some, control);
  ASSERT_EQ(some.outputs.size(), 1u);
  EXPECT_EQ(some.outputs.at("normal"), all.outputs.at("normal"));
  expectSameBits(some, all, "colour with fewer outputs");
  EXPECT_EQ(some.depth, all.depth);
}

TEST_F(EmbreeMediator, BadParametersAreTypedErrors) {
  auto settings = rig.settings();
  settings.parameters.set("spp", std::string("many"));
  EXPECT_THROW(rig.registry.create(settings, contexts), med::BadParameterValue) << "refused before it renders";
  settings.parameters = {};
  auto viewport = rig.registry.create(settings, contexts);
  EXPECT_THROW(viewport->setParameter("sigmaS", 0.0), med::BadParameterValue);
  EXPECT_THROW(viewport->setParameter("sigmaSS", 4.0), med::UnknownParameter);
  viewport->setParameter("antialiasRecovery", true);
  viewport->setParameter("filterKernel", std::string("bilateral"));
  med::FrameBuffer image;
  EXPECT_THROW(viewport->render(replica, rig.view(replica.scene()), image), med::ParameterError)
      << "a combination the table cannot see is refused when rendering";
}

// Volumes travel like every other field: attached to a geometry, edited,
// or filling the scene from the background, the incremental render equals
// a fresh conversion, and the change shows.
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
  ASSERT_NE(glass, nullptr) << "builtin:cornell has a glass sphere";
  auto& jelly = rig.source.create<sg::VolumeMaterial>("jelly");
  jelly.setAbsorption({0.002f, 0.02f, 0.02f});  // per millimetre: the sphere is about 160 wide
  jelly.setScattering(glm::vec3(0.01f));
  glass->setVolume(jelly.id());
  check("volume attached");
  before = follower.image;
  jelly.setScattering(glm::vec3(0.03f));
  check("volume edited");
}

TEST_F(IncrementalSync, VolumeTextureAttachedEditedAndResliced) {
  sg::Geometry* glass = glassGeometry(rig.source);
  ASSERT_NE(glass, nullptr);
  // A cloud in the glass sphere: 2 x 2 texels in 2 slices, dense on one side.
  auto& density = rig.source.create<sg::Image>("density");
  density.setPixels(2, 4, 1, sg::PixelFormat::UInt8, {255, 0, 255, 0, 128, 0, 128, 0});
  density.setColorSpace(sg::ColorSpace::Linear);
  auto& cloud = rig.source.create<sg::VolumeMaterial>("cloud");
  cloud.setScattering(glm::vec3(0.05f));
  glass->setVolume(cloud.id());
  check("untextured cloud");
  before = follower.image;
  cloud.setScatteringTexture(density.id());
  cloud.setTextureSlices(2);
  check("texture attached");
  before = follower.image;
  density.setPixels(2, 4, 1, sg::PixelFormat::UInt8, {0, 255, 0, 255, 0, 64, 0, 64});
  check("texture edited");
  before = follower.image;
  cloud.setTextureSlices(1);
  check("slices changed");
}

TEST_F(IncrementalSync, FogFillsTheSceneFromTheBackground) {
  auto& fog = rig.source.create<sg::VolumeMaterial>("fog");
  fog.setScattering(glm::vec3(0.001f));
  fog.setAbsorption(glm::vec3(0.0005f));
  rig.source.find<sg::Background>(rig.imported.background)->setMedium(fog.id());
  check("fog");
}

// The history parameter: off, a panned view restarts; on, it carries the
// samples held to the pixels that show the same surfaces. The window slides
// by whole pixels and the render is cancelled before tracing, so the image
// shown is the carried history alone: the old one moved by those pixels.
TEST_F(EmbreeMediator, HistoryCarriesAPannedViewAndIsOffUnlessAsked) {
  for (const bool history : {false, true}) {
    SCOPED_TRACE(history ? "history on" : "history off");
    auto viewport = rig.registry.create(rig.settings(4), contexts);
    if (history) viewport->setParameter("history", true);
    med::View view = rig.view(replica.scene());
    med::FrameBuffer before, after;
    viewport->render(replica, view, before);
    constexpr std::uint32_t kShift = 2;
    const float step = (view.right - view.left) / float(view.width) * float(kShift);
    view.left += step;
    view.right += step;
    std::atomic<bool> cancel{true};
    med::RenderControl control;
    control.cancel = &cancel;
    EXPECT_EQ(viewport->render(replica, view, after, control).samples, 0u) << "nothing traced for the new view";
    const auto& samples = after.outputs.at("samples");
    std::size_t carried = 0;
    for (std::uint32_t y = 0; y < kSize; ++y)
      for (std::uint32_t x = 0; x + kShift < kSize; ++x) {
        const std::size_t i = after.index(x, y), from = before.index(x + kShift, y);
        EXPECT_EQ(samples[i].r, 0.0f);
        if (!history) {
          ASSERT_EQ(samples[i].g, 0.0f) << x << ", " << y;
          continue;
        }
        if (samples[i].g == 0.0f) continue;  // nothing there: the box's opening, or an edge the depth test refused
        ++carried;
        ASSERT_EQ(samples[i].g, 4.0f);
        for (int c = 0; c < 4; ++c)
          EXPECT_NEAR(after.colour[i][c], before.colour[from][c], 1e-4f * (1.0f + std::abs(before.colour[from][c])));
      }
    if (history) {
      EXPECT_GT(carried, kSize * kSize / 2);
    }
  }
}
