#pragma once
// Back-end instances with their converted scenes, shared by every viewport
// on the same replica that asks for the same key (the two eyes of a stereo
// pair share one conversion). Contexts are ref-counted: the last viewport
// to let go frees it.
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

namespace tsr::med {

class ContextPool {
 public:
  template <class C>
  std::shared_ptr<C> acquire(const std::string& key, const std::function<std::shared_ptr<C>()>& make) {
    std::lock_guard lock(mutex_);
    if (auto held = std::static_pointer_cast<C>(contexts_[key].lock())) return held;
    auto made = make();
    contexts_[key] = made;
    return made;
  }
  // Contexts still in use by someone.
  std::size_t live() const;

 private:
  mutable std::mutex mutex_;
  std::map<std::string, std::weak_ptr<void>> contexts_;
};

}  // namespace tsr::med
