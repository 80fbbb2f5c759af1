#pragma once
// A scene that follows a source, together with the log of the lists it
// applied, so that consumers at different versions (viewports switched off
// and on, adapters of several back-ends) can each catch up on their own.
#include "tsr/sg/changes/change_log.hpp"
#include "tsr/sg/scene.hpp"

#include <vector>

namespace tsr::sg {

class Replica {
 public:
  explicit Replica(std::size_t logCapacity = 256) : log_(logCapacity) {}

  // Applies a delta (logged) or, to an empty replica, a snapshot (which
  // starts a fresh log). Parts of a snapshot (splitSnapshot) are held until
  // its last part arrives, then applied as one. Throws ApplyError, leaving
  // the scene unchanged (and the parts held so far dropped).
  void apply(const ChangeListPtr& list);
  // Parts of a snapshot have arrived, and its last has not.
  bool awaitingSnapshot() const { return !parts_.empty(); }

  const Scene& scene() const { return scene_; }
  std::uint64_t version() const { return scene_.version(); }
  const ChangeLog& log() const { return log_; }

 private:
  Scene scene_;
  ChangeLog log_;
  std::vector<ChangeListPtr> parts_;
};

}  // namespace tsr::sg
