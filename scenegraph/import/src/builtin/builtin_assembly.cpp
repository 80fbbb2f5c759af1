#include "builtin/builtin_assembly.hpp"

#include <glm/gtc/matrix_transform.hpp>

namespace tsr::sg::builtin {

parsed::Material material(std::string name, const Vec3& base, float metallic, float roughness) {
  parsed::Material m;
  m.name = std::move(name);
  m.baseColor = base;
  m.metallic = metallic;
  m.roughness = roughness;
  return m;
}

parsed::Light light(std::string name, LightKind kind, const Vec3& color, float intensity) {
  parsed::Light l;
  l.name = std::move(name);
  l.kind = kind;
  l.color = color;
  l.intensity = intensity;
  return l;
}

int addMesh(parsed::Scene& s, parsed::Primitive p, int material, std::string name) {
  p.material = material;
  s.primitives.push_back(std::move(p));
  s.meshes.push_back({std::move(name), {static_cast<int>(s.primitives.size()) - 1}});
  return static_cast<int>(s.meshes.size()) - 1;
}

int addNode(parsed::Scene& s, std::string name, const Mat4& local, int mesh, int light, int camera,
            std::optional<Animation::Pose> pose, bool root) {
  parsed::Node n;
  n.name = std::move(name);
  n.local = local;
  n.trs = pose;
  n.mesh = mesh;
  n.light = light;
  n.camera = camera;
  s.nodes.push_back(std::move(n));
  const int index = static_cast<int>(s.nodes.size()) - 1;
  if (root) s.roots.push_back(index);
  return index;
}

Mat4 lookFrom(const Vec3& eye, const Vec3& target, const Vec3& up) {
  return glm::inverse(glm::lookAt(eye, target, up));
}

void addCamera(parsed::Scene& s, const Vec3& eye, const Vec3& target, float fovDegrees, float znear, float zfar) {
  s.cameras.push_back({"camera", glm::radians(fovDegrees), znear, zfar});
  addNode(s, "camera", lookFrom(eye, target), parsed::kNone, parsed::kNone, static_cast<int>(s.cameras.size()) - 1);
}

}  // namespace tsr::sg::builtin
