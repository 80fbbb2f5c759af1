#include "cache/parsed_scene_validation.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "tsr/sg/coordinate_limit.hpp"

namespace tsr::sg::parsed {
namespace {

[[noreturn]] void fail(const std::string& what) { throw std::runtime_error(what); }

template <class V>
bool finite(const V& v) {
  for (int i = 0; i < V::length(); ++i)
    if (!std::isfinite(v[i])) return false;
  return true;
}

// Positions and matrices within kMaxCoordinate, as the glTF importer requires.
template <class V>
void inRange(std::span<const V> values, const std::string& what) {
  for (const V& v : values)
    for (int i = 0; i < V::length(); ++i)
      if (!(std::abs(v[i]) <= kMaxCoordinate))
        fail(what + " holds a coordinate beyond " + std::to_string(kMaxCoordinate));
}

template <class V>
void allFinite(std::span<const V> values, const std::string& what) {
  for (const V& v : values)
    if (!finite(v)) fail(what + " holds NaN or infinity");
}

void reference(int index, std::size_t count, bool optional, const std::string& what) {
  if (optional && index == kNone) return;
  if (index < 0 || std::size_t(index) >= count) fail(what + " " + std::to_string(index) + " does not exist");
}

void checkPrimitive(const Scene& s, const Primitive& p, const std::string& what) {
  const ArrayViews a = p.arrays();
  const std::size_t n = a.positions.size();
  if (p.primitive >= GeometryPrimitive::Count) fail(what + " has an unknown primitive");
  if (n == 0 || a.indices.empty() || a.indices.size() % indicesPerPrimitive(p.primitive) != 0)
    fail(what + " is not a list of its primitives");
  if ((!a.normals.empty() && a.normals.size() != n) || (!a.uvs.empty() && a.uvs.size() != n) ||
      (!a.colors.empty() && a.colors.size() != n))
    fail(what + " has attributes of different lengths");
  for (std::uint32_t i : a.indices)
    if (i >= n) fail(what + " has an index out of range");
  inRange(a.positions, what + "'s positions");
  allFinite(a.normals, what + "'s normals");
  allFinite(a.uvs, what + "'s uvs");
  allFinite(a.colors, what + "'s colours");
  reference(p.material, s.materials.size(), true, what + ": material");
}

// Coefficients finite and not negative, g strictly inside (-1, 1), and
// textures (a material's only) whose images hold whole slices.
void checkVolume(const Volume& v, const Scene& s, bool textures, const std::string& what) {
  for (const Vec3& c : {v.emission, v.absorption, v.scattering})
    if (!finite(c) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f) fail(what + " has a negative or non-finite coefficient");
  if (!(v.phaseG > -1.0f && v.phaseG < 1.0f)) fail(what + " has a phase g outside (-1, 1)");
  if (v.textureSlices < 1 || v.textureSlices > kMaxTextureSlices)
    fail(what + " has " + std::to_string(v.textureSlices) + " texture slices");
  for (int image : {v.absorptionImage, v.scatteringImage, v.emissionImage}) {
    if (image != kNone && !textures) fail(what + " is textured, which only a material's volume may be");
    reference(image, s.images.size(), true, what + ": image");
    if (image == kNone) continue;
    const Image& i = s.images[static_cast<std::size_t>(image)];
    if (i.height % v.textureSlices != 0)
      fail(what + ": image " + std::to_string(image) + " is " + std::to_string(i.height) + " rows high, not " +
           std::to_string(v.textureSlices) + " slices of equal height");
  }
}

void checkMaterials(const Scene& s) {
  for (std::size_t i = 0; i < s.materials.size(); ++i) {
    const Material& m = s.materials[i];
    const std::string what = "material " + std::to_string(i);
    for (int image : {m.baseColorImage, m.metallicRoughnessImage, m.emissionImage, m.transmissionImage, m.normalImage,
                      m.occlusionImage})
      reference(image, s.images.size(), true, what + ": image");
    if (!m.uvTransforms.empty() && m.uvTransforms.size() != SurfaceMaterial::kUvTransformRows)
      fail(what + " has " + std::to_string(m.uvTransforms.size()) + " texture transform rows");
    for (const Vec3& row : m.uvTransforms)
      if (!finite(row)) fail(what + " has a texture transform with NaN or infinity");
    if (!std::isfinite(m.alphaCutoff) || !std::isfinite(m.occlusionStrength)) fail(what + " holds NaN or infinity");
    if (!finite(m.baseColor) || !finite(m.emission) || !std::isfinite(m.opacity) || !std::isfinite(m.metallic) ||
        !std::isfinite(m.roughness) || !std::isfinite(m.emissionStrength) || !std::isfinite(m.transmission) ||
        !std::isfinite(m.ior) || !std::isfinite(m.normalScale))
      fail(what + " holds NaN or infinity");
    if (m.volume) checkVolume(*m.volume, s, true, what + "'s volume");
  }
  if (s.medium) checkVolume(*s.medium, s, false, "the scene medium");
}

// Every node reached once from the roots, none twice (no cycles, no sharing).
void checkNodes(const Scene& s) {
  std::vector<char> seen(s.nodes.size(), 0);
  std::vector<int> stack;
  for (int root : s.roots) {
    reference(root, s.nodes.size(), false, "root node");
    stack.push_back(root);
  }
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (seen[std::size_t(n)]) fail("node " + std::to_string(n) + " is reached twice");
    seen[std::size_t(n)] = 1;
    const Node& node = s.nodes[std::size_t(n)];
    const std::string what = "node " + std::to_string(n);
    reference(node.mesh, s.meshes.size(), true, what + ": mesh");
    reference(node.light, s.lights.size(), true, what + ": light");
    reference(node.camera, s.cameras.size(), true, what + ": camera");
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j)
        if (!(std::abs(node.local[i][j]) <= kMaxCoordinate)) fail(what + "'s matrix holds a value out of range");
    for (int c : node.children) {
      reference(c, s.nodes.size(), false, what + ": child");
      stack.push_back(c);
    }
  }
}

