#include "tsr/sg/changes/change_log.hpp"

#include <stdexcept>
#include <string>

namespace tsr::sg {

ChangeLog::ChangeLog(std::size_t capacity) : capacity_(capacity) {
  if (capacity == 0) throw std::invalid_argument("ChangeLog capacity must be at least 1");
}

void ChangeLog::append(ChangeListPtr list) {
  if (!list || list->isSnapshot()) throw std::invalid_argument("ChangeLog holds deltas only");
  std::lock_guard lock(mutex_);
  bool fresh = lists_.empty() && newest_ == 0;
  if (!fresh && list->baseVersion() != newest_)
    throw std::invalid_argument("change list " + std::to_string(list->version()) + " does not follow version " +
                                std::to_string(newest_));
  if (lists_.empty()) base_ = list->baseVersion();
  newest_ = list->version();
  lists_.push_back(std::move(list));
  if (lists_.size() > capacity_) {
    lists_.pop_front();
    base_ = lists_.front()->baseVersion();
  }
}

void ChangeLog::reset(std::uint64_t version) {
  std::lock_guard lock(mutex_);
  lists_.clear();
  base_ = newest_ = version;
}

ChangeLog::SinceResult ChangeLog::since(std::uint64_t v) const {
  std::lock_guard lock(mutex_);
  SinceResult result;
  if (v == newest_) return result;
  if (v < base_ || v > newest_) {
    result.status = CatchUp::TooFarBehind;
    return result;
  }
  result.status = CatchUp::Deltas;
  std::size_t first = static_cast<std::size_t>(v - base_);
  result.lists.assign(lists_.begin() + static_cast<std::ptrdiff_t>(first), lists_.end());
  return result;
}

std::uint64_t ChangeLog::newestVersion() const {
  std::lock_guard lock(mutex_);
  return newest_;
}

std::uint64_t ChangeLog::oldestBaseVersion() const {
  std::lock_guard lock(mutex_);
  return base_;
}

std::size_t ChangeLog::size() const {
  std::lock_guard lock(mutex_);
  return lists_.size();
}

}  // namespace tsr::sg
