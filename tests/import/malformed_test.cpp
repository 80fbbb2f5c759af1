#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <glm/gtc/matrix_transform.hpp>

#include "test_scenes.hpp"
#include "tsr/sg/import/importer.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

// A scene that already holds something, committed, to check that failed
// imports leave it exactly as it was.
class MalformedFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    auto& g = scene.create<Group>("existing");
    auto& t = scene.create<Transform>("existing transform");
    t.setMatrix(glm::translate(Mat4(1.0f), Vec3(1, 2, 3)));
    g.addChild(t.id());
    scene.create<SurfaceMaterial>("existing material");
    scene.commit();
    hash = scene.contentHash();
    size = scene.size();
  }

  // Imports `path`, expecting an ImportError naming the file and containing
  // `problem`, and the scene untouched.
  void expectRejected(const std::string& path, const std::string& problem, const ImportOptions& options = {}) {
    try {
      importScene(scene, path, options);
      ADD_FAILURE() << path << " was accepted; expected: " << problem;
    } catch (const ImportError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path));
      EXPECT_THAT(e.what(), HasSubstr(problem));
      EXPECT_EQ(e.source(), path);
    }
    EXPECT_EQ(scene.size(), size);
    EXPECT_EQ(scene.contentHash(), hash);
    EXPECT_FALSE(scene.hasPendingChanges());
  }

  void expectRejected(test::GltfBuilder b, const std::string& name, const std::string& problem) {
    const std::string path = dir.file(name);
    b.writeGltf(path);
    expectRejected(path, problem);
  }

  test::TempDir dir;
  Scene scene;
  std::uint64_t hash = 0;
  std::size_t size = 0;
};

TEST_F(MalformedFiles, AccessorBeyondItsBufferView) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["accessors"][0]["count"] = 4;
  expectRejected(b, "count.gltf", "reads bytes [0, 48) of buffer view 0, which has 36 bytes");
  b = test::tinyScene();
  b.doc["accessors"][0]["byteOffset"] = 8;
  expectRejected(b, "offset.gltf", "buffer view 0");
  b = test::tinyScene();
  b.doc["bufferViews"][0]["byteStride"] = 16;
  expectRejected(b, "stride.gltf", "accessor 0");
}

TEST_F(MalformedFiles, BufferViewBeyondItsBuffer) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["bufferViews"][1]["byteOffset"] = 4096;
  expectRejected(b, "view.gltf", "buffer view 1 covers bytes");
}

TEST_F(MalformedFiles, IndexOutOfRangeOfTheVertices) {
  test::GltfBuilder b;
  const int pos = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int idx = b.addIndices(std::vector<std::uint16_t>{0, 1, 3});
  b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}}}};
  b.doc["nodes"] = {{{"mesh", 0}}};
  expectRejected(b, "indices.gltf", "index 2 is 3, but there are only 3 vertices");
}

TEST_F(MalformedFiles, MissingFiles) {
  expectRejected(dir.file("nothing-here.gltf"), "no such file");
  test::GltfBuilder b = test::tinyScene();
  b.writeGltf(dir.file("nobin.gltf"));
  std::filesystem::remove(dir.file("nobin.bin"));
  expectRejected(dir.file("nobin.gltf"), "nobin.bin");
  b = test::tinyScene();
  b.doc["images"] = {{{"uri", "absent.png"}}};
  b.doc["textures"] = {{{"source", 0}}};
  expectRejected(b, "noimage.gltf", "image 0 ('absent.png'): file missing");
}

TEST_F(MalformedFiles, CyclicNodeGraphs) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["nodes"].push_back({{"children", {2}}});
  b.doc["nodes"].push_back({{"children", {1}}});
  expectRejected(b, "cycle.gltf", "cyclic node graph");
  b = test::tinyScene();
  b.doc["nodes"][0]["children"] = {0};
  expectRejected(b, "self.gltf", "node 0 is its own child");
}

TEST_F(MalformedFiles, NodeWithTwoParents) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["nodes"].push_back({{"children", {0}}});
  b.doc["nodes"].push_back({{"children", {0}}});
  expectRejected(b, "parents.gltf", "node 0 is a child of two parents (nodes 1 and 2)");
}

TEST_F(MalformedFiles, NonFiniteNumbers) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  test::GltfBuilder b;
  const int pos = b.addFloats({0, 0, 0, 1, nan, 0, 0, 1, 0}, "VEC3");
  b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}}}}}};
  b.doc["nodes"] = {{{"mesh", 0}}};
  expectRejected(b, "nan.gltf", "element 1 is not finite");

  // JSON has no NaN, but numbers beyond float range become infinite.
  b = test::tinyScene();
  b.doc["nodes"][0].erase("translation");
  b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1e39, 0, 0, 1};
  expectRejected(b, "matrix.gltf", "node 0 matrix is not finite");
  b = test::tinyScene();
  b.doc["nodes"][0]["translation"] = {0.0, -1e300, 0.0};
  expectRejected(b, "trs.gltf", "node 0 translation is not finite");

  b = test::tinyScene();
  const int times = b.addFloats({0, 1}, "SCALAR");
  const int values = b.addFloats({0, 0, 0, std::numeric_limits<float>::infinity(), 0, 0}, "VEC3");
  b.doc["animations"] = {{{"samplers", {{{"input", times}, {"output", values}}}},
                          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}};
  expectRejected(b, "anim.gltf", "animation 0 channel 0 output");
}

