// tessera-render --layers: parsing the layer list, finding layer roots, and
// the command compositing a rasterised layer over a path-traced one.
#include <fstream>

#include "command_runner.hpp"
#include "layers.hpp"
#include "tsr/med/image_file.hpp"
#include "two_root_scene.hpp"

namespace {

using tsr::app::LayerSpec;
using tsr::test::Outcome;

TEST(Layers, ParsesBackEndsWithOptionalRoots) {
  auto layers = tsr::app::parseLayers("embree,vulkan:markers,vulkan:a:b");
  ASSERT_EQ(layers.size(), 3u);
  EXPECT_EQ(layers[0].backend, "embree");
  EXPECT_EQ(layers[0].root, "");
  EXPECT_EQ(layers[1].backend, "vulkan");
  EXPECT_EQ(layers[1].root, "markers");
  EXPECT_EQ(layers[2].root, "a:b") << "only the first colon separates";
  for (const char* bad : {"", ",", "embree,", ":markers", "vulkan:", "embree,,vulkan"})
    EXPECT_THROW(tsr::app::parseLayers(bad), std::invalid_argument) << bad;
}

TEST(Layers, RootsAreUniquelyNamedGroupsOrTransforms) {
  tsr::sg::Scene scene;
  auto& markers = scene.create<tsr::sg::Group>("markers");
  scene.create<tsr::sg::Geometry>("mesh");
  scene.create<tsr::sg::Transform>("twice");
  scene.create<tsr::sg::Group>("twice");
  EXPECT_EQ(tsr::app::findLayerRoot(scene, "markers"), markers.id());
  EXPECT_THROW(tsr::app::findLayerRoot(scene, "mesh"), std::invalid_argument) << "not a node with children";
  EXPECT_THROW(tsr::app::findLayerRoot(scene, "twice"), std::invalid_argument);
  EXPECT_THROW(tsr::app::findLayerRoot(scene, "none"), std::invalid_argument);
}

class LayersCommand : public tsr::test::CommandTest {
 protected:
  Outcome run(const std::string& args) { return runBinary(TSR_RENDER_PATH, args); }
};

TEST_F(LayersCommand, RasterisedMarkerOverPathTracedBoxIsOccludedWhereTheBoxIsNearer) {
  std::ofstream(dir / "two_roots.gltf") << tsr::test::twoRootScene();
  const std::string common = "two_roots.gltf --size 64x64 --spp 2 --max-depth 2 --seed 1 --quiet ";
  Outcome r = run(common + "--layers embree:box --output traced.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run(common + "--layers embree:box,vulkan:markers --output layered.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  auto traced = tsr::med::readImage((dir / "traced.exr").string());
  auto layered = tsr::med::readImage((dir / "layered.exr").string());
  // The camera frames the bounds from +z: the marker spans the middle, the
  // occluder the left half. Visible marker pixels are green; the rest is
  // the path-traced image, the occluder included.
  std::size_t green = 0, greenLeft = 0, other = 0;
  for (std::uint32_t y = 0; y < traced.height; ++y)
    for (std::uint32_t x = 0; x < traced.width; ++x) {
      std::size_t i = traced.index(x, y);
      if (layered.colour[i] == traced.colour[i]) continue;
      const bool isGreen = layered.colour[i].g > 0.9f && layered.colour[i].r < 0.2f;
      green += isGreen;
      greenLeft += isGreen && x < traced.width / 2 - 1;
      other += !isGreen;
    }
  EXPECT_GT(green, 20u) << "the marker's right half shows";
  EXPECT_EQ(greenLeft, 0u) << "its left half is behind the path-traced occluder";
  EXPECT_LE(other, 2 * traced.height) << "only edge pixels blend";
  const auto centreLeft = traced.index(traced.width / 2 - 3, traced.height / 2);
  EXPECT_EQ(layered.colour[centreLeft], traced.colour[centreLeft]);
  EXPECT_GT(traced.colour[centreLeft].r, 0.7f) << "the occluder";

  std::ofstream(dir / "layers.json") << R"([{"backend": "embree", "root": "box"},
    {"backend": "vulkan", "root": "markers", "parameters": {"msaa": 4}}])";
  r = run(common + "--layers layers.json --output fromfile.exr");
  ASSERT_EQ(r.status, 0) << r.err;
  auto fromFile = tsr::med::readImage((dir / "fromfile.exr").string());
  std::size_t same = 0;
  for (std::size_t i = 0; i < traced.colour.size(); ++i) same += fromFile.colour[i] == layered.colour[i];
  EXPECT_GT(same, traced.colour.size() * 9 / 10) << "the same layers, MSAA only on the marker's edges";
}

TEST_F(LayersCommand, EveryFrameOfASequenceIsALayeredWindow) {
  std::ofstream(dir / "two_roots.gltf") << tsr::test::twoRootScene();
  const std::string common =
      "two_roots.gltf --size 32x32 --spp 2 --max-depth 2 --seed 1 --quiet --layers embree:box,vulkan:markers ";
  Outcome r = run(common + "--output single.exr --aov depth");
  ASSERT_EQ(r.status, 0) << r.err;
  r = run(common + "--frames 2 --output seq.####.exr --aov depth");
  ASSERT_EQ(r.status, 0) << r.err;
  // The scene has no animation: both frames are the single layered image.
  const auto single = tsr::med::readImage((dir / "single.exr").string());
  const auto singleDepth = tsr::med::readImage((dir / "single.depth.exr").string());
  for (const char* frame : {"0000", "0001"}) {
    const auto image = tsr::med::readImage((dir / ("seq." + std::string(frame) + ".exr")).string());
    EXPECT_EQ(image.colour, single.colour) << frame;
    EXPECT_EQ(tsr::med::readImage((dir / ("seq." + std::string(frame) + ".depth.exr")).string()).colour,
              singleDepth.colour);
  }
  expectOneErrorLine(run(common + "--frames 2 --temporal pca --output t.####.exr"), "--temporal pca with --layers");
}

TEST_F(LayersCommand, BadLayersAreOneErrorLine) {
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers \"vulkan:nosuch\""), "nosuch");
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers embree,nosuch"), "unknown back-end 'nosuch'");
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers missing.json"), "missing.json");
  std::ofstream(dir / "bad.json") << R"([{"root": "x"}])";
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers bad.json"), "backend");
  std::ofstream(dir / "typo.json") << R"([{"backend": "embree", "rot": "box"}])";
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers typo.json"), "unknown key \"rot\"");
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers"), "--layers");
}

}  // namespace
