// Volumes from glTF: KHR_materials_volume's attenuation becomes absorption
// (Beer's law), Tessera's TSR_materials_volume adds scattering, emission
// and the phase function, TSR_scene_medium fills the scene with fog; a
// geometry names its volume beside its surface material. Bad values are
// refused with the place they are in, and nothing is half-imported.
#include <gtest/gtest.h>

#include <cmath>

#include "expect_refused.hpp"
#include "gltf_writer.hpp"
#include "test_scenes.hpp"
#include "tsr/sg/import/import_error.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

test::GltfBuilder volumeScene(const nlohmann::json& extensions) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["materials"] = {
      {{"name", "jelly"}, {"extensions", extensions}, {"pbrMetallicRoughness", {{"metallicFactor", 0.0}}}}};
  b.doc["meshes"][0]["primitives"][0]["material"] = 0;
  b.doc["extensionsUsed"] = {"KHR_materials_volume", "TSR_materials_volume", "TSR_scene_medium"};
  return b;
}

const VolumeMaterial* onlyVolume(const Scene& scene, ContainerId* geometryVolume = nullptr) {
  const VolumeMaterial* found = nullptr;
  for (ContainerId id : scene.ids()) {
    if (const auto* v = scene.find<VolumeMaterial>(id)) found = v;
    if (const auto* g = scene.find<Geometry>(id); g && geometryVolume) *geometryVolume = g->volume();
  }
  return found;
}

TEST(VolumeImport, AttenuationBecomesAbsorptionAndTesseraAddsTheRest) {
  test::TempDir dir;
  volumeScene(
      {{"KHR_materials_volume",
        {{"thicknessFactor", 1.0}, {"attenuationDistance", 2.0}, {"attenuationColor", {0.5, 1.0, 0.25}}}},
       {"TSR_materials_volume", {{"scattering", {1.0, 2.0, 3.0}}, {"emission", {0.1, 0.0, 0.0}}, {"phaseG", 0.4}}}})
      .writeGltf(dir.file("jelly.gltf"));
  Scene scene;
  importScene(scene, dir.file("jelly.gltf"));
  ContainerId bound = kNoContainer;
  const VolumeMaterial* v = onlyVolume(scene, &bound);
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(bound, v->id()) << "the geometry names the volume beside its surface";
  EXPECT_NEAR(v->absorption().x, -std::log(0.5f) / 2.0f, 1e-6f);
  EXPECT_NEAR(v->absorption().y, 0.0f, 1e-6f);
  EXPECT_NEAR(v->absorption().z, -std::log(0.25f) / 2.0f, 1e-6f);
  EXPECT_EQ(v->scattering(), Vec3(1, 2, 3));
  EXPECT_EQ(v->emission(), Vec3(0.1f, 0, 0));
  EXPECT_FLOAT_EQ(v->phaseG(), 0.4f);
}

TEST(VolumeImport, TheSceneMediumFillsTheBackground) {
  test::TempDir dir;
  test::GltfBuilder b = test::tinyScene();
  b.doc["scenes"][0]["extensions"] = {{"TSR_scene_medium", {{"scattering", {0.05, 0.05, 0.05}}, {"phaseG", -0.2}}}};
  b.doc["extensionsUsed"] = {"TSR_scene_medium"};
  b.writeGltf(dir.file("fog.gltf"));
  Scene scene;
  const ImportResult r = importScene(scene, dir.file("fog.gltf"));
  const auto* bg = scene.find<Background>(r.background);
  ASSERT_NE(bg, nullptr);
  const auto* fog = scene.find<VolumeMaterial>(bg->medium());
  ASSERT_NE(fog, nullptr);
  EXPECT_EQ(fog->scattering(), Vec3(0.05f));
  EXPECT_FLOAT_EQ(fog->phaseG(), -0.2f);
}