// Found by mutating real files: finite but huge coordinates passed every
// check and aborted Embree ("Assertion 'ray.valid()' failed").
TEST_F(MalformedFiles, CoordinatesBeyondWhatRenderersTrace) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  b.doc["nodes"].push_back({{"camera", 0}, {"translation", {0.0, 0.0, -1e20}}});
  b.doc["scenes"][0]["nodes"].push_back(1);
  expectRejected(b, "far-camera.gltf", "node 1 translation -1e+20 is beyond 1e+12");

  b = test::tinyScene();
  b.doc["nodes"][0].erase("translation");
  b.doc["nodes"][0]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -2.7e38, 1};
  expectRejected(b, "far-matrix.gltf", "node 0 matrix -2.7e+38 is beyond 1e+12");

  b = test::GltfBuilder();
  const int pos = b.addFloats({0, 0, 0, 5e12f, 0, 0, 0, 1, 0}, "VEC3");
  b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}}}}}};
  b.doc["nodes"] = {{{"mesh", 0}}};
  expectRejected(b, "far-vertex.gltf", "mesh 0 primitive 0 POSITION 1 coordinate 5e+12 is beyond 1e+12");

  // Each matrix within the limit, their composition not.
  b = test::tinyScene();
  b.doc["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  b.doc["nodes"][0]["scale"] = {1e7, 1e7, 1e7};
  b.doc["nodes"][0]["children"] = {1};
  b.doc["nodes"].push_back({{"camera", 0}, {"translation", {0.0, 0.0, 1e6}}});
  expectRejected(b, "composed.gltf", "node 1 places its camera at 1e+13");

  b = test::tinyScene();
  const int times = b.addFloats({0, 1}, "SCALAR");
  const int values = b.addFloats({0, 0, 0, 0, 3e15f, 0}, "VEC3");
  b.doc["animations"] = {{{"samplers", {{{"input", times}, {"output", values}}}},
                          {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}};
  expectRejected(b, "far-animation.gltf", "animation 0 channel 0 output value 3e+15 is beyond 1e+12");

  // At the limit is fine.
  b = test::tinyScene();
  b.doc["nodes"][0]["translation"] = {0.0, 1e12, 0.0};
  b.writeGltf(dir.file("edge.gltf"));
  EXPECT_NO_THROW(importScene(scene, dir.file("edge.gltf")));
}

// A 300 MB file of 100 million array elements took 4 GB and 17 s to refuse.
// Limits refuse it before anything is parsed; both name what they count.
TEST_F(MalformedFiles, OversizedInputsAreRefusedBeforeParsing) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["extras"] = json::array();
  for (int i = 0; i < 1000; ++i) b.doc["extras"].push_back(i);
  const std::string gltf = dir.file("many.gltf"), glb = dir.file("many.glb");
  b.writeGltf(gltf);
  b.writeGlb(glb);
  ImportOptions few;
  few.maxJsonValues = 500;
  for (const std::string& path : {gltf, glb}) {
    expectRejected(path, "the JSON holds more than 500 values", few);
    try {
      importScene(scene, path, few);
    } catch (const ImportLimitError& e) {
      EXPECT_EQ(e.limit(), ImportLimitError::Limit::JsonValues);
    }
  }
  ImportOptions small;
  small.maxFileBytes = 1000;
  expectRejected(gltf, "bytes, more than the limit of 1000 bytes", small);
  try {
    importScene(scene, gltf, small);
  } catch (const ImportLimitError& e) {
    EXPECT_EQ(e.limit(), ImportLimitError::Limit::FileBytes);
  }
  // Malformed JSON is still reported as such by the scan.
  test::writeText(dir.file("broken.gltf"), R"({"asset": {"version": "2.0"}, "nodes": [1, 2,)");
  expectRejected(dir.file("broken.gltf"), "invalid JSON", few);
  // The defaults take it.
  EXPECT_NO_THROW(importScene(scene, gltf));
}

