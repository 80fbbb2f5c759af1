#include "test_scenes.hpp"

namespace tsr::test {

const std::vector<std::uint8_t> kFilePixels = {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 255, 10, 20, 30, 40};
const std::vector<std::uint8_t> kUriPixels = {1, 2, 3, 200, 150, 100};

GltfBuilder richScene(const TempDir& dir) {
  GltfBuilder b;
  using nlohmann::json;

  // Mesh 0: interleaved position (12 bytes) + uv (8 bytes), stride 20.
  std::vector<float> interleaved = {0, 0, 0, 0, 1, 1, 0, 0, 1, 1, 1, 1, 0, 1, 0, 0, 1, 0, 0, 0};
  const int quadView = b.addView(interleaved, 20);
  const int quadPos = b.addAccessor(quadView, kFloat, 4, "VEC3");
  const int quadUv = b.addAccessor(quadView, kFloat, 4, "VEC2", false, 12);
  const int quadIdx = b.addIndices(std::vector<std::uint16_t>{0, 1, 2, 0, 2, 3});

  // Mesh 1: normals given, normalized u8 colours and u16 uvs.
  const int triPos = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int triNrm = b.addFloats({0, 0, 1, 0, 0, 1, 0, 0, 1}, "VEC3");
  const int triCol = b.addAccessor(b.addView(std::vector<std::uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 51}),
                                   kUByte, 3, "VEC4", true);
  const int triUv =
      b.addAccessor(b.addView(std::vector<std::uint16_t>{0, 0, 65535, 0, 0, 65535}), kUShort, 3, "VEC2", true);
  const int triIdx = b.addIndices(std::vector<std::uint8_t>{0, 1, 2});

  // Mesh 2: five points used by a strip, a fan and points; a loose triangle.
  const int stripPos = b.addFloats({0, 0, 0, 0, 1, 0, 1, 0, 0, 1, 1, 0, 2, 0, 0}, "VEC3");
  const int stripIdx = b.addIndices(std::vector<std::uint32_t>{0, 1, 2, 3, 4});
  const int fanIdx = b.addIndices(std::vector<std::uint8_t>{0, 1, 3, 4, 2});
  const int loosePos = b.addFloats({5, 5, 5, 6, 5, 5, 5, 6, 5}, "VEC3");
  const int looseCol = b.addFloats({1, 0, 0, 0, 1, 0, 0, 0, 1}, "VEC3");

  b.doc["meshes"] = json::array({
      {{"name", "quad"},
       {"primitives",
        {{{"attributes", {{"POSITION", quadPos}, {"TEXCOORD_0", quadUv}}}, {"indices", quadIdx}, {"material", 0}}}}},
      {{"name", "triangle"},
       {"primitives",
        {{{"attributes", {{"POSITION", triPos}, {"NORMAL", triNrm}, {"COLOR_0", triCol}, {"TEXCOORD_0", triUv}}},
          {"indices", triIdx},
          {"material", 1}}}}},
      {{"name", "strips"},
       {"primitives",
        {{{"attributes", {{"POSITION", stripPos}}}, {"indices", stripIdx}, {"mode", 5}},
         {{"attributes", {{"POSITION", stripPos}}}, {"indices", fanIdx}, {"mode", 6}},
         {{"attributes", {{"POSITION", stripPos}}}, {"mode", 0}},
         {{"attributes", {{"POSITION", loosePos}, {"COLOR_0", looseCol}}}}}}},
  });

  writePng(dir.file("tex.png"), 2, 2, 4, kFilePixels);
  writePng(dir.file("uri.png"), 2, 1, 3, kUriPixels);
  const std::string uri = "data:image/png;base64," + base64(readBytes(dir.file("uri.png")));
  std::filesystem::remove(dir.file("uri.png"));
  b.doc["images"] = json::array({{{"uri", "tex.png"}}, {{"uri", uri}}});
  b.doc["textures"] = json::array({{{"source", 0}}, {{"source", 1}}});
  b.doc["materials"] = json::array({
      {{"name", "fancy"},
       {"pbrMetallicRoughness",
        {{"baseColorFactor", {0.5, 0.25, 1.0, 0.5}},
         {"baseColorTexture", {{"index", 0}}},
         {"metallicFactor", 0.3},
         {"roughnessFactor", 0.7}}},
       {"alphaMode", "BLEND"},
       {"emissiveFactor", {1.0, 0.5, 0.0}},
       {"normalTexture", {{"index", 1}, {"scale", 0.5}}},
       {"extensions",
        {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}},
         {"KHR_materials_transmission", {{"transmissionFactor", 0.8}}},
         {"KHR_materials_ior", {{"ior", 1.33}}}}}},
      {{"name", "plain"},
       {"pbrMetallicRoughness", {{"metallicRoughnessTexture", {{"index", 1}}}}},
       {"emissiveTexture", {{"index", 0}}}},
  });
  b.doc["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_emissive_strength", "KHR_materials_transmission",
                             "KHR_materials_ior"};
  b.doc["extensionsRequired"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({
      {{"type", "point"}, {"color", {1.0, 0.5, 0.25}}, {"intensity", 20.0}, {"range", 7.0}},
      {{"type", "spot"}, {"intensity", 5.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 0.6}}}},
      {{"type", "directional"}, {"intensity", 3.0}},
  });
  b.doc["cameras"] =
      json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.5}, {"zfar", 200.0}}}}});
  b.doc["nodes"] = json::array({
      {{"name", "parent"}, {"translation", {10.0, 0.0, 0.0}}, {"children", {1, 2, 5}}},
      {{"name", "childA"}, {"translation", {0.0, 5.0, 0.0}}, {"mesh", 0}},
      {{"name", "childB"}, {"scale", {2.0, 2.0, 2.0}}, {"mesh", 0}},
      {{"name", "matrix"},
       {"matrix", {0, 1, 0, 0, -1, 0, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1}},  // 90 degrees about z, then z -= 3
       {"mesh", 1}},
      {{"name", "strips"}, {"mesh", 2}},
      {{"name", "camera"}, {"translation", {0.0, 0.0, 10.0}}, {"camera", 0}},
      {{"name", "point"}, {"translation", {0.0, 3.0, 0.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}},
      {{"name", "spot"}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}},
      {{"name", "sun"}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}},
  });
  b.doc["scene"] = 0;
  b.doc["scenes"] = json::array({{{"nodes", {0, 3, 4, 6, 7, 8}}}});
  return b;
}

GltfBuilder tinyScene() {
  GltfBuilder b;
  const int pos = b.addFloats({0, 0, 0, 1, 0, 0, 0, 1, 0}, "VEC3");
  const int idx = b.addIndices(std::vector<std::uint16_t>{0, 1, 2});
  b.doc["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", pos}}}, {"indices", idx}}}}}};
  b.doc["nodes"] = {{{"name", "node"}, {"mesh", 0}, {"translation", {1.0, 2.0, 3.0}}}};
  b.doc["scenes"] = {{{"nodes", {0}}}};
  return b;
}

}  // namespace tsr::test
