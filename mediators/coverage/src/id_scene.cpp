#include "id_scene.hpp"

#include <string>

#include "tsr/cov/error.hpp"

namespace tsr::med::coverage_mediator {

IdScene::IdScene(const std::shared_ptr<IdRendererSource>& source) {
  if (!source || !source->make) throw cov::Error("id scene needs a renderer source");
  renderer_ = source->make();
}

IdScene::Material& IdScene::material(MaterialId id) {
  const auto i = static_cast<std::uint32_t>(id);
  if (i >= materials_.size() || !materials_[i]) throw cov::Error("unknown material id " + std::to_string(i));
  return *materials_[i];
}

MaterialId IdScene::addMaterial(Transparency m) {
  materials_.emplace_back(Material{m.transparent, {}});
  return MaterialId(materials_.size() - 1);
}

void IdScene::setMaterial(MaterialId id, Transparency m) {
  Material& held = material(id);
  if (held.transparent == m.transparent) return;
  held.transparent = m.transparent;
  for (cov::InstanceId user : held.users) setTransparent(user, m.transparent);
}

void IdScene::removeMaterial(MaterialId id) {
  if (!material(id).users.empty()) throw cov::Error("material still in use");
  materials_[static_cast<std::uint32_t>(id)].reset();
}

cov::InstanceId IdScene::addInstance(cov::MeshId mesh, MaterialId m, const glm::mat4& world, cov::ObjectId object) {
  Material& held = material(m);
  const cov::InstanceId id = renderer_->addInstance(cov::Instance{mesh, world, object, held.transparent});
  held.users.insert(id);
  instanceMaterials_.emplace(id, m);
  return id;
}

void IdScene::setInstanceMaterial(cov::InstanceId id, MaterialId m) {
  Material& next = material(m);
  auto held = instanceMaterials_.find(id);
  if (held == instanceMaterials_.end()) throw cov::Error("unknown instance id " + std::to_string(cov::index(id)));
  Material& previous = material(held->second);
  previous.users.erase(id);
  next.users.insert(id);
  held->second = m;
  if (previous.transparent != next.transparent) setTransparent(id, next.transparent);
}

void IdScene::removeInstance(cov::InstanceId id) {
  renderer_->removeInstance(id);
  if (auto held = instanceMaterials_.find(id); held != instanceMaterials_.end()) {
    material(held->second).users.erase(id);
    instanceMaterials_.erase(held);
  }
}

void IdScene::setTransparent(cov::InstanceId id, bool transparent) {
  renderer_->setInstanceTransparent(id, transparent);
  ++transparencyUpdates_;
}

}  // namespace tsr::med::coverage_mediator