TEST_F(MalformedFiles, WrongJsonTypes) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["nodes"][0]["mesh"] = "zero";
  expectRejected(b, "type1.gltf", "glTF.nodes[0].mesh must be a non-negative integer index");
  b = test::tinyScene();
  b.doc["nodes"][0]["translation"] = {1, 2};
  expectRejected(b, "type2.gltf", "glTF.nodes[0].translation must be an array of 3 numbers");
  b = test::tinyScene();
  b.doc["accessors"] = json::object();
  expectRejected(b, "type3.gltf", "glTF.accessors must be an array");
  test::writeText(dir.file("garbage.gltf"), "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [");
  expectRejected(dir.file("garbage.gltf"), "invalid JSON");
}

TEST_F(MalformedFiles, UnsupportedRequiredExtensions) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
  b.doc["extensionsRequired"] = {"EXT_mesh_gpu_instancing"};
  expectRejected(b, "instancing.gltf", "required extension EXT_mesh_gpu_instancing is not supported");
}

TEST_F(MalformedFiles, InvalidIndices) {
  test::GltfBuilder b = test::tinyScene();
  b.doc["nodes"][0]["mesh"] = 42;
  expectRejected(b, "mesh.gltf", "node 0 names mesh 42, but there are 1");
  b = test::tinyScene();
  b.doc["meshes"][0]["primitives"][0]["material"] = 3;
  expectRejected(b, "material.gltf", "mesh 0 primitive 0 names material 3, but there are 0");
  b = test::tinyScene();
  b.doc["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 9;
  expectRejected(b, "accessor.gltf", "names accessor 9, but there are 2 accessors");
  b = test::tinyScene();
  b.doc["images"] = {{{"uri", "data:image/png;base64,AAAA"}}};
  b.doc["textures"] = {{{"source", 5}}};
  expectRejected(b, "image.gltf", "texture 0 names image 5, but there are 1");
  b = test::tinyScene();
  b.doc["scenes"] = {{{"nodes", {7}}}};
  expectRejected(b, "scene.gltf", "scene 0 names node 7");
}

TEST_F(MalformedFiles, BrokenGlbContainers) {
  test::GltfBuilder b = test::tinyScene();
  b.writeGlb(dir.file("ok.glb"));
  std::vector<std::uint8_t> bytes = test::readBytes(dir.file("ok.glb"));
  std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(bytes.size() / 2));
  test::writeBytes(dir.file("cut.glb"), cut);
  expectRejected(dir.file("cut.glb"), "GLB header says");
  bytes[12] = 0xFF;  // JSON chunk longer than the file
  bytes[13] = 0xFF;
  test::writeBytes(dir.file("json.glb"), bytes);
  expectRejected(dir.file("json.glb"), "GLB JSON chunk runs past the end");
}

// Random edits of a valid document: every import either succeeds or throws
// ImportError; anything else (a crash, another exception) fails the test.
TEST_F(MalformedFiles, RandomMutationsNeverCrash) {
  test::GltfBuilder base = test::richScene(dir);
  base.writeGltf(dir.file("base.gltf"), true);
  const json original = json::parse(test::readBytes(dir.file("base.gltf")));

  std::mt19937 rng(1234);
  const json replacements[] = {json(-1),     json(0),       json(4294967296LL), json(1e300),    json(-1e300),
                               json("text"), json(nullptr), json::array(),      json::object(), json(true),
                               json(7),      json(2.5)};
  int accepted = 0, rejected = 0;
  for (int iteration = 0; iteration < 300; ++iteration) {
    json doc = original;
    const int edits = 1 + static_cast<int>(rng() % 3);
    for (int e = 0; e < edits; ++e) {
      // Pick a random value in the tree, but never the large data URIs.
      std::vector<json::json_pointer> pointers;
      std::function<void(const json&, const json::json_pointer&)> collect = [&](const json& v,
                                                                                const json::json_pointer& p) {
        if (p.back() != "uri") pointers.push_back(p);
        if (v.is_object())
          for (auto it = v.begin(); it != v.end(); ++it) collect(it.value(), p / it.key());
        if (v.is_array())
          for (std::size_t i = 0; i < v.size(); ++i) collect(v[i], p / i);
      };
      for (auto it = doc.begin(); it != doc.end(); ++it) collect(it.value(), json::json_pointer("/" + it.key()));
      const json::json_pointer target = pointers[rng() % pointers.size()];
      if (rng() % 3 == 0) {
        json& parent = doc[target.parent_pointer()];
        if (parent.is_object())
          parent.erase(target.back());
        else if (parent.is_array() && !parent.empty())
          parent.erase(parent.size() - 1);
      } else {
        doc[target] = replacements[rng() % std::size(replacements)];
      }
    }
    const std::string path = dir.file("fuzz.gltf");
    test::writeText(path, doc.dump());
    try {
      importScene(scene, path);
      ++accepted;
      scene.commit();
    } catch (const ImportError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path));
      EXPECT_FALSE(scene.hasPendingChanges());
      ++rejected;
    }
  }
  EXPECT_GT(rejected, 0);
  EXPECT_GT(accepted, 0);
}

}  // namespace
}  // namespace tsr::sg
