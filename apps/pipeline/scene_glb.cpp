#include "scene_glb.hpp"

#include <cstring>
#include <sstream>

#include <tiny_gltf.h>
#include <glm/gtc/matrix_inverse.hpp>
#include <glm/mat3x3.hpp>

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

int addMaterial(tinygltf::Model& m, const sg::Container* material) {
  tinygltf::Material out;
  out.pbrMetallicRoughness.baseColorFactor = {0.8, 0.8, 0.8, 1.0};
  if (const auto* s = dynamic_cast<const sg::SurfaceMaterial*>(material)) {
    out.pbrMetallicRoughness.baseColorFactor = {s->baseColor().r, s->baseColor().g, s->baseColor().b, s->opacity()};
    out.pbrMetallicRoughness.metallicFactor = s->metallic();
    out.pbrMetallicRoughness.roughnessFactor = s->roughness();
    out.emissiveFactor = {s->emittedRadiance().r, s->emittedRadiance().g, s->emittedRadiance().b};
  } else if (const auto* p = dynamic_cast<const sg::SimpleMaterial*>(material)) {
    out.pbrMetallicRoughness.baseColorFactor = {p->diffuse().r, p->diffuse().g, p->diffuse().b,
                                                1.0 - p->transparency()};
    out.pbrMetallicRoughness.metallicFactor = 0.0;
  }
  m.materials.push_back(out);
  return int(m.materials.size()) - 1;
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
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
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

std::vector<std::uint8_t> glbOf(const sg::Scene& scene, const std::vector<med::FlatNode>& instances) {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "tessera-cull";
  m.buffers.resize(1);
  m.scenes.resize(1);
  m.defaultScene = 0;
  for (const auto& instance : instances) addInstance(m, scene, instance);
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&m, out, false, true);
  const std::string bytes = out.str();
  return {bytes.begin(), bytes.end()};
}

}  // namespace tsr::app
