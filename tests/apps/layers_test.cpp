// tessera-render --layers: parsing the layer list, finding layer roots, and
// the command compositing a rasterised layer over a path-traced one.
#include <fstream>

#include "command_runner.hpp"
#include "layers.hpp"
#include "tsr/med/image_file.hpp"

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

TEST(Layers, TakesTheOptionOutOfTheRemainingArguments) {
  std::vector<std::string> args{"--frames", "3", "--layers", "embree,vulkan:m", "--x"};
  auto layers = tsr::app::takeLayers(args);
  EXPECT_EQ(layers.size(), 2u);
  EXPECT_EQ(args, (std::vector<std::string>{"--frames", "3", "--x"}));
  args = {"--layers=vulkan"};
  EXPECT_EQ(tsr::app::takeLayers(args).size(), 1u);
  EXPECT_TRUE(args.empty());
  EXPECT_TRUE(tsr::app::takeLayers(args).empty());
  args = {"--layers"};
  EXPECT_THROW(tsr::app::takeLayers(args), std::invalid_argument);
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

// A glTF scene with two roots: "box" (a wall and, nearer, an occluder over
// its left half) and "markers" (a green quad between them, across the
// middle). Every surface is emissive, so the path tracer needs no light.
std::string twoRootScene() {
  const float positions[] = {-0.5f, -0.5f, 0, 0.5f, -0.5f, 0, 0.5f, 0.5f, 0, -0.5f, 0.5f, 0};
  const std::uint16_t indices[] = {0, 1, 2, 0, 2, 3};
  std::string bytes(reinterpret_cast<const char*>(positions), sizeof positions);
  bytes.append(reinterpret_cast<const char*>(indices), sizeof indices);
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string base64;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = std::uint32_t(std::uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= std::uint8_t(bytes[i + 2]);
    for (std::size_t k = 0; k < 4; ++k) base64 += i + k <= bytes.size() ? table[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return R"({"asset": {"version": "2.0"},
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" + base64 + R"("}],
  "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 12}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-0.5, -0.5, 0], "max": [0.5, 0.5, 0]},
                {"bufferView": 1, "componentType": 5123, "count": 6, "type": "SCALAR"}],
  "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}, "emissiveFactor": [0.3, 0.3, 0.3]},
                {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}, "emissiveFactor": [0.8, 0.1, 0.1]},
                {"pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1]}, "emissiveFactor": [0.1, 1.0, 0.1]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]},
             {"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 1}]},
             {"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 2}]}],
  "nodes": [{"name": "box", "children": [1, 2]},
            {"name": "wall", "mesh": 0, "scale": [4, 4, 1]},
            {"name": "occluder", "mesh": 1, "translation": [-1, 0, 0.5], "scale": [2, 4, 1]},
            {"name": "markers", "children": [4]},
            {"name": "marker", "mesh": 2, "translation": [0, 0, 0.25]}],
  "scenes": [{"nodes": [0, 3]}], "scene": 0})";
}

TEST_F(LayersCommand, RasterisedMarkerOverPathTracedBoxIsOccludedWhereTheBoxIsNearer) {
  std::ofstream(dir / "two_roots.gltf") << twoRootScene();
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

TEST_F(LayersCommand, BadLayersAreOneErrorLine) {
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers \"vulkan:nosuch\""), "nosuch");
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers embree,nosuch"), "unknown back-end 'nosuch'");
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers missing.json"), "missing.json");
  std::ofstream(dir / "bad.json") << R"([{"root": "x"}])";
  expectOneErrorLine(run("builtin:cornell --size 8x8 --layers bad.json"), "backend");
}

}  // namespace
