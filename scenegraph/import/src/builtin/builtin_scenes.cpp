#include "builtin/builtin_scenes.hpp"

#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "builtin/builtin_assembly.hpp"
#include "builtin/mesh_shapes.hpp"

namespace tsr::sg::builtin {
namespace {

struct Quad {
  int material;
  Vec3 corners[4];
};
enum CornellMaterial { kWhite, kRed, kGreen, kLight, kMirror, kGlass, kCornellMaterialCount };

// The geometry of make_cornell.py (Embree's tutorial data), same winding.
const Quad kCornellQuads[] = {
    {kWhite, {{552.8f, 0, 0}, {0, 0, 0}, {0, 0, 559.2f}, {549.6f, 0, 559.2f}}},
    {kWhite, {{556, 548.8f, 0}, {556, 548.8f, 559.2f}, {0, 548.8f, 559.2f}, {0, 548.8f, 0}}},
    {kWhite, {{549.6f, 0, 559.2f}, {0, 0, 559.2f}, {0, 548.8f, 559.2f}, {556, 548.8f, 559.2f}}},
    {kGreen, {{0, 0, 559.2f}, {0, 0, 0}, {0, 548.8f, 0}, {0, 548.8f, 559.2f}}},
    {kRed, {{552.8f, 0, 0}, {549.6f, 0, 559.2f}, {556, 548.8f, 559.2f}, {556, 548.8f, 0}}},
    {kWhite, {{130, 165, 65}, {82, 165, 225}, {240, 165, 272}, {290, 165, 114}}},
    {kWhite, {{290, 0, 114}, {290, 165, 114}, {240, 165, 272}, {240, 0, 272}}},
    {kWhite, {{130, 0, 65}, {130, 165, 65}, {290, 165, 114}, {290, 0, 114}}},
    {kWhite, {{82, 0, 225}, {82, 165, 225}, {130, 165, 65}, {130, 0, 65}}},
    {kWhite, {{240, 0, 272}, {240, 165, 272}, {82, 165, 225}, {82, 0, 225}}},
    {kWhite, {{423, 330, 247}, {265, 330, 296}, {314, 330, 456}, {472, 330, 406}}},
    {kWhite, {{423, 0, 247}, {423, 330, 247}, {472, 330, 406}, {472, 0, 406}}},
    {kWhite, {{472, 0, 406}, {472, 330, 406}, {314, 330, 456}, {314, 0, 456}}},
    {kWhite, {{314, 0, 456}, {314, 330, 456}, {265, 330, 296}, {265, 0, 296}}},
    {kWhite, {{265, 0, 296}, {265, 330, 296}, {423, 330, 247}, {423, 0, 247}}},
    // The light: a small quad just below the ceiling, facing down.
    {kLight, {{343, 548.3f, 227}, {343, 548.3f, 332}, {213, 548.3f, 332}, {213, 548.3f, 227}}},
};
const Vec3 kEye(278, 273, -800), kAt(278, 273, 0);
constexpr float kFovDegrees = 37.0f;

parsed::Scene cornellBox() {
  parsed::Scene s;
  s.metresPerUnit = 0.001f;  // the classic data's millimetres
  s.materials.resize(kCornellMaterialCount);
  auto diffuse = [](std::string name, Vec3 c) { return material(std::move(name), c, 0.0f, 1.0f); };
  s.materials[kWhite] = diffuse("white", Vec3(1, 1, 1));
  s.materials[kRed] = diffuse("red", Vec3(1, 0, 0));
  s.materials[kGreen] = diffuse("green", Vec3(0, 1, 0));
  // Radiance chosen so the white floor under it reflects roughly 0.5.
  s.materials[kLight] = diffuse("light", Vec3(0.78f));
  s.materials[kLight].emission = Vec3(1.0f, 0.9f, 0.75f);
  s.materials[kLight].emissionStrength = 40.0f;
  s.materials[kMirror] = material("mirror", Vec3(1), 1.0f, 0.0f);
  s.materials[kGlass] = material("glass", Vec3(1), 0.0f, 0.0f);
  s.materials[kGlass].transmission = 1.0f;
  s.materials[kGlass].ior = 1.5f;

  // One mesh per material, as make_cornell.py groups them.
  for (int material : {kWhite, kRed, kGreen, kLight}) {
    parsed::Primitive p;
    for (const Quad& q : kCornellQuads)
      if (q.material == material) shapes::appendQuad(p, q.corners[0], q.corners[1], q.corners[2], q.corners[3]);
    const int mesh = addMesh(s, std::move(p), material, s.materials[static_cast<std::size_t>(material)].name);
    addNode(s, s.meshes[static_cast<std::size_t>(mesh)].name, Mat4(1.0f), mesh);
  }
  const int mirror = addMesh(s, shapes::sphere(Vec3(368, 410, 351), 80, 24), kMirror, "mirror sphere");
  addNode(s, "mirror sphere", Mat4(1.0f), mirror);
  const int glass = addMesh(s, shapes::sphere(Vec3(186, 235, 169), 70, 24), kGlass, "glass sphere");
  addNode(s, "glass sphere", Mat4(1.0f), glass);
  addCamera(s, kEye, kAt, kFovDegrees, 1.0f, 10000.0f);
  return s;
}

Animation::Pose translated(const Vec3& t) {
  Animation::Pose p;
  p.translation = t;
  return p;
}

}  // namespace

parsed::Scene cornell() { return cornellBox(); }

parsed::Scene cornellFog() {
  parsed::Scene s = cornellBox();
  // Units are millimetres: the glass sphere (radius 70) holds milk-like
  // scattering (optical depth about 3 across), the room a thin haze
  // (about 0.3 across the box) that shows the light's cone.
  parsed::Volume milk;
  milk.scattering = Vec3(0.02f, 0.021f, 0.022f);
  milk.absorption = Vec3(0.0004f, 0.0008f, 0.0016f);
  milk.phaseG = 0.3f;
  s.materials[kGlass].volume = milk;
  parsed::Volume haze;
  haze.scattering = Vec3(0.0005f);
  haze.phaseG = 0.2f;
  s.medium = haze;
  return s;
}

parsed::Scene instances(std::uint64_t count) {
  parsed::Scene s;
  const Vec3 palette[] = {{0.8f, 0.2f, 0.2f}, {0.2f, 0.7f, 0.3f}, {0.2f, 0.3f, 0.8f}, {0.9f, 0.8f, 0.3f}};
  const float metallic[] = {0.0f, 1.0f, 0.0f, 1.0f};
  const float roughness[] = {0.6f, 0.2f, 0.05f, 0.5f};
  for (std::size_t i = 0; i < 4; ++i)
    s.materials.push_back(material("material " + std::to_string(i), palette[i], metallic[i], roughness[i]));
  const parsed::Primitive shapes[] = {shapes::sphere(Vec3(0), 0.4f, 16), shapes::box(Vec3(0.35f)),
                                      shapes::torus(0.3f, 0.1f, 32, 12)};
  const char* shapeNames[] = {"sphere", "cube", "torus"};
  // Every shape in every material: 12 shared meshes.
  for (std::size_t shape = 0; shape < 3; ++shape)
    for (std::size_t m = 0; m < 4; ++m)
      addMesh(s, shapes[shape], static_cast<int>(m), std::string(shapeNames[shape]) + " " + std::to_string(m));

  const auto side = static_cast<std::uint64_t>(std::ceil(std::sqrt(static_cast<double>(count))));
  const float spacing = 1.0f;
  const float half = 0.5f * spacing * static_cast<float>(side - 1);
  s.nodes.reserve(count + 2);
  s.roots.reserve(count + 2);
  for (std::uint64_t i = 0; i < count; ++i) {
    const float x = static_cast<float>(i % side) * spacing - half;
    const float z = static_cast<float>(i / side) * spacing - half;
    Animation::Pose pose = translated(Vec3(x, 0.0f, z));
    pose.rotation = glm::angleAxis(0.7f * static_cast<float>(i % 9), Vec3(0, 1, 0));
    const int shape = static_cast<int>(i % 3), paint = static_cast<int>((i / 3) % 4);
    addNode(s, {}, pose.matrix(), shape * 4 + paint, parsed::kNone, parsed::kNone, pose);
  }
  const float w = half + spacing;
  addCamera(s, Vec3(0.0f, 1.5f * w + 2.0f, 1.5f * w + 3.0f), Vec3(0.0f), 60.0f, 0.1f, 10.0f * w + 100.0f);
  s.lights.push_back(light("sun", LightKind::Directional, Vec3(1.0f), 3.0f));
  addNode(s, "sun", lookFrom(Vec3(0), Vec3(-0.3f, -1.0f, -0.5f)), parsed::kNone, 0);
  s.background = Vec3(0.05f, 0.05f, 0.08f);
  return s;
}

parsed::Scene animated() {
  parsed::Scene s = cornellBox();
  s.materials.push_back(material("yellow", Vec3(0.9f, 0.8f, 0.2f), 0.0f, 0.4f));
  const int cube = addMesh(s, shapes::box(Vec3(25.0f)), static_cast<int>(s.materials.size()) - 1, "moving cube");
  const Animation::Pose cubeStart = translated(Vec3(120, 25, 30));
  const int cubeNode = addNode(s, "moving cube", cubeStart.matrix(), cube, parsed::kNone, parsed::kNone, cubeStart);

  s.lights.push_back(light("moving light", LightKind::Point, Vec3(1.0f, 0.95f, 0.9f), 60000.0f));
  const Animation::Pose lightStart = translated(Vec3(428, 450, 280));
  const int lightNode = addNode(s, "moving light", lightStart.matrix(), parsed::kNone,
                                static_cast<int>(s.lights.size()) - 1, parsed::kNone, lightStart);

  parsed::AnimationClip clip{"builtin animation", true, {}};
  const std::vector<float> times = {0, 1, 2, 3, 4};
  parsed::AnimationChannel slide{cubeNode, Animation::Path::Translation, Animation::Interpolation::Linear, times, {}};
  for (float x : {120.0f, 280.0f, 440.0f, 280.0f, 120.0f}) slide.values.emplace_back(x, 25, 30, 0);
  parsed::AnimationChannel spin{cubeNode, Animation::Path::Rotation, Animation::Interpolation::Linear, times, {}};
  for (int k = 0; k < 5; ++k) {
    const glm::quat q = glm::angleAxis(glm::half_pi<float>() * static_cast<float>(k), Vec3(0, 1, 0));
    spin.values.emplace_back(q.x, q.y, q.z, q.w);
  }
  parsed::AnimationChannel orbit{lightNode, Animation::Path::Translation, Animation::Interpolation::Linear, times, {}};
  for (int k = 0; k < 5; ++k) {
    const float a = glm::half_pi<float>() * static_cast<float>(k);
    orbit.values.emplace_back(278.0f + 150.0f * std::cos(a), 450.0f, 280.0f + 150.0f * std::sin(a), 0.0f);
  }
  clip.channels = {std::move(slide), std::move(spin), std::move(orbit)};
  s.animations.push_back(std::move(clip));
  return s;
}

}  // namespace tsr::sg::builtin
