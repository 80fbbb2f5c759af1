#pragma once
// The scene: containers by id, the edits of the current frame, and the
// operations that turn edits into change lists and change lists back into
// state (replicas). A scene is used by one thread at a time; change lists
// are immutable and may be handed to other threads freely.
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "tsr/sg/background.hpp"
#include "tsr/sg/camera.hpp"
#include "tsr/sg/changes/change_list.hpp"
#include "tsr/sg/container.hpp"
#include "tsr/sg/geometry.hpp"
#include "tsr/sg/image.hpp"
#include "tsr/sg/light.hpp"
#include "tsr/sg/parent_node.hpp"
#include "tsr/sg/simple_material.hpp"
#include "tsr/sg/surface_material.hpp"
#include "tsr/sg/volume_material.hpp"

namespace tsr::sg {

class Scene {
 public:
  Scene();
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // Creates a container with the next free id; recorded as a creation.
  template <class T>
  // NOLINTNEXTLINE(performance-unnecessary-value-param): moved below; clang-tidy misses moves in calls that depend on T
  T& create(std::string name = {}) {
    auto owned = std::make_unique<T>();
    T& c = *owned;
    adopt(std::move(owned), nextId_++, std::move(name));
    return c;
  }
  // Destroys a container and removes it from everything that refers to it
  // (parents' children, material and texture slots); those removals are
  // recorded as changes. Children of a destroyed node are not destroyed.
  void destroy(ContainerId id);

  Container* find(ContainerId id) const;
  template <class T>
  T* find(ContainerId id) const {
    Container* c = find(id);
    return c && c->type() == T::kType ? static_cast<T*>(c) : nullptr;
  }
  std::size_t size() const { return containers_.size(); }
  // Ids in ascending order.
  std::vector<ContainerId> ids() const;
  std::size_t count(ContainerType type) const;
  // Node containers that no node holds as a child, ascending.
  std::vector<ContainerId> roots() const;
  // Containers whose reference fields name `target`.
  std::vector<ContainerId> referrers(ContainerId target) const;

  // The version of the last commit (or of the last list applied).
  std::uint64_t version() const { return version_; }
  bool hasPendingChanges() const { return !pending_.empty() || !destroyed_.empty(); }
  // Closes the frame: everything edited since the last commit, as one list.
  ChangeListPtr commit();
  // The whole scene as creations, at version(); needs no pending edits.
  ChangeListPtr snapshot() const;
  // Makes this scene (a replica) follow a list: a snapshot to an empty
  // scene, or the delta that follows version(). Throws ApplyError and
  // leaves the scene untouched when the list does not fit.
  void apply(const ChangeList& changes);

  // Equal for scenes with equal containers (ids, types, every field value).
  std::uint64_t contentHash() const;

 private:
  friend class Container;
  friend class ChangeApplier;

  struct PendingChange {
    bool created = false;
    FieldMask mask = 0;
    FieldMask wholeArrays = 0;                            // array fields replaced whole this frame
    std::vector<std::pair<FieldIndex, RangeSet>> ranges;  // array fields edited only by range
  };
  struct ReferrerKey {
    ContainerId from;
    FieldIndex field;
    bool operator==(const ReferrerKey&) const = default;
  };
  struct ReferrerKeyHash {
    std::size_t operator()(const ReferrerKey& k) const { return std::hash<std::uint64_t>()(k.from * 131 + k.field); }
  };
  using ReferrerCounts = std::unordered_map<ReferrerKey, std::uint32_t, ReferrerKeyHash>;

  void adopt(std::unique_ptr<Container> c, ContainerId id, std::string name);
  void recordChange(const Container& c, FieldIndex f);
  void recordRange(const Container& c, FieldIndex f, std::uint64_t begin, std::uint64_t end);
  void checkReferences(const Container& from, FieldIndex f, std::span<const ContainerId> added) const;
  void link(ContainerId from, FieldIndex f, ContainerId to);
  void unlink(ContainerId from, FieldIndex f, ContainerId to);
  void unlinkAll(const Container& c);
  // True when `ancestor` can be reached from `start` through children.
  bool reaches(ContainerId start, ContainerId ancestor) const;

  std::unordered_map<ContainerId, std::unique_ptr<Container>> containers_;
  std::unordered_map<ContainerId, ReferrerCounts> referrers_;
  std::unordered_map<ContainerId, PendingChange> pending_;
  std::vector<Destruction> destroyed_;
  ContainerId nextId_ = 1;
  std::uint64_t version_ = 0;
};

}  // namespace tsr::sg
