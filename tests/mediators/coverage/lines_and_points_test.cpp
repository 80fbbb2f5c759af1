// glTF's points and lines as Debian's glTF-Asset-Generator models carry them
// (Mesh_PrimitiveMode_00-03 and, indexed, 07-10: points, lines, a line loop, a line strip, no
// material): the rasterizer draws them, the Vulkan id pass counts them, and
// the back-ends that cannot (the path tracer, the Embree id pass) leave them
// out with a warning instead of failing the frame.
#include <gtest/gtest.h>

#include <filesystem>

#include "tsr/med/coverage/ranking.hpp"
#include "tsr/med/coverage/register.hpp"
#include "tsr/med/embree/register.hpp"
#include "tsr/med/vulkan/register.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/import/scene_camera.hpp"

using namespace tsr;

namespace {

const std::string kModes = "/usr/share/assimp/models/glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/";
constexpr std::uint32_t kSize = 64;

struct Drawing {
  sg::Scene source;
  sg::ImportResult imported;
  sg::ContainerId camera = sg::kNoContainer;
  sg::Replica replica;
  med::ViewportRegistry registry;
  med::ContextPool contexts;
  explicit Drawing(const std::string& file) {
    imported = sg::importScene(source, file);
    camera = sg::addFramingCamera(source, imported.root);
    replica.apply(source.commit());
    med::registerCoverage(registry);
    med::registerVulkan(registry);
    med::registerEmbree(registry);
  }
  med::FrameBuffer render(const std::string& backend, const std::string& engine = "") {
    med::ViewportSettings s;
    s.backend = backend;
    s.root = imported.root;
    if (!engine.empty()) s.parameters.set("engine", engine);
    auto viewport = registry.create(s, contexts);
    med::FrameBuffer image;
    viewport->render(replica, med::View::fromCamera(*replica.scene().find<sg::Camera>(camera), kSize, kSize), image);
    return image;
  }
};

std::size_t covered(const med::FrameBuffer& image) {
  std::size_t n = 0;
  for (const glm::vec4& c : image.colour) n += c.a > 0.0f;
  return n;
}

class PrimitiveModes : public ::testing::TestWithParam<const char*> {};

TEST_P(PrimitiveModes, DrawnByTheRasterizerLeftOutWithAWarningElsewhere) {
  const std::string file = kModes + "Mesh_PrimitiveMode_" + GetParam() + ".gltf";
  ASSERT_TRUE(std::filesystem::exists(file)) << file << " (Debian's assimp-testmodels, scripts/install-deps.sh)";
  Drawing d(file);
  EXPECT_EQ(d.imported.counts.skippedPrimitives, 0u);

  const med::FrameBuffer raster = d.render("vulkan");
  const std::size_t drawn = covered(raster);
  EXPECT_GT(drawn, 8u) << "the rasterizer draws them";
  EXPECT_LT(drawn, kSize * kSize / 4) << "one pixel wide, not filled";
  // Unlit glTF default material: white, whatever the lights.
  for (std::size_t i = 0; i < raster.colour.size(); ++i) {
    if (raster.colour[i].a > 0.0f) {
      EXPECT_NEAR(raster.colour[i].r, 1.0f, 1e-3f);
    }
  }

  const med::FrameBuffer ids = d.render("coverage", "vulkan");
  const auto ranked = med::rankObjects(ids, d.replica.scene());
  ASSERT_EQ(ranked.size(), 1u) << "the Vulkan id pass counts them";
  EXPECT_GT(ranked.front().pixels, 8u);

  // The Embree id pass and the path tracer draw no lines or points: the
  // frame renders, without them.
  EXPECT_TRUE(med::rankObjects(d.render("coverage", "embree"), d.replica.scene()).empty());
  EXPECT_EQ(covered(d.render("embree")), 0u);
}

INSTANTIATE_TEST_SUITE_P(Mesh, PrimitiveModes, ::testing::Values("00", "01", "02", "03", "07", "08", "09", "10"));

}  // namespace