// A 2 x 4 grey PNG: two slices of 2 x 2, the first dense, the second thin.
test::GltfBuilder texturedVolumeScene(const test::TempDir& dir, const nlohmann::json& tesseraVolume) {
  test::writePng(dir.file("density.png"), 2, 4, 1, {255, 255, 255, 255, 64, 64, 64, 64});
  test::GltfBuilder b = volumeScene({{"TSR_materials_volume", tesseraVolume}});
  b.doc["images"] = {{{"uri", "density.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  return b;
}

TEST(VolumeImport, TesseraVolumesCarry3DTexturesAsLinearDensities) {
  test::TempDir dir;
  texturedVolumeScene(dir, {{"scattering", {1.0, 1.0, 1.0}},
                            {"scatteringTexture", {{"index", 0}}},
                            {"absorptionTexture", {{"index", 0}}},
                            {"textureSlices", 2}})
      .writeGltf(dir.file("cloud.gltf"));
  Scene scene;
  importScene(scene, dir.file("cloud.gltf"));
  const VolumeMaterial* v = onlyVolume(scene);
  ASSERT_NE(v, nullptr);
  EXPECT_EQ(v->textureSlices(), 2u);
  EXPECT_EQ(v->absorptionTexture(), v->scatteringTexture()) << "one image, shared";
  EXPECT_EQ(v->emissionTexture(), kNoContainer);
  const auto* image = scene.find<Image>(v->scatteringTexture());
  ASSERT_NE(image, nullptr);
  EXPECT_EQ(image->height(), 4u);
  EXPECT_EQ(image->colorSpace(), ColorSpace::Linear) << "densities are data, not colours";
}

TEST(VolumeImport, BadVolumeTexturesAreRefused) {
  test::TempDir dir;
  const std::pair<nlohmann::json, std::string> cases[] = {
      {{{"scatteringTexture", {{"index", 0}}}, {"textureSlices", 3}}, "not 3 slices of equal height"},
      {{{"scatteringTexture", {{"index", 0}}}, {"textureSlices", 0}}, "textureSlices must be a whole number"},
      {{{"scatteringTexture", {{"index", 0}}}, {"textureSlices", 1.5}}, "textureSlices must be a whole number"},
      {{{"scatteringTexture", {{"index", 7}}}}, "texture"},
      {{{"scatteringTexture", {{"texCoord", 0}}}}, "has no index"},
  };
  int n = 0;
  for (const auto& [tessera, problem] : cases) {
    const std::string path = dir.file("bad" + std::to_string(n++) + ".gltf");
    texturedVolumeScene(dir, tessera).writeGltf(path);
    test::expectRefused(path, problem);
  }
  // The scene's fog has no mesh to stretch a texture over.
  test::GltfBuilder b = texturedVolumeScene(dir, {{"scattering", {1.0, 1.0, 1.0}}});
  b.doc["scenes"][0]["extensions"] = {{"TSR_scene_medium", {{"scatteringTexture", {{"index", 0}}}}}};
  b.writeGltf(dir.file("fog.gltf"));
  Scene scene;
  EXPECT_THROW(importScene(scene, dir.file("fog.gltf")), ImportError);
}

TEST(VolumeImport, BadVolumesAreRefusedWhereTheyAre) {
  test::TempDir dir;
  const std::pair<nlohmann::json, std::string> cases[] = {
      {{{"KHR_materials_volume", {{"attenuationDistance", 0.0}}}}, "attenuationDistance must be positive"},
      {{{"KHR_materials_volume", {{"attenuationDistance", 1.0}, {"attenuationColor", {2.0, 1.0, 1.0}}}}},
       "attenuationColor must lie in [0, 1]"},
      {{{"TSR_materials_volume", {{"scattering", {-1.0, 0.0, 0.0}}}}}, "scattering must not be negative"},
      {{{"TSR_materials_volume", {{"phaseG", 1.0}}}}, "phaseG must lie strictly between -1 and 1"},
      {{{"TSR_materials_volume", {{"absorption", {1.0, 2.0}}}}}, "absorption"},
  };
  int n = 0;
  for (const auto& [extensions, problem] : cases) {
    const std::string path = dir.file("bad" + std::to_string(n++) + ".gltf");
    volumeScene(extensions).writeGltf(path);
    test::expectRefused(path, problem, "material");
  }
}

}  // namespace
}  // namespace tsr::sg
