#pragma once
// A scene that follows a source, together with the log of the lists it
// applied, so that consumers at different versions (viewports switched off
// and on, adapters of several back-ends) can each catch up on their own.
#include "tsr/sg/changes/change_log.hpp"
#include "tsr/sg/scene.hpp"

namespace tsr::sg {

class Replica {
 public:
  explicit Replica(std::size_t logCapacity = 256) : log_(logCapacity) {}

  // Applies a delta (logged) or, to an empty replica, a snapshot (which
  // starts a fresh log). Throws ApplyError, leaving everything unchanged.
  void apply(const ChangeListPtr& list);

  const Scene& scene() const { return scene_; }
  std::uint64_t version() const { return scene_.version(); }
  const ChangeLog& log() const { return log_; }

 private:
  Scene scene_;
  ChangeLog log_;
};

}  // namespace tsr::sg
