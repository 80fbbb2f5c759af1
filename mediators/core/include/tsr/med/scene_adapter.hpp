#pragma once
// Keeps a back-end's own scene in step with a replica: converts once, then
// syncs only what change lists touched. It holds a version cursor into the
// replica's change log, so an adapter left alone for a while (a viewport
// switched off) catches up in one sync from where it was, and converts
// again only when it fell out of the log's window.
#include <cstdint>
#include <optional>

#include "tsr/sg/changes/merged_changes.hpp"
#include "tsr/sg/replica.hpp"

namespace tsr::med {

class SceneAdapter {
 public:
  enum class Update { None, Synced, Converted };

  virtual ~SceneAdapter() = default;

  // Brings the back-end scene to the replica's version.
  Update catchUp(const sg::Replica& replica);
  std::optional<std::uint64_t> version() const { return version_; }

 protected:
  // Builds the back-end scene from nothing (dropping what it held).
  virtual void convert(const sg::Scene& scene) = 0;
  // Updates the back-end objects for the containers `changes` names; the
  // scene already holds their new values.
  virtual void sync(const sg::Scene& scene, const sg::MergedChanges& changes) = 0;

 private:
  std::optional<std::uint64_t> version_;
};

}  // namespace tsr::med
