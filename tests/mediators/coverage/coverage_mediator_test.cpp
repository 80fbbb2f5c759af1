// The coverage mediator through the real id pass: ids are scene ids with
// names, transparent materials let the view through, tiles are crops, and
// incremental sync gives exactly the ids of a fresh conversion.
#include <gtest/gtest.h>

#include <map>

#include <glm/gtc/matrix_transform.hpp>

#include "../viewport_rig.hpp"
#include "tsr/med/coverage/false_colour.hpp"
#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/coverage/register.hpp"
#include "tsr/sg/import/importer.hpp"

using namespace tsr;

namespace {
constexpr std::uint32_t kSize = 64;

struct Rig : test::ViewportRig {
  Rig() : ViewportRig("coverage", med::registerCoverage, "builtin:cornell", kSize) {}
};

using test::Follower;

med::FrameBuffer fresh(const Rig& rig) { return test::freshRender(rig); }

const std::vector<glm::vec4>& ids(const med::FrameBuffer& fb) { return fb.outputs.at(med::kIdOutput); }

sg::ContainerId byName(const sg::Scene& s, sg::ContainerType type, const std::string& name) {
  for (auto id : s.ids())
    if (s.find(id)->type() == type && s.find(id)->name() == name) return id;
  return sg::kNoContainer;
}

std::uint64_t pixelsOf(const std::vector<med::RankedObject>& ranking, sg::ContainerId id) {
  for (const auto& r : ranking)
    if (r.id == id) return r.pixels;
  return 0;
}
}  // namespace

TEST(CoverageMediator, CornellRankingNamesSceneObjects) {
  Rig rig;
  Follower f;
  f.replica.apply(rig.source.commit());
  auto stats = f.render(rig);
  EXPECT_EQ(stats.rays, kSize * kSize);
  const auto& scene = f.replica.scene();
  auto ranking = med::rankObjects(f.image, scene);
  ASSERT_GE(ranking.size(), 4u);
  std::uint64_t sum = med::backgroundPixels(f.image);
  for (const auto& r : ranking) sum += r.pixels;
  EXPECT_EQ(sum, kSize * kSize);
  EXPECT_EQ(ranking.front().name, "white") << "floor, ceiling and back wall cover most of the view";
  for (const char* name : {"red", "green", "mirror sphere"}) {
    const sg::ContainerId t = byName(scene, sg::ContainerType::Transform, name);
    ASSERT_NE(t, sg::kNoContainer) << name;
    EXPECT_GT(pixelsOf(ranking, t), 0u) << name << " is reported by its Transform's id";
  }
  const sg::ContainerId glass = byName(scene, sg::ContainerType::Transform, "glass sphere");
  EXPECT_EQ(pixelsOf(ranking, glass), 0u) << "transmission > 0.5 is transparent: not counted";

  // The colour is the false colour of the id, the depth finite where hit.
  for (std::size_t i = 0; i < f.image.colour.size(); ++i) {
    const sg::ContainerId id = med::decodeObjectId(ids(f.image)[i]);
    EXPECT_EQ(glm::vec3(f.image.colour[i]), med::falseColour(id));
    EXPECT_EQ(f.image.colour[i].a, id ? 1.0f : 0.0f);
    EXPECT_EQ(std::isfinite(f.image.depth[i]), id != sg::kNoContainer);
  }
}

TEST(CoverageMediator, RankingEqualsBruteForceOverTheIdOutput) {
  Rig rig;
  Follower f;
  f.replica.apply(rig.source.commit());
  f.render(rig);
  std::map<sg::ContainerId, std::uint64_t> count;
  for (const auto& v : ids(f.image))
    if (v.r != 0.0f || v.g != 0.0f) ++count[static_cast<sg::ContainerId>(v.r)];
  auto ranking = med::rankObjects(f.image, f.replica.scene());
  ASSERT_EQ(ranking.size(), count.size());
  for (std::size_t i = 0; i < ranking.size(); ++i) {
    EXPECT_EQ(ranking[i].pixels, count[ranking[i].id]);
    EXPECT_DOUBLE_EQ(ranking[i].fraction, double(ranking[i].pixels) / (kSize * kSize));
    if (i) {
      EXPECT_GE(ranking[i - 1].pixels, ranking[i].pixels);
    }
  }
}

TEST(CoverageMediator, TileIsCropOfFullImage) {
  Rig rig;
  Follower f;
  f.replica.apply(rig.source.commit());
  f.render(rig);
  const med::FrameBuffer full = f.image;
  auto view = rig.view(f.replica.scene()).cropped({10, 20, 47, 61});
  med::FrameBuffer tile;
  f.viewport->render(f.replica, view, tile);
  ASSERT_EQ(tile.width, 37u);
  std::size_t differ = 0;
  for (std::uint32_t y = 0; y < tile.height; ++y)
    for (std::uint32_t x = 0; x < tile.width; ++x) {
      differ += ids(tile)[tile.index(x, y)] != ids(full)[full.index(10 + x, 20 + y)];
      differ += tile.depth[tile.index(x, y)] != full.depth[full.index(10 + x, 20 + y)];
    }
  EXPECT_EQ(differ, 0u);
}

