#include "tsr/sg/change_log.hpp"

#include <stdexcept>
#include <string>

namespace tsr::sg {

ChangeLog::ChangeLog(std::size_t capacity) : capacity_(capacity) {
  if (capacity == 0) throw std::invalid_argument("ChangeLog capacity must be at least 1");
}

void ChangeLog::append(ChangeListPtr list) {
  if (!list || list->isSnapshot()) throw std::invalid_argument("ChangeLog holds deltas only");
  std::lock_guard lock(mutex_);
  if (!lists_.empty() && list->baseVersion() != lists_.back()->version())
    throw std::invalid_argument("change list " + std::to_string(list->version()) + " does not follow version " +
                                std::to_string(lists_.back()->version()));
  lists_.push_back(std::move(list));
  if (lists_.size() > capacity_) lists_.pop_front();
}

ChangeLog::SinceResult ChangeLog::since(std::uint64_t v) const {
  std::lock_guard lock(mutex_);
  SinceResult result;
  if (lists_.empty() || v == lists_.back()->version()) return result;
  if (v < lists_.front()->baseVersion() || v > lists_.back()->version()) {
    result.status = CatchUp::TooFarBehind;
    return result;
  }
  result.status = CatchUp::Deltas;
  std::size_t first = static_cast<std::size_t>(v - lists_.front()->baseVersion());
  result.lists.assign(lists_.begin() + static_cast<std::ptrdiff_t>(first), lists_.end());
  return result;
}

std::uint64_t ChangeLog::newestVersion() const {
  std::lock_guard lock(mutex_);
  return lists_.empty() ? 0 : lists_.back()->version();
}

std::uint64_t ChangeLog::oldestBaseVersion() const {
  std::lock_guard lock(mutex_);
  return lists_.empty() ? 0 : lists_.front()->baseVersion();
}

std::size_t ChangeLog::size() const {
  std::lock_guard lock(mutex_);
  return lists_.size();
}

}  // namespace tsr::sg
