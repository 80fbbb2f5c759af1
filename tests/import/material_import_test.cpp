// glTF material fields beyond the metallic-roughness factors: alpha modes
// and cut-off, the occlusion texture and its strength, and
// KHR_texture_transform on each texture slot, read into SurfaceMaterial;
// bad values are refused with the material they are in.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "expect_refused.hpp"
#include "gltf_writer.hpp"
#include "test_scenes.hpp"
#include "tsr/sg/import/import_error.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

test::GltfBuilder materialScene(const test::TempDir& dir, const nlohmann::json& material) {
  test::writePng(dir.file("p.png"), 2, 2, 4, test::kFilePixels);
  test::GltfBuilder b = test::tinyScene();
  b.doc["images"] = {{{"uri", "p.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  b.doc["materials"] = {material};
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["extensionsUsed"] = {"KHR_texture_transform"};
  return b;
}

const SurfaceMaterial& onlyMaterial(const Scene& scene) {
  for (ContainerId id : scene.ids())
    if (const auto* m = scene.find<SurfaceMaterial>(id)) return *m;
  throw std::runtime_error("no material");
}

const SurfaceMaterial& imported(Scene& scene, const test::TempDir& dir, const nlohmann::json& material) {
  materialScene(dir, material).writeGltf(dir.file("m.gltf"));
  importScene(scene, dir.file("m.gltf"));
  return onlyMaterial(scene);
}

TEST(MaterialImport, AlphaModesAndCutoff) {
  test::TempDir dir;
  const nlohmann::json pbr = {{"baseColorFactor", {1.0, 1.0, 1.0, 0.4}}};
  {
    Scene scene;
    const auto& m = imported(scene, dir, {{"alphaMode", "MASK"}, {"alphaCutoff", 0.3}, {"pbrMetallicRoughness", pbr}});
    EXPECT_EQ(m.alphaMode(), AlphaMode::Mask);
    EXPECT_FLOAT_EQ(m.alphaCutoff(), 0.3f);
    EXPECT_FLOAT_EQ(m.opacity(), 0.4f);
  }
  {
    Scene scene;
    const auto& m = imported(scene, dir, {{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", pbr}});
    EXPECT_EQ(m.alphaMode(), AlphaMode::Blend);
    EXPECT_FLOAT_EQ(m.alphaCutoff(), 0.5f) << "glTF's default";
  }
  {
    Scene scene;
    const auto& m = imported(scene, dir, {{"pbrMetallicRoughness", pbr}});
    EXPECT_EQ(m.alphaMode(), AlphaMode::Opaque) << "glTF's default";
    EXPECT_FLOAT_EQ(m.opacity(), 1.0f);
  }
}

TEST(MaterialImport, OcclusionTextureAndStrength) {
  test::TempDir dir;
  Scene scene;
  const auto& m = imported(scene, dir, {{"occlusionTexture", {{"index", 0}, {"strength", 0.7}}}});
  ASSERT_NE(m.occlusionTexture(), kNoContainer);
  EXPECT_FLOAT_EQ(m.occlusionStrength(), 0.7f);
  EXPECT_EQ(scene.find<Image>(m.occlusionTexture())->colorSpace(), ColorSpace::Linear) << "data, not colour";
}

TEST(MaterialImport, TextureTransformsArePerSlot) {
  test::TempDir dir;
  Scene scene;
  const nlohmann::json transform = {{"offset", {0.5, 0.25}}, {"rotation", std::numbers::pi / 2}, {"scale", {2.0, 3.0}}};
  const auto& m =
      imported(scene, dir,
               {{"pbrMetallicRoughness",
                 {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}}}},
                {"normalTexture", {{"index", 0}}}});
  const auto [row0, row1] = m.uvTransform(TextureSlot::BaseColor);
  // uv (1, 0): scaled to (2, 0), turned a quarter to (0, -2), moved by (0.5, 0.25).
  const Vec3 uv(1.0f, 0.0f, 1.0f);
  EXPECT_NEAR(glm::dot(row0, uv), 0.5f, 1e-6f);
  EXPECT_NEAR(glm::dot(row1, uv), -1.75f, 1e-6f);
  const auto [n0, n1] = m.uvTransform(TextureSlot::Normal);
  EXPECT_EQ(n0, Vec3(1, 0, 0));
  EXPECT_EQ(n1, Vec3(0, 1, 0)) << "a slot without a transform keeps the identity";
}

TEST(MaterialImport, BadMaterialFieldsAreRefused) {
  test::TempDir dir;
  nlohmann::json badTransform = {{"index", 0}};
  badTransform["extensions"]["KHR_texture_transform"]["offset"] = {1.0};
  const std::pair<nlohmann::json, std::string> cases[] = {
      {{{"alphaMode", "SOMETIMES"}}, "alphaMode"},
      {{{"pbrMetallicRoughness", {{"baseColorTexture", badTransform}}}}, "offset"},
      {{{"occlusionTexture", {{"index", 3}}}}, "texture"},
  };
  int n = 0;
  for (const auto& [material, problem] : cases) {
    const std::string path = dir.file("bad" + std::to_string(n++) + ".gltf");
    materialScene(dir, material).writeGltf(path);
    test::expectRefused(path, problem);
  }
}

}  // namespace
}  // namespace tsr::sg
