#include "vulkan_id_renderer.hpp"

#include <mutex>

#include "tsr/backend/validate.hpp"
#include "tsr/cov/error.hpp"
#include "tsr/vk/error.hpp"
#include "tsr/vk/renderer.hpp"
#include "tsr/vk/scene.hpp"
#include "tsr/vk/shared_device.hpp"

namespace tsr::med::coverage_mediator {

namespace {
// Back-end errors surface as the interface's error type.
template <class F>
auto translated(F&& f) {
  try {
    return f();
  } catch (const vk::Error& e) {
    throw cov::Error(e.what());
  }
}

static_assert(vk::kNoObject == cov::kBackground, "ids pass through unchanged");

vk::Material withOpacity(float opacity) {
  vk::Material m;
  m.opacity = opacity;
  return m;
}

vk::MeshData meshData(const cov::MeshData& data) {
  data.validate();
  vk::MeshData m;
  m.positions = data.positions;
  m.indices = data.indices;
  m.primitive = data.primitive;
  return m;
}
}  // namespace

struct VulkanIdRenderer::State {
  struct Placed {
    cov::Instance instance;
    vk::InstanceId id;
  };
  explicit State(std::shared_ptr<vk::SharedDevice> s) : shared(std::move(s)) {}
  std::shared_ptr<vk::SharedDevice> shared;
  vk::Scene scene{shared->device};
  vk::Renderer renderer{shared->device};
  // The id pass leaves out instances whose material is transparent; the
  // materials do nothing else here.
  vk::MaterialId opaque = scene.addMaterial(withOpacity(1.0f));
  vk::MaterialId transparent = scene.addMaterial(withOpacity(0.5f));
  // Our handles stay stable when a mesh is replaced (the rasterizer's
  // meshes cannot change size, so instances move to a new one).
  std::unordered_map<std::uint32_t, vk::MeshId> meshes;
  std::unordered_map<std::uint32_t, Placed> instances;
  std::uint32_t nextMesh = 0, nextInstance = 0;

  vk::MeshId mesh(cov::MeshId id) const {
    auto it = meshes.find(cov::index(id));
    if (it == meshes.end()) throw cov::Error("unknown mesh id " + std::to_string(cov::index(id)));
    return it->second;
  }
  Placed& placed(cov::InstanceId id) {
    auto it = instances.find(cov::index(id));
    if (it == instances.end()) throw cov::Error("unknown instance id " + std::to_string(cov::index(id)));
    return it->second;
  }
  vk::InstanceId place(const cov::Instance& i) {
    vk::InstanceId id = scene.addInstance(mesh(i.mesh), i.transparent ? transparent : opaque, i.transform);
    scene.setInstanceObject(id, i.object);
    return id;
  }
};

VulkanIdRenderer::VulkanIdRenderer() {
  auto shared = vk::sharedDevice();
  std::lock_guard lock(shared->mutex);
  state_ = std::make_unique<State>(shared);
}

VulkanIdRenderer::~VulkanIdRenderer() {
  auto shared = state_->shared;  // outlives the lock: the mutex lives in it
  std::lock_guard lock(shared->mutex);
  state_.reset();
}

cov::MeshId VulkanIdRenderer::addMesh(cov::MeshData data) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  vk::MeshId m = translated([&] { return s.scene.addMesh(meshData(data)); });
  s.meshes.emplace(s.nextMesh, m);
  return cov::MeshId(s.nextMesh++);
}

void VulkanIdRenderer::setMeshData(cov::MeshId mesh, cov::MeshData data) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  translated([&] {
    const vk::MeshId old = s.mesh(mesh);
    const vk::MeshId fresh = s.scene.addMesh(meshData(data));
    s.meshes[cov::index(mesh)] = fresh;
    for (auto& [key, p] : s.instances)
      if (p.instance.mesh == mesh) {
        s.scene.removeInstance(p.id);
        p.id = s.place(p.instance);
      }
    s.scene.removeMesh(old);
    return 0;
  });
}

void VulkanIdRenderer::updateMeshVertices(cov::MeshId mesh, const cov::VertexEdit& edit) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  translated([&] {
    cov::VertexEdit positionsOnly = edit;  // the id pass has no normals
    positionsOnly.normals = {};
    s.scene.updateMeshVertices(s.mesh(mesh), positionsOnly);
    return 0;
  });
}

void VulkanIdRenderer::removeMesh(cov::MeshId mesh) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  const vk::MeshId m = s.mesh(mesh);
  for (const auto& [key, p] : s.instances)
    if (p.instance.mesh == mesh) throw cov::Error("mesh " + std::to_string(cov::index(mesh)) + " is still instanced");
  translated([&] {
    s.scene.removeMesh(m);
    return 0;
  });
  s.meshes.erase(cov::index(mesh));
}

cov::InstanceId VulkanIdRenderer::addInstance(const cov::Instance& instance) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  if (instance.object == cov::kBackground) throw cov::Error("object id 0 is the background");
  vk::InstanceId id = translated([&] { return s.place(instance); });
  s.instances.emplace(s.nextInstance, State::Placed{instance, id});
  return cov::InstanceId(s.nextInstance++);
}

void VulkanIdRenderer::setInstanceTransform(cov::InstanceId instance, const glm::mat4& transform) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  State::Placed& p = s.placed(instance);
  translated([&] {
    s.scene.setInstanceTransform(p.id, transform);
    return 0;
  });
  p.instance.transform = transform;
}

void VulkanIdRenderer::setInstanceObject(cov::InstanceId instance, cov::ObjectId object) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  if (object == cov::kBackground) throw cov::Error("object id 0 is the background");
  State::Placed& p = s.placed(instance);
  s.scene.setInstanceObject(p.id, object);
  p.instance.object = object;
}

void VulkanIdRenderer::setInstanceTransparent(cov::InstanceId instance, bool transparent) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  State::Placed& p = s.placed(instance);
  s.scene.setInstanceMaterial(p.id, transparent ? s.transparent : s.opaque);
  p.instance.transparent = transparent;
}

void VulkanIdRenderer::removeInstance(cov::InstanceId instance) {
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  State::Placed& p = s.placed(instance);
  s.scene.removeInstance(p.id);
  s.instances.erase(cov::index(instance));
}

std::size_t VulkanIdRenderer::meshCount() const { return state_->meshes.size(); }
std::size_t VulkanIdRenderer::instanceCount() const { return state_->instances.size(); }

cov::IdBuffer VulkanIdRenderer::render(const cov::Camera& camera, const cov::Region& region) {
  backend::validate<cov::Error>(camera);
  backend::validate<cov::Error>(region);
  State& s = *state_;
  std::lock_guard lock(s.shared->mutex);
  // The id pass never clips: the far plane goes far out.
  vk::Camera c = camera;
  c.far = camera.near * 1e7f;
  vk::IdBuffer ids(region.regionWidth(), region.regionHeight());
  translated([&] {
    s.renderer.renderIds(s.scene, c, region, ids);
    return 0;
  });
  cov::IdBuffer out(region);
  out.ids = std::move(ids.ids);  // vk::kNoObject and cov::kBackground are both 0
  out.depth = std::move(ids.depth);
  return out;
}

}  // namespace tsr::med::coverage_mediator
