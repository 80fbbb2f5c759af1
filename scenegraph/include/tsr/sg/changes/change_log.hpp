#pragma once
// The last N change lists, so a consumer that has seen version v (a paused
// viewport, a slow node) can catch up with since(v), or learns that it fell
// too far behind and must start again from a snapshot. Safe to use from
// several threads: one appends, any number read.
#include <cstdint>
#include <deque>
#include <mutex>
#include <vector>

#include "tsr/sg/changes/change_list.hpp"

namespace tsr::sg {

class ChangeLog {
 public:
  explicit ChangeLog(std::size_t capacity);

  // Appends the next delta; throws std::invalid_argument when it does not
  // follow the newest list held.
  void append(ChangeListPtr list);
  // Forgets every list: the producer restarted at `version` (a replica that
  // took a snapshot). Consumers at other versions are then too far behind.
  void reset(std::uint64_t version);

  enum class CatchUp { UpToDate, Deltas, TooFarBehind };
  struct SinceResult {
    CatchUp status = CatchUp::UpToDate;
    std::vector<ChangeListPtr> lists;  // in order, when status is Deltas
  };
  // The lists that take a consumer from version v to the newest.
  SinceResult since(std::uint64_t v) const;

  std::uint64_t newestVersion() const;
  std::uint64_t oldestBaseVersion() const;
  std::size_t size() const;
  std::size_t capacity() const { return capacity_; }

 private:
  mutable std::mutex mutex_;
  std::deque<ChangeListPtr> lists_;
  std::size_t capacity_;
  std::uint64_t base_ = 0;    // version before the oldest list held
  std::uint64_t newest_ = 0;  // version after the newest list held
};

}  // namespace tsr::sg
