#include "scene/scene_glb.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include <tiny_gltf.h>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat3x3.hpp>

#include "tsr/sg/camera.hpp"
#include "tsr/sg/node_world.hpp"

namespace tsr::app {

namespace {

constexpr int kArrayBuffer = 34962, kElementArrayBuffer = 34963;

// Appends `bytes` to the one buffer as a view (4-byte aligned) and returns it.
int addView(tinygltf::Model& m, const void* bytes, std::size_t size, int target) {
  auto& data = m.buffers[0].data;
  data.resize((data.size() + 3) & ~std::size_t{3});
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = data.size();
  view.byteLength = size;
  view.target = target;
  data.insert(data.end(), static_cast<const unsigned char*>(bytes), static_cast<const unsigned char*>(bytes) + size);
  m.bufferViews.push_back(view);
  return int(m.bufferViews.size()) - 1;
}

int addAccessor(tinygltf::Model& m, int view, int componentType, std::size_t count, int type) {
  tinygltf::Accessor a;
  a.bufferView = view;
  a.componentType = componentType;
  a.count = count;
  a.type = type;
  m.accessors.push_back(a);
  return int(m.accessors.size()) - 1;
}

void useExtension(tinygltf::Model& m, tinygltf::Material& material, const std::string& name, const char* key,
                  double value) {
  tinygltf::Value::Object values;
  values[key] = tinygltf::Value(value);
  material.extensions[name] = tinygltf::Value(values);
  if (std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), name) == m.extensionsUsed.end())
    m.extensionsUsed.push_back(name);
}

int addMaterial(tinygltf::Model& m, const sg::Container* material) {
  tinygltf::Material out;
  out.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
  if (const auto* s = dynamic_cast<const sg::SurfaceMaterial*>(material)) {
    out.name = s->name();
    out.pbrMetallicRoughness.baseColorFactor = {s->baseColor().r, s->baseColor().g, s->baseColor().b, s->opacity()};
    out.pbrMetallicRoughness.metallicFactor = s->metallic();
    out.pbrMetallicRoughness.roughnessFactor = s->roughness();
    // glTF's emissiveFactor stops at 1: a brighter emitter (a lamp) keeps its
    // radiance as factor times KHR_materials_emissive_strength.
    const glm::vec3 emitted = s->emittedRadiance();
    const double strength = std::max({1.0, double(emitted.r), double(emitted.g), double(emitted.b)});
    out.emissiveFactor = {emitted.r / strength, emitted.g / strength, emitted.b / strength};
    if (strength > 1.0) useExtension(m, out, "KHR_materials_emissive_strength", "emissiveStrength", strength);
    if (s->transmission() > 0.0f)
      useExtension(m, out, "KHR_materials_transmission", "transmissionFactor", s->transmission());
    if (s->ior() != 1.5f && s->ior() >= 1.0f) useExtension(m, out, "KHR_materials_ior", "ior", s->ior());
  } else if (const auto* p = dynamic_cast<const sg::SimpleMaterial*>(material)) {
    out.pbrMetallicRoughness.baseColorFactor = {p->diffuse().r, p->diffuse().g, p->diffuse().b,
                                                1.0 - p->transparency()};
    out.pbrMetallicRoughness.metallicFactor = 0.0;
  }
  m.materials.push_back(out);
  return int(m.materials.size()) - 1;
}

// A scene camera as a node in world space, so other tools open the scene
// looking where Tessera looks; in metres, unscaled (a camera's node should
// carry no scale).
void addCamera(tinygltf::Model& m, const sg::Scene& scene, sg::ContainerId id, float metresPerUnit) {
  const auto* c = scene.find<sg::Camera>(id);
  if (!c) return;
  tinygltf::Camera camera;
  camera.type = "perspective";
  camera.name = c->name();
  camera.perspective.yfov = c->verticalFov();
  camera.perspective.znear = c->nearPlane() * metresPerUnit;
  if (std::isfinite(c->farPlane()) && c->farPlane() < 1e29f)
    camera.perspective.zfar = c->farPlane() * metresPerUnit;  // else infinite
  m.cameras.push_back(camera);
  tinygltf::Node node;
  node.camera = int(m.cameras.size()) - 1;
  node.name = c->name();
  sg::Mat4 world = sg::cameraWorldPose(scene, id);
  world[3] = sg::Vec4(sg::Vec3(world[3]) * metresPerUnit, 1.0f);
  for (int column = 0; column < 4; ++column)
    for (int row = 0; row < 4; ++row) node.matrix.push_back(world[column][row]);
  m.nodes.push_back(node);
  m.scenes[0].nodes.push_back(int(m.nodes.size()) - 1);
}

