#pragma once
// A small glTF written by the tests: a grey floor and two boxes with no
// lights, no emissive material and no environment (so the default light rig
// applies), three cameras ("front", "top", and "tracking" under the
// animated node "dolly", which moves 2 units along +X in one second).
// With `sun`, a directional light of its own stands still (the default rig
// follows the camera, so it moves whenever the camera does).
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tsr::test {

inline std::string base64(const std::vector<std::uint8_t>& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t v = std::uint32_t(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= std::uint32_t(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) v |= bytes[i + 2];
    out += digits[(v >> 18) & 63];
    out += digits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(v >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[v & 63] : '=';
  }
  return out;
}

// The eye of camera "front" (it looks down -Z), of "tracking" at time 0,
// and the vertical field of view all three share.
inline constexpr float kFrontEye[3] = {0.0f, 1.5f, 6.0f};
inline constexpr float kCameraYfov = 0.8f;

inline void writeLitSceneGltf(const std::string& path, bool sun = false) {
  std::vector<std::uint8_t> bin;
  nlohmann::json views = nlohmann::json::array(), accessors = nlohmann::json::array();
  auto add = [&](const std::vector<float>& values, const char* type, int components, bool bounds) {
    const std::size_t offset = bin.size();
    bin.resize(offset + values.size() * 4);
    std::memcpy(bin.data() + offset, values.data(), values.size() * 4);
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * 4}});
    nlohmann::json a = {{"bufferView", views.size() - 1},
                        {"componentType", 5126},
                        {"count", values.size() / components},
                        {"type", type}};
    if (bounds) {
      std::vector<float> lo(components, 1e30f), hi(components, -1e30f);
      for (std::size_t i = 0; i < values.size(); ++i) {
        lo[i % components] = std::min(lo[i % components], values[i]);
        hi[i % components] = std::max(hi[i % components], values[i]);
      }
      a["min"] = lo;
      a["max"] = hi;
    }
    accessors.push_back(a);
    return int(accessors.size() - 1);
  };
  auto addIndices = [&](const std::vector<std::uint32_t>& values) {
    const std::size_t offset = bin.size();
    bin.resize(offset + values.size() * 4);
    std::memcpy(bin.data() + offset, values.data(), values.size() * 4);
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", values.size() * 4}});
    accessors.push_back(
        {{"bufferView", views.size() - 1}, {"componentType", 5125}, {"count", values.size()}, {"type", "SCALAR"}});
    return int(accessors.size() - 1);
  };
  // A unit cube centred at the origin, four vertices a face with its normal.
  std::vector<float> p, n;
  std::vector<std::uint32_t> idx;
  // Each face: its normal a and two edges with t1 x t2 = a.
  const float faces[6][3][3] = {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
                                {{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
                                {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}};
  for (const auto& [a, t1, t2] : faces) {
    const std::uint32_t base = std::uint32_t(p.size() / 3);
    const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& c : corners)
      for (int k = 0; k < 3; ++k) {
        p.push_back(0.5f * (a[k] + c[0] * t1[k] + c[1] * t2[k]));
        n.push_back(a[k]);
      }
    // Counter-clockwise seen from outside: t1 x t2 = a.
    for (std::uint32_t k : {0u, 1u, 2u, 0u, 2u, 3u}) idx.push_back(base + k);
  }
  const int boxP = add(p, "VEC3", 3, true), boxN = add(n, "VEC3", 3, false), boxI = addIndices(idx);
  const int floorP = add({-3, 0, 3, 3, 0, 3, 3, 0, -3, -3, 0, -3}, "VEC3", 3, true);
  const int floorN = add({0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0}, "VEC3", 3, false);
  const int floorI = addIndices({0, 1, 2, 0, 2, 3});
  const int times = add({0.0f, 1.0f}, "SCALAR", 1, true), moves = add({0, 0, 0, 2, 0, 0}, "VEC3", 3, false);

  nlohmann::json doc;
  doc["asset"] = {{"version", "2.0"}};
  auto diffuse = [](float r, float g, float b) {
    return nlohmann::json{{"pbrMetallicRoughness",
                           {{"baseColorFactor", {r, g, b, 1.0}}, {"metallicFactor", 0.0}, {"roughnessFactor", 1.0}}}};
  };
  doc["materials"] = {diffuse(0.8f, 0.8f, 0.8f), diffuse(0.8f, 0.25f, 0.2f)};
  doc["meshes"] = {
      {{"primitives",
        {{{"attributes", {{"POSITION", floorP}, {"NORMAL", floorN}}}, {"indices", floorI}, {"material", 0}}}}},
      {{"primitives", {{{"attributes", {{"POSITION", boxP}, {"NORMAL", boxN}}}, {"indices", boxI}, {"material", 1}}}}}};
  auto camera = [](const char* name) {
    return nlohmann::json{{"name", name},
                          {"type", "perspective"},
                          {"perspective", {{"yfov", kCameraYfov}, {"znear", 0.05}, {"zfar", 100.0}}}};
  };
  doc["cameras"] = {camera("front"), camera("top"), camera("tracking")};
  const std::vector<float> eye(kFrontEye, kFrontEye + 3);
  doc["nodes"] = {{{"name", "floor"}, {"mesh", 0}},
                  {{"name", "box a"}, {"mesh", 1}, {"translation", {-0.8, 0.5, 0.0}}},
                  {{"name", "box b"}, {"mesh", 1}, {"translation", {0.9, 0.75, -0.4}}, {"scale", {1.0, 1.5, 1.0}}},
                  {{"name", "front camera"}, {"camera", 0}, {"translation", eye}},
                  // Looking straight down (-90 degrees about X).
                  {{"name", "top camera"},
                   {"camera", 1},
                   {"translation", {0.0, 8.0, 0.0}},
                   {"rotation", {-0.70710678, 0.0, 0.0, 0.70710678}}},
                  {{"name", "dolly"}, {"children", {6}}},
                  {{"name", "tracking camera"}, {"camera", 2}, {"translation", eye}}};
  doc["scenes"] = {{{"nodes", {0, 1, 2, 3, 4, 5}}}};
  if (sun) {
    doc["extensionsUsed"] = {"KHR_lights_punctual"};
    doc["extensions"] = {
        {"KHR_lights_punctual", {{"lights", {{{"type", "directional"}, {"intensity", 3.0}, {"color", {1, 1, 1}}}}}}}};
    // Pointing down and away from the front camera (-60 degrees about X).
    doc["nodes"].push_back({{"name", "sun"},
                            {"rotation", {-0.5, 0.0, 0.0, 0.8660254}},
                            {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    doc["scenes"][0]["nodes"].push_back(7);
  }
  doc["scene"] = 0;
  nlohmann::json sampler = {{"input", times}, {"output", moves}, {"interpolation", "LINEAR"}};
  nlohmann::json channel = {{"sampler", 0}, {"target", {{"node", 5}, {"path", "translation"}}}};
  nlohmann::json animation = {{"name", "dolly move"}};
  animation["samplers"] = nlohmann::json::array({sampler});
  animation["channels"] = nlohmann::json::array({channel});
  doc["animations"] = nlohmann::json::array({animation});
  doc["bufferViews"] = views;
  doc["accessors"] = accessors;
  doc["buffers"] = {{{"byteLength", bin.size()}, {"uri", "data:application/octet-stream;base64," + base64(bin)}}};
  std::ofstream(path) << doc.dump();
}

}  // namespace tsr::test