TEST(CoverageMediator, GeometryWithoutTransformReportsItsOwnId) {
  sg::Scene source;
  auto& g = source.create<sg::Geometry>("bare quad");
  g.setPositions({{-1, -1, -2}, {1, -1, -2}, {1, 1, -2}, {-1, 1, -2}});
  g.setIndices({0, 1, 2, 0, 2, 3});
  sg::Replica replica;
  replica.apply(source.commit());
  med::ViewportRegistry registry;
  med::registerCoverage(registry);
  med::ContextPool contexts;
  med::ViewportSettings settings;
  settings.backend = "coverage";
  auto viewport = registry.create(settings, contexts);
  med::View view;
  view.width = view.height = 100;
  view.region = {0, 0, 100, 100};
  view.nearPlane = 1.0f;  // window [-1,1]^2 at z = -1: the quad at z = -2 covers the middle 50x50
  med::FrameBuffer out;
  viewport->render(replica, view, out);
  auto ranking = med::rankObjects(out, replica.scene());
  ASSERT_EQ(ranking.size(), 1u);
  EXPECT_EQ(ranking[0], (med::RankedObject{g.id(), "bare quad", 2500, 0.25}));
}

namespace {
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
  void check(const char* what) {
    follower.replica.apply(rig.source.commit());
    EXPECT_EQ(follower.render(rig).update, med::SceneAdapter::Update::Synced) << what;
    const med::FrameBuffer expected = fresh(rig);
    EXPECT_EQ(ids(follower.image), ids(expected)) << what;
    EXPECT_EQ(follower.image.depth, expected.depth) << what;
    EXPECT_NE(ids(follower.image), ids(before)) << what << ": the edit is visible";
  }
  sg::ContainerId named(sg::ContainerType type, const std::string& name) { return byName(rig.source, type, name); }
};
}  // namespace

TEST_F(IncrementalSync, TransformEdit) {
  auto* t = rig.source.find<sg::Transform>(named(sg::ContainerType::Transform, "mirror sphere"));
  ASSERT_NE(t, nullptr);
  t->setMatrix(glm::translate(t->matrix(), glm::vec3(-60, 0, 0)));
  check("transform");
}

TEST_F(IncrementalSync, CreateAndDestroy) {
  // A second placement of the mirror sphere's geometry, then the red wall gone.
  auto* mirror = rig.source.find<sg::Transform>(named(sg::ContainerType::Transform, "mirror sphere"));
  auto& copy = rig.source.create<sg::Transform>("second mirror");
  copy.setMatrix(glm::translate(glm::mat4(1.0f), glm::vec3(-200, -250, 0)));
  copy.addChild(mirror->children().front());
  rig.source.find<sg::Group>(rig.imported.root)->addChild(copy.id());
  check("create");
  EXPECT_GT(pixelsOf(med::rankObjects(follower.image, follower.replica.scene()), copy.id()), 0u);
  before = follower.image;
  rig.source.destroy(named(sg::ContainerType::Transform, "red"));
  check("destroy");
}

TEST_F(IncrementalSync, MaterialTransparency) {
  auto* white = rig.source.find<sg::SurfaceMaterial>(named(sg::ContainerType::SurfaceMaterial, "white"));
  ASSERT_NE(white, nullptr);
  white->setOpacity(0.5f);
  check("opacity");
  before = follower.image;
  white->setOpacity(1.0f);
  check("opaque again");
  before = follower.image;
  auto* glass = rig.source.find<sg::SurfaceMaterial>(named(sg::ContainerType::SurfaceMaterial, "glass"));
  glass->setTransmission(0.0f);
  check("glass made opaque");
}

// A medium with no surface (a cloud) is as transparent as glass to the
// ranking: what lies behind it covers the pixels.
TEST_F(IncrementalSync, AMediumOnlyObjectIsTransparent) {
  auto& cloud = rig.source.create<sg::VolumeMaterial>("cloud");
  cloud.setScattering(glm::vec3(0.1f));
  auto* redWall = rig.source.find<sg::Transform>(named(sg::ContainerType::Transform, "red"));
  auto* geometry = rig.source.find<sg::Geometry>(redWall->children().front());
  geometry->setVolume(cloud.id());
  geometry->setMaterial(sg::kNoContainer);
  check("medium only");
}

TEST_F(IncrementalSync, SimpleMaterialAssigned) {
  auto& veil = rig.source.create<sg::SimpleMaterial>("veil");
  veil.setTransparency(0.3f);
  auto* redWall = rig.source.find<sg::Transform>(named(sg::ContainerType::Transform, "red"));
  auto* geometry = rig.source.find<sg::Geometry>(redWall->children().front());
  geometry->setMaterial(veil.id());
  check("simple transparent material");
  before = follower.image;
  veil.setTransparency(0.0f);
  check("simple material opaque");
}

TEST_F(IncrementalSync, GeometryEdits) {
  auto* mirror = rig.source.find<sg::Transform>(named(sg::ContainerType::Transform, "mirror sphere"));
  auto* g = rig.source.find<sg::Geometry>(mirror->children().front());
  std::vector<sg::Vec3> moved(g->positions().begin(), g->positions().begin() + 40);
  for (auto& p : moved) p += sg::Vec3(0, 60, 0);
  g->updatePositions(0, moved);
  check("range edit");
  before = follower.image;
  std::vector<std::uint32_t> half(g->indices().begin(), g->indices().begin() + g->indices().size() / 2);
  g->setIndices(half);
  check("topology edit");
  before = follower.image;
  g->setIndices({0, 1, 1u << 30});  // invalid: skipped, the sphere disappears
  check("invalid geometry");
}
