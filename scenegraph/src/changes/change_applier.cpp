#include "tsr/sg/changes/change_applier.hpp"

#include <bit>

#include "tsr/sg/container_factory.hpp"

namespace tsr::sg {

void ChangeApplier::fail(const std::string& reason) const {
  throw ApplyError("change list " + std::to_string(list_.version()) + ": " + reason);
}

void ChangeApplier::run() {
  validate();
  mutate();
}

void ChangeApplier::validate() {
  if (scene_.hasPendingChanges()) fail("the replica has local edits that were never committed");
  if (list_.isSnapshotPart()) fail("a part of a snapshot applies with the others (sg::Replica, sg::joinSnapshot)");
  if (list_.isSnapshot()) {
    if (scene_.size() != 0) fail("a snapshot applies only to an empty replica");
  } else if (list_.baseVersion() != scene_.version()) {
    fail("follows version " + std::to_string(list_.baseVersion()) + " but the replica is at version " +
         std::to_string(scene_.version()));
  }
  checkIds();
  checkReferences();
  checkNoCycles();
}

void ChangeApplier::checkIds() {
  for (const auto& e : list_.creations()) {
    if (scene_.find(e.id)) fail("creates container " + std::to_string(e.id) + ", which exists");
    if (!created_.emplace(e.id, e.type).second) fail("creates container " + std::to_string(e.id) + " twice");
  }
  for (const auto& e : list_.changes()) {
    const Container* c = scene_.find(e.id);
    if (!c) fail("changes container " + std::to_string(e.id) + ", which does not exist");
    if (c->type() != e.type)
      fail("changes container " + std::to_string(e.id) + " as a " + std::string(typeName(e.type)) + ", it is a " +
           std::string(typeName(c->type())));
    if (!changed_.emplace(e.id, &e).second) fail("changes container " + std::to_string(e.id) + " twice");
    for (const auto& edit : e.rangedEdits)
      if (c->arrayLength(edit.field) != edit.length)
        fail("edits " + std::string(c->fieldInfo(edit.field).name) + " of container " + std::to_string(e.id) + " as " +
             std::to_string(edit.length) + " elements, it has " + std::to_string(c->arrayLength(edit.field)));
  }
  for (const auto& d : list_.destructions()) {
    const Container* c = scene_.find(d.id);
    if (!c) fail("destroys container " + std::to_string(d.id) + ", which does not exist");
    if (c->type() != d.type) fail("destroys container " + std::to_string(d.id) + " under the wrong type");
    if (!destroyed_.insert(d.id).second) fail("destroys container " + std::to_string(d.id) + " twice");
  }
}

void ChangeApplier::checkReferences() {
  // Every reference held afterwards names a live container of an allowed type.
  auto liveType = [&](ContainerId id) -> std::optional<ContainerType> {
    if (auto it = created_.find(id); it != created_.end()) return it->second;
    if (destroyed_.count(id)) return std::nullopt;
    if (const Container* c = scene_.find(id)) return c->type();
    return std::nullopt;
  };
  auto check = [&](const ChangeEntry& e) {
    for (const auto& ref : e.references) {
      FieldInfo info = prototype(e.type).fieldInfo(ref.field);
      auto type = liveType(ref.target);
      if (!type)
        fail(std::string(typeName(e.type)) + " " + std::to_string(e.id) + "." + std::string(info.name) +
             " names container " + std::to_string(ref.target) + ", which will not exist");
      if (!(typeBit(*type) & info.allowedTargets))
        fail(std::string(typeName(e.type)) + " " + std::to_string(e.id) + "." + std::string(info.name) +
             " cannot name a " + std::string(typeName(*type)));
    }
  };
  for (const auto& e : list_.creations()) check(e);
  for (const auto& e : list_.changes()) check(e);
  // Whatever referred to a destroyed container must be destroyed too, or
  // have that field rewritten (and the rewrite was checked above).
  for (ContainerId d : destroyed_) {
    auto refs = scene_.referrers_.find(d);
    if (refs == scene_.referrers_.end()) continue;
    for (const auto& [key, count] : refs->second) {
      if (destroyed_.count(key.from)) continue;
      auto it = changed_.find(key.from);
      if (it == changed_.end() || !it->second->changed(key.field))
        fail("destroys container " + std::to_string(d) + " while container " + std::to_string(key.from) +
             " still refers to it");
    }
  }
}

void ChangeApplier::checkNoCycles() const {
  // Any new cycle passes through a children list this list sets, so a
  // depth-first search from those, over the graph as it will be, finds it.
  std::unordered_map<ContainerId, std::vector<ContainerId>> overlay;
  auto collect = [&](const ChangeEntry& e) {
    if (!isParentType(e.type) || !e.changed(Group::Children)) return;
    auto& kids = overlay[e.id];
    for (const auto& ref : e.references)
      if (ref.field == Group::Children) kids.push_back(ref.target);
  };
  for (const auto& e : list_.creations()) collect(e);
  for (const auto& e : list_.changes()) collect(e);
  if (overlay.empty()) return;

  auto childrenOf = [&](ContainerId id) -> std::span<const ContainerId> {
    if (auto it = overlay.find(id); it != overlay.end()) return it->second;
    if (const Container* c = scene_.find(id); c && isParentType(c->type()))
      return c->type() == ContainerType::Group ? static_cast<const Group*>(c)->children()
                                               : static_cast<const Transform*>(c)->children();
    return {};
  };
  enum : std::uint8_t { Open = 1, Done = 2 };
  std::unordered_map<ContainerId, std::uint8_t> state;
  struct Frame {
    ContainerId id;
    std::span<const ContainerId> children;
    std::size_t next;
  };
  std::vector<Frame> stack;
  for (const auto& [start, kids] : overlay) {
    if (state[start] == Done) continue;
    state[start] = Open;
    stack.push_back({start, childrenOf(start), 0});
    while (!stack.empty()) {
      Frame& top = stack.back();
      if (top.next == top.children.size()) {
        state[top.id] = Done;
        stack.pop_back();
        continue;
      }
      ContainerId child = top.children[top.next++];
      std::uint8_t& s = state[child];
      if (s == Open) fail("children would form a cycle through container " + std::to_string(child));
      if (s == Done) continue;
      s = Open;
      stack.push_back({child, childrenOf(child), 0});
    }
  }
}

void ChangeApplier::read(Container& c, const ChangeEntry& e, bool creation) {
  DecodeLimits unlimited{SIZE_MAX, SIZE_MAX, SIZE_MAX, SIZE_MAX, SIZE_MAX, SIZE_MAX};
  FieldReadContext ctx{unlimited, /*scan=*/false};
  ctx.slices = &list_.slices();
  ByteReader r(list_.values(e), e.valueOffset);
  FieldMask refs = e.mask & c.referenceFields();
  if (!creation) {
    for (FieldMask m = refs; m; m &= m - 1) {
      auto f = static_cast<FieldIndex>(std::countr_zero(m));
      c.forEachReference(f, [&](ContainerId to) { scene_.unlink(c.id(), f, to); });
    }
  }
  for (FieldMask m = e.mask; m; m &= m - 1) c.readField(static_cast<FieldIndex>(std::countr_zero(m)), r, ctx);
  for (FieldMask m = refs; m; m &= m - 1) {
    auto f = static_cast<FieldIndex>(std::countr_zero(m));
    c.forEachReference(f, [&](ContainerId to) { scene_.link(c.id(), f, to); });
  }
}

void ChangeApplier::mutate() {
  try {
    for (const auto& e : list_.creations()) {
      auto owned = makeContainer(e.type);
      Container& c = *owned;
      c.id_ = e.id;
      c.scene_ = &scene_;
      scene_.containers_.emplace(e.id, std::move(owned));
      read(c, e, /*creation=*/true);
      scene_.nextId_ = std::max(scene_.nextId_, e.id + 1);
    }
    for (const auto& e : list_.changes()) read(*scene_.containers_.at(e.id), e, /*creation=*/false);
    for (const auto& d : list_.destructions()) {
      scene_.unlinkAll(*scene_.containers_.at(d.id));
      scene_.containers_.erase(d.id);
    }
    for (ContainerId d : destroyed_) scene_.referrers_.erase(d);
  } catch (const std::exception& e) {
    // validate() admits only lists that apply; reaching here is a bug.
    throw std::logic_error(std::string("validated change list failed to apply: ") + e.what());
  }
  scene_.version_ = list_.version();
}

}  // namespace tsr::sg
