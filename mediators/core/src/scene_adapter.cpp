#include "tsr/med/scene_adapter.hpp"

namespace tsr::med {

SceneAdapter::Update SceneAdapter::catchUp(const sg::Replica& replica) {
  if (version_) {
    auto since = replica.log().since(*version_);
    if (since.status == sg::ChangeLog::CatchUp::UpToDate) return Update::None;
    if (since.status == sg::ChangeLog::CatchUp::Deltas) {
      sg::MergedChanges changes(*version_);
      for (const auto& list : since.lists) changes.add(*list);
      sync(replica.scene(), changes);
      version_ = changes.version();
      return Update::Synced;
    }
  }
  convert(replica.scene());
  version_ = replica.version();
  return Update::Converted;
}

}  // namespace tsr::med
