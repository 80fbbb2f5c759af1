// EXT_meshopt_compression with KHR_mesh_quantization on import (issue 46):
// Debian's gltfpack compresses the 2CylinderEngine of assimp-testmodels (and
// quantises it, octahedral normals included), the importer decodes it, and
// what it decodes is the engine; broken compressed views are refused with
// errors that name the extension.
#include <cstdlib>
#include <cstring>
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

using ::testing::HasSubstr;

const std::string kEngine = "/usr/share/assimp/models/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb";

SceneStats statsOf(const std::string& path) {
  Scene scene;
  const ImportResult r = importScene(scene, path);
  return computeSceneStats(scene, r.root);
}

// gltfpack's compressed, quantised engine in `dir`, as .glb or .gltf + .bin.
std::string packed(const test::TempDir& dir, const std::string& name) {
  const std::string out = dir.file(name);
  const std::string command = "gltfpack -i '" + kEngine + "' -o '" + out + "' -cc > /dev/null 2>&1";
  EXPECT_EQ(std::system(command.c_str()), 0) << "scripts/install-deps.sh installs gltfpack";
  return out;
}

// The JSON chunk of a GLB, for looking inside.
nlohmann::json glbJson(const std::string& path) {
  const std::vector<std::uint8_t> b = test::readBytes(path);
  std::uint32_t length = 0;
  std::memcpy(&length, &b[12], 4);
  return nlohmann::json::parse(b.begin() + 20, b.begin() + 20 + length);
}

TEST(MeshoptImport, TheCompressedEngineIsTheEngine) {
  test::TempDir dir;
  const std::string glb = packed(dir, "engine.glb");
  const nlohmann::json doc = glbJson(glb);
  ASSERT_THAT(doc["extensionsRequired"].dump(), HasSubstr("EXT_meshopt_compression"));
  ASSERT_THAT(doc["extensionsRequired"].dump(), HasSubstr("KHR_mesh_quantization"));
  ASSERT_THAT(doc.dump(), HasSubstr("OCTAHEDRAL")) << "the normals go through a filter";
  const SceneStats plain = statsOf(kEngine), compressed = statsOf(glb);
  // gltfpack leaves out degenerate triangles (a tenth of this file's).
  EXPECT_LE(compressed.triangles, plain.triangles);
  EXPECT_GT(compressed.triangles, plain.triangles * 85 / 100);
  // Positions are quantised to 14 bits of each mesh's extent.
  const float size = glm::length(plain.boundsMax - plain.boundsMin);
  EXPECT_LT(glm::length(compressed.boundsMin - plain.boundsMin), 1e-3f * size);
  EXPECT_LT(glm::length(compressed.boundsMax - plain.boundsMax), 1e-3f * size);
  // Octahedral normals come out of the filter as unit vectors.
  Scene scene;
  importScene(scene, glb);
  std::size_t normals = 0;
  for (ContainerId id : scene.ids())
    if (const auto* g = scene.find<Geometry>(id))
      for (const Vec3& n : g->normals()) {
        EXPECT_NEAR(glm::length(n), 1.0f, 1e-2f);
        ++normals;
      }
  EXPECT_GT(normals, 50000u);
  // The same through .gltf with an external .bin.
  const SceneStats separate = statsOf(packed(dir, "engine.gltf"));
  EXPECT_EQ(separate.triangles, compressed.triangles);
}

// The compressed file's JSON and binary chunk in a builder, to be changed.
test::GltfBuilder packedBuilder(const test::TempDir& dir) {
  const std::string glb = packed(dir, "source.glb");
  test::GltfBuilder b;
  b.doc = glbJson(glb);
  const std::vector<std::uint8_t> bytes = test::readBytes(glb);
  std::uint32_t jsonLength = 0, binLength = 0;
  std::memcpy(&jsonLength, &bytes[12], 4);
  std::memcpy(&binLength, &bytes[20 + jsonLength], 4);
  b.bin.assign(bytes.begin() + 28 + jsonLength, bytes.begin() + 28 + jsonLength + binLength);
  // writeGlb writes the binary chunk as the one buffer: the fallback buffer
  // goes, and the compressed views say where their bytes are themselves.
  return b;
}

TEST(MeshoptImport, BrokenCompressedViewsAreRefused) {
  test::TempDir dir;
  {
    test::GltfBuilder b = packedBuilder(dir);
    auto& e = b.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
    const std::size_t offset = e.value("byteOffset", 0), length = e["byteLength"];
    std::fill(b.bin.begin() + std::ptrdiff_t(offset), b.bin.begin() + std::ptrdiff_t(offset + length), 0xFF);
    b.writeGlb(dir.file("garbage.glb"));
    test::expectRefused(dir.file("garbage.glb"), "EXT_meshopt_compression): the compressed bytes do not decode",
                        "EXT_meshopt_compression");
  }
  {
    test::GltfBuilder b = packedBuilder(dir);
    auto& e = b.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"];
    e["count"] = e["count"].get<std::uint64_t>() * 1000;  // more than the view holds
    b.writeGlb(dir.file("count.glb"));
    test::expectRefused(dir.file("count.glb"), "do not fit the view's", "EXT_meshopt_compression");
  }
  {
    test::GltfBuilder b = packedBuilder(dir);
    b.doc["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]["mode"] = "PACKED";
    b.writeGlb(dir.file("mode.glb"));
    test::expectRefused(dir.file("mode.glb"), "mode 'PACKED' is none of ATTRIBUTES, TRIANGLES, INDICES",
                        "EXT_meshopt_compression");
  }
}

}  // namespace
}  // namespace tsr::sg
