#include "tsr/sg/replica.hpp"

namespace tsr::sg {

void Replica::apply(const ChangeListPtr& list) {
  if (list->isSnapshotPart() || (list->isSnapshot() && !parts_.empty())) {
    if (scene_.size() != 0 || scene_.version() != 0) {
      parts_.clear();
      throw ApplyError("a snapshot part applies only to an empty replica");
    }
    parts_.push_back(list);
    if (list->isSnapshotPart()) return;
    std::vector<ChangeListPtr> parts;
    parts.swap(parts_);  // dropped whether the whole applies or not
    ChangeListPtr whole = joinSnapshot(parts);
    scene_.apply(*whole);
    log_.reset(whole->version());
    return;
  }
  scene_.apply(*list);
  if (!list->isSnapshot()) {
    log_.append(list);
  } else {
    log_.reset(list->version());
  }
}

}  // namespace tsr::sg
