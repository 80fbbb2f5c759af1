// External files resolve inside the glTF's folder only: uris that stay in
// it load, whatever their spelling; the same bytes reached by a uri that
// leaves it, an absolute path or a scheme are refused, from files and from
// memory alike.
#include <gtest/gtest.h>

#include "gltf_writer.hpp"
#include "test_scenes.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace {

using namespace tsr::test;

// tiny.gltf in dir/scene whose buffer uri is `uri`; the buffer lies in
// dir/scene/data/tiny.bin and dir/tiny.bin.
std::string sceneWithBufferAt(const TempDir& dir, const std::string& uri) {
  std::filesystem::create_directories(dir.path() / "scene" / "data");
  GltfBuilder b = tinyScene();
  b.writeGltf(dir.file("scene/data/tiny.gltf"));
  b.writeGltf(dir.file("tiny.gltf"));
  b.doc["buffers"] = {{{"byteLength", b.bin.size()}, {"uri", uri}}};
  writeText(dir.file("scene/tiny.gltf"), b.doc.dump());
  return dir.file("scene/tiny.gltf");
}

TEST(UriConfinement, UrisInsideTheFolderLoad) {
  for (const std::string uri : {"data/tiny.bin", "./data/tiny.bin", "data/../data/tiny.bin", "data%2Ftiny.bin"}) {
    TempDir dir;
    tsr::sg::Scene scene;
    EXPECT_NO_THROW(tsr::sg::importScene(scene, sceneWithBufferAt(dir, uri))) << uri;
  }
}

TEST(UriConfinement, UrisLeavingTheFolderAreRefusedBeforeReading) {
  TempDir dir;
  const std::string outside = dir.file("tiny.bin");
  for (const std::string& uri :
       std::vector<std::string>{"../tiny.bin", "data/../../tiny.bin", "..%2Ftiny.bin", "..\\tiny.bin", outside,
                                "file://" + outside, "FILE:" + outside}) {
    tsr::sg::Scene scene;
    try {
      tsr::sg::importScene(scene, sceneWithBufferAt(dir, uri));
      ADD_FAILURE() << uri << " was read";
    } catch (const tsr::sg::ImportError& e) {
      EXPECT_NE(std::string(e.what()).find("refused, not read"), std::string::npos) << e.what();
    }
  }
}

TEST(UriConfinement, BytesInMemoryResolveInTheirBaseFolderOnly) {
  TempDir dir;
  const std::string path = sceneWithBufferAt(dir, "data/tiny.bin");
  const auto bytes = readBytes(path);
  tsr::sg::Scene inside, elsewhere;
  EXPECT_EQ(tsr::sg::importGltf(inside, bytes, "memory", dir.file("scene")).counts.uniqueTriangles, 1u);
  // Against another base the buffer is not there (tinygltf would go on to
  // search the working directory; nothing outside the base is opened).
  EXPECT_THROW(tsr::sg::importGltf(elsewhere, bytes, "memory", dir.file("scene/data")), tsr::sg::ImportError);
}

}  // namespace
