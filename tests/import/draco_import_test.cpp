// KHR_draco_mesh_compression on import (issue 46): the Draco-compressed
// 2CylinderEngine of Debian's assimp-testmodels against its uncompressed
// twin, as .gltf and rebuilt as .glb, and broken streams refused with
// errors that name the extension.
#include <filesystem>
#include <fstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "expect_refused.hpp"
#include "gltf_writer.hpp"
#include "tsr/sg/geometry.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/import/scene_stats.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

const std::string kModels = "/usr/share/assimp/models/glTF2/";
const std::string kDraco = kModels + "draco/2CylinderEngine.gltf";
const std::string kPlain = kModels + "2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

SceneStats statsOf(const std::string& path) {
  Scene scene;
  const ImportResult r = importScene(scene, path);
  return computeSceneStats(scene, r.root);
}

// Triangles of non-zero area over the file's geometries (each counted once):
// Draco's encoder drops the others.
std::uint64_t properTriangles(const std::string& path) {
  Scene scene;
  importScene(scene, path);
  std::uint64_t n = 0;
  for (ContainerId id : scene.ids())
    if (const auto* g = scene.find<Geometry>(id)) {
      const auto& p = g->positions();
      const auto& i = g->indices();
      for (std::size_t t = 0; t + 2 < i.size(); t += 3)
        n += glm::length(glm::cross(p[i[t + 1]] - p[i[t]], p[i[t + 2]] - p[i[t]])) > 0.0f;
    }
  return n;
}

// The compressed file's JSON and buffer in a builder, to be written back
// changed or as GLB.
test::GltfBuilder dracoBuilder() {
  test::GltfBuilder b;
  std::ifstream in(kDraco);
  b.doc = json::parse(in);
  b.bin = test::readBytes(kModels + "draco/2CylinderEngine.bin");
  return b;
}

TEST(DracoImport, TheCompressedEngineIsTheUncompressedOne) {
  ASSERT_TRUE(std::filesystem::exists(kDraco)) << "scripts/install-deps.sh installs assimp-testmodels";
  const SceneStats draco = statsOf(kDraco), plain = statsOf(kPlain);
  EXPECT_EQ(draco.geometryInstances, plain.geometryInstances);
  // Every triangle of non-zero area, and only those (a few of them become
  // slivers of zero area once positions are quantised).
  EXPECT_EQ(draco.uniqueTriangles, properTriangles(kPlain));
  EXPECT_LT(draco.uniqueTriangles, plain.uniqueTriangles) << "the uncompressed file has degenerate triangles";
  // Positions are quantised in the stream: equal bounds to a fraction of the size.
  const float size = glm::length(plain.boundsMax - plain.boundsMin);
  EXPECT_LT(glm::length(draco.boundsMin - plain.boundsMin), 1e-3f * size);
  EXPECT_LT(glm::length(draco.boundsMax - plain.boundsMax), 1e-3f * size);
}

TEST(DracoImport, AGlbCarriesTheStreamsToo) {
  test::TempDir dir;
  dracoBuilder().writeGlb(dir.file("engine.glb"));
  const SceneStats glb = statsOf(dir.file("engine.glb")), gltf = statsOf(kDraco);
  EXPECT_EQ(glb.triangles, gltf.triangles);
  EXPECT_EQ(glb.boundsMin, gltf.boundsMin);
  EXPECT_EQ(glb.boundsMax, gltf.boundsMax);
}

TEST(DracoImport, ABrokenStreamIsRefusedNamingTheExtension) {
  test::TempDir dir;
  test::GltfBuilder b = dracoBuilder();
  const json& view = b.doc["bufferViews"][0];
  const std::size_t offset = view.value("byteOffset", 0), length = view["byteLength"];
  std::fill(b.bin.begin() + std::ptrdiff_t(offset), b.bin.begin() + std::ptrdiff_t(offset + length), std::uint8_t(7));
  b.writeGltf(dir.file("broken.gltf"));
  test::expectRefused(dir.file("broken.gltf"), "mesh 0 primitive 0", "KHR_draco_mesh_compression");
}

TEST(DracoImport, CountsThatDisagreeWithTheStreamAreRefused) {
  test::TempDir dir;
  test::GltfBuilder b = dracoBuilder();
  const int position = b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"];
  b.doc["accessors"][position]["count"] = b.doc["accessors"][position]["count"].get<int>() + 1;
  b.writeGltf(dir.file("count.gltf"));
  test::expectRefused(dir.file("count.gltf"), "vertices, POSITION declares", "KHR_draco_mesh_compression");
}

TEST(DracoImport, AStreamOutsideItsBufferIsRefused) {
  test::TempDir dir;
  test::GltfBuilder b = dracoBuilder();
  b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 999;
  b.writeGltf(dir.file("view.gltf"));
  test::expectRefused(dir.file("view.gltf"), "bufferView 999 does not exist", "KHR_draco_mesh_compression");
}

TEST(DracoImport, ExtensionValuesOfTheWrongKindAreRefused) {
  test::TempDir dir;
  test::GltfBuilder b = dracoBuilder();
  b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"] = 1;
  b.writeGltf(dir.file("number.gltf"));
  test::expectRefused(dir.file("number.gltf"), "needs a bufferView and an attributes object",
                      "KHR_draco_mesh_compression");
  // tinygltf keeps indices as int: 2^32 would have named view 0.
  b = dracoBuilder();
  b.doc["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 4294967296ull;
  b.writeGltf(dir.file("wide.gltf"));
  test::expectRefused(dir.file("wide.gltf"), "bufferView must be an index from 0 to", "KHR_draco_mesh_compression");
}

}  // namespace
}  // namespace tsr::sg