// The same checks the glTF importer makes: Animation::addChannel's.
void checkAnimations(const Scene& s) {
  for (const AnimationClip& clip : s.animations)
    for (const AnimationChannel& c : clip.channels) {
      const std::string what = "animation '" + clip.name + "'";
      reference(c.node, s.nodes.size(), false, what + ": node");
      allFinite(std::span<const Vec4>(c.values), what + "'s values");
      try {
        Animation check;
        check.addChannel({0, c.path, c.interpolation, c.times, c.values});
      } catch (const std::invalid_argument& e) {
        fail(what + ": " + e.what());
      }
    }
}

}  // namespace

void validateScene(const Scene& s) {
  for (std::size_t i = 0; i < s.images.size(); ++i) {
    const Image& img = s.images[i];
    if (img.channels < 1 || img.channels > 4 || img.width == 0 || img.height == 0 ||
        img.pixels.size() != std::uint64_t(img.width) * img.height * img.channels)
      fail("image " + std::to_string(i) + " has pixels that do not match its size");
  }
  checkMaterials(s);
  for (std::size_t i = 0; i < s.primitives.size(); ++i)
    checkPrimitive(s, s.primitives[i], "primitive " + std::to_string(i));
  for (std::size_t i = 0; i < s.meshes.size(); ++i)
    for (int p : s.meshes[i].primitives)
      reference(p, s.primitives.size(), false, "mesh " + std::to_string(i) + ": primitive");
  for (const Light& l : s.lights)
    if (!finite(l.color) || !std::isfinite(l.intensity) || !std::isfinite(l.innerCone) || !std::isfinite(l.outerCone))
      fail("light '" + l.name + "' holds NaN or infinity");
  for (const Camera& c : s.cameras)
    if (!(c.yfov > 0.0f && c.yfov < 3.1415926f) || !(c.znear > 0.0f && std::isfinite(c.znear)) ||
        !(c.zfar > c.znear && std::isfinite(c.zfar)))
      fail("camera '" + c.name + "' has an impossible frustum");
  for (const Camera& c : s.cameras)
    if (!(c.apertureRadius >= 0.0f && std::isfinite(c.apertureRadius)) ||
        !(c.focusDistance > 0.0f && std::isfinite(c.focusDistance)))
      fail("camera '" + c.name + "' has an impossible lens");
  checkNodes(s);
  checkAnimations(s);
  if (!finite(s.background)) fail("the background holds NaN or infinity");
}

}  // namespace tsr::sg::parsed
