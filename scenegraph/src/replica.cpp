#include "tsr/sg/replica.hpp"

namespace tsr::sg {

void Replica::apply(const ChangeListPtr& list) {
  scene_.apply(*list);
  if (!list->isSnapshot()) {
    log_.append(list);
  } else {
    log_.reset(list->version());
  }
}

}  // namespace tsr::sg