void addInstance(tinygltf::Model& m, const sg::Scene& scene, const med::FlatNode& instance) {
  const auto* g = scene.find<sg::Geometry>(instance.id);
  if (!g || g->invalidReason() || g->indices().empty()) return;
  const glm::mat3 normalMatrix = glm::inverseTranspose(glm::mat3(instance.world));
  std::vector<glm::vec3> positions(g->positions().size());
  std::vector<double> lo(3, 1e300), hi(3, -1e300);
  for (std::size_t i = 0; i < positions.size(); ++i) {
    positions[i] = glm::vec3(instance.world * glm::vec4(g->positions()[i], 1.0f));
    for (int c = 0; c < 3; ++c)
      lo[c] = std::min(lo[c], double(positions[i][c])), hi[c] = std::max(hi[c], double(positions[i][c]));
  }
  tinygltf::Primitive primitive;
  primitive.mode = g->primitive() == sg::GeometryPrimitive::Lines    ? TINYGLTF_MODE_LINE
                   : g->primitive() == sg::GeometryPrimitive::Points ? TINYGLTF_MODE_POINTS
                                                                     : TINYGLTF_MODE_TRIANGLES;
  const int pv = addView(m, positions.data(), positions.size() * sizeof(glm::vec3), kArrayBuffer);
  primitive.attributes["POSITION"] =
      addAccessor(m, pv, TINYGLTF_COMPONENT_TYPE_FLOAT, positions.size(), TINYGLTF_TYPE_VEC3);
  m.accessors.back().minValues = lo;  // glTF requires the bounds of positions
  m.accessors.back().maxValues = hi;
  if (g->normals().size() == g->positions().size()) {
    std::vector<glm::vec3> normals(g->normals().size());
    for (std::size_t i = 0; i < normals.size(); ++i) {
      const glm::vec3 n = normalMatrix * g->normals()[i];
      const float length = glm::length(n);
      normals[i] = length > 0 ? n / length : glm::vec3(0, 1, 0);
    }
    const int nv = addView(m, normals.data(), normals.size() * sizeof(glm::vec3), kArrayBuffer);
    primitive.attributes["NORMAL"] =
        addAccessor(m, nv, TINYGLTF_COMPONENT_TYPE_FLOAT, normals.size(), TINYGLTF_TYPE_VEC3);
  }
  const auto& indices = g->indices();
  const int iv = addView(m, indices.data(), indices.size() * sizeof(std::uint32_t), kElementArrayBuffer);
  primitive.indices = addAccessor(m, iv, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, indices.size(), TINYGLTF_TYPE_SCALAR);
  primitive.material = addMaterial(m, g->material() ? scene.find(g->material()) : nullptr);
  tinygltf::Mesh mesh;
  mesh.name = g->name();
  mesh.primitives.push_back(primitive);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = int(m.meshes.size()) - 1;
  node.name = g->name();
  m.nodes.push_back(node);
  m.scenes[0].nodes.push_back(int(m.nodes.size()) - 1);
}

}  // namespace

std::vector<std::uint8_t> glbOf(const sg::Scene& scene, const std::vector<med::FlatNode>& instances,
                                const std::vector<sg::ContainerId>& cameras, float metresPerUnit) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "Tessera";
  m.buffers.resize(1);
  m.scenes.resize(1);
  m.defaultScene = 0;
  for (const auto& instance : instances) addInstance(m, scene, instance);
  if (metresPerUnit != 1.0f) {  // the meshes under one scaled node
    tinygltf::Node units;
    units.name = "scene units";
    units.scale = {metresPerUnit, metresPerUnit, metresPerUnit};
    units.children = m.scenes[0].nodes;
    m.nodes.push_back(units);
    m.scenes[0].nodes = {int(m.nodes.size()) - 1};
  }
  for (sg::ContainerId camera : cameras) addCamera(m, scene, camera, metresPerUnit);
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&m, out, false, true);
  const std::string bytes = out.str();
  return {bytes.begin(), bytes.end()};
}

}  // namespace tsr::app
