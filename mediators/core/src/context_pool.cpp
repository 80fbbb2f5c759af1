#include "tsr/med/context_pool.hpp"

namespace tsr::med {

std::size_t ContextPool::live() const {
  std::lock_guard lock(mutex_);
  std::size_t n = 0;
  for (const auto& [key, weak] : contexts_)
    if (!weak.expired()) ++n;
  return n;
}

}  // namespace tsr::med
