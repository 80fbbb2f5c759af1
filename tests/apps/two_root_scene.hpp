#pragma once
// A small layered test scene, shared by the local and the cluster layer tests.
#include <cstdint>
#include <string>

namespace tsr::test {

// A glTF scene with two roots: "box" (a wall and, nearer, an occluder over
// its left half) and "markers" (a green quad between them, across the
// middle). Every surface is emissive, so the path tracer needs no light.
inline std::string twoRootScene() {
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
  "buffers": [{"byteLength": 60, "uri": "data:application/octet-stream;base64,)" +
         base64 + R"("}],
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

}  // namespace tsr::test
