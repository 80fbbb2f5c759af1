#include "tsr/sg/scene.hpp"

#include <algorithm>
#include <bit>

#include "tsr/sg/changes/change_applier.hpp"

namespace tsr::sg {

Scene::Scene() = default;
Scene::~Scene() = default;

void Scene::adopt(std::unique_ptr<Container> c, ContainerId id, std::string name) {
  c->id_ = id;
  c->scene_ = this;
  c->name_ = std::move(name);
  pending_[id].created = true;
  containers_.emplace(id, std::move(c));
}

void Scene::destroy(ContainerId id) {
  auto it = containers_.find(id);
  if (it == containers_.end()) throw SceneError("destroy: no container " + std::to_string(id));
  Container& c = *it->second;
  // Detach it from everything that refers to it; each detach is a recorded change.
  if (auto refs = referrers_.find(id); refs != referrers_.end()) {
    std::vector<ReferrerKey> from;
    for (const auto& [key, count] : refs->second) from.push_back(key);
    std::sort(from.begin(), from.end(),
              [](auto& a, auto& b) { return std::tie(a.from, a.field) < std::tie(b.from, b.field); });
    for (const auto& key : from) containers_.at(key.from)->dropReference(key.field, id);
  }
  unlinkAll(c);
  referrers_.erase(id);
  auto p = pending_.find(id);
  bool announced = p == pending_.end() || !p->second.created;
  if (p != pending_.end()) pending_.erase(p);
  if (announced) destroyed_.push_back({id, c.type()});
  containers_.erase(it);
}

Container* Scene::find(ContainerId id) const {
  auto it = containers_.find(id);
  return it == containers_.end() ? nullptr : it->second.get();
}

std::vector<ContainerId> Scene::ids() const {
  std::vector<ContainerId> out;
  out.reserve(containers_.size());
  for (const auto& [id, c] : containers_) out.push_back(id);
  std::sort(out.begin(), out.end());
  return out;
}

std::size_t Scene::count(ContainerType type) const {
  return static_cast<std::size_t>(
      std::count_if(containers_.begin(), containers_.end(), [&](const auto& kv) { return kv.second->type() == type; }));
}

std::vector<ContainerId> Scene::roots() const {
  std::vector<ContainerId> out;
  for (const auto& [id, c] : containers_) {
    if (!(typeBit(c->type()) & kNodeTypes)) continue;
    bool hasParent = false;
    if (auto refs = referrers_.find(id); refs != referrers_.end())
      for (const auto& [key, count] : refs->second)
        if (key.field == Group::Children && isParentType(containers_.at(key.from)->type())) hasParent = true;
    if (!hasParent) out.push_back(id);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<ContainerId> Scene::referrers(ContainerId target) const {
  std::vector<ContainerId> out;
  if (auto refs = referrers_.find(target); refs != referrers_.end())
    for (const auto& [key, count] : refs->second) out.push_back(key.from);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void Scene::recordChange(const Container& c, FieldIndex f) {
  PendingChange& p = pending_[c.id()];
  if (p.created) return;  // the creation carries every field's final value
  p.mask |= fieldBit(f);
  if (c.fieldInfo(f).kind == FieldKind::Array) {
    p.wholeArrays |= fieldBit(f);
    std::erase_if(p.ranges, [&](const auto& r) { return r.first == f; });
  }
}

void Scene::recordRange(const Container& c, FieldIndex f, std::uint64_t begin, std::uint64_t end) {
  PendingChange& p = pending_[c.id()];
  if (p.created) return;
  p.mask |= fieldBit(f);
  if (p.wholeArrays & fieldBit(f)) return;
  auto it = std::find_if(p.ranges.begin(), p.ranges.end(), [&](const auto& r) { return r.first == f; });
  if (it == p.ranges.end()) it = p.ranges.insert(p.ranges.end(), {f, RangeSet{}});
  it->second.add({begin, end});
}

void Scene::checkReferences(const Container& from, FieldIndex f, std::span<const ContainerId> added) const {
  FieldInfo info = from.fieldInfo(f);
  for (ContainerId id : added) {
    const Container* target = find(id);
    if (!target)
      throw SceneError(std::string(typeName(from.type())) + "." + std::string(info.name) + ": no container " +
                       std::to_string(id) + " in this scene");
    if (!(typeBit(target->type()) & info.allowedTargets))
      throw SceneError(std::string(typeName(from.type())) + "." + std::string(info.name) + " cannot name a " +
                       std::string(typeName(target->type())));
    if (info.allowedTargets == kNodeTypes && (id == from.id() || reaches(id, from.id())))
      throw SceneError("adding " + std::to_string(id) + " under " + std::to_string(from.id()) + " would make a cycle");
  }
}

bool Scene::reaches(ContainerId start, ContainerId ancestor) const {
  std::vector<ContainerId> stack{start};
  std::unordered_map<ContainerId, bool> seen;
  while (!stack.empty()) {
    ContainerId id = stack.back();
    stack.pop_back();
    if (id == ancestor) return true;
    if (!seen.emplace(id, true).second) continue;
    const Container* c = find(id);
    if (!c) continue;
    if (isParentType(c->type()))
      c->forEachReference(Group::Children, [&](ContainerId child) { stack.push_back(child); });
  }
  return false;
}

void Scene::link(ContainerId from, FieldIndex f, ContainerId to) { ++referrers_[to][{from, f}]; }

void Scene::unlink(ContainerId from, FieldIndex f, ContainerId to) {
  auto refs = referrers_.find(to);
  if (refs == referrers_.end()) return;
  auto it = refs->second.find({from, f});
  if (it == refs->second.end()) return;
  if (--it->second == 0) refs->second.erase(it);
  if (refs->second.empty()) referrers_.erase(refs);
}

void Scene::unlinkAll(const Container& c) {
  for (FieldMask refs = c.referenceFields(); refs; refs &= refs - 1) {
    auto f = static_cast<FieldIndex>(std::countr_zero(refs));
    c.forEachReference(f, [&](ContainerId to) { unlink(c.id(), f, to); });
  }
}

ChangeListPtr Scene::commit() {
  ChangeList::Builder builder(ChangeList::Kind::Delta, version_ + 1);
  std::vector<ContainerId> touched;
  touched.reserve(pending_.size());
  for (const auto& [id, p] : pending_) touched.push_back(id);
  std::sort(touched.begin(), touched.end());
  for (ContainerId id : touched)
    if (pending_[id].created) builder.addCreation(*containers_.at(id));
  std::vector<RangedEdit> edits;
  for (ContainerId id : touched) {
    const PendingChange& p = pending_[id];
    if (p.created || p.mask == 0) continue;
    edits.clear();
    for (const auto& [f, set] : p.ranges) edits.push_back({f, containers_.at(id)->arrayLength(f), set.ranges()});
    builder.addChange(*containers_.at(id), p.mask, edits);
  }
  std::sort(destroyed_.begin(), destroyed_.end(), [](auto& a, auto& b) { return a.id < b.id; });
  for (const auto& d : destroyed_) builder.addDestruction(d.id, d.type);
  pending_.clear();
  destroyed_.clear();
  ++version_;
  return builder.finish();
}

ChangeListPtr Scene::snapshot() const {
  if (hasPendingChanges()) throw SceneError("snapshot: commit the pending edits first");
  ChangeList::Builder builder(ChangeList::Kind::Snapshot, version_);
  for (ContainerId id : ids()) builder.addCreation(*containers_.at(id));
  return builder.finish();
}

void Scene::apply(const ChangeList& changes) { ChangeApplier(*this, changes).run(); }

std::uint64_t Scene::contentHash() const {
  // FNV-1a over every container's id, type and serialised fields, by id.
  std::uint64_t h = 14695981039346656037ull;
  auto mix = [&](const std::uint8_t* p, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  std::vector<std::uint8_t> bytes;
  for (ContainerId id : ids()) {
    const Container& c = *containers_.at(id);
    bytes.clear();
    ByteWriter w(bytes);
    w.varint(id);
    w.u8(static_cast<std::uint8_t>(c.type()));
    for (FieldIndex f = 0; f < c.fieldCount(); ++f) c.writeField(f, w, nullptr);
    mix(bytes.data(), bytes.size());
  }
  return h;
}

}  // namespace tsr::sg
