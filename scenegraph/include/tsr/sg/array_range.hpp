#pragma once
// Element ranges of an array field edited within one frame. Overlapping and
// touching ranges are merged, so a frame's edits travel as few disjoint runs.
#include <cstdint>
#include <vector>

namespace tsr::sg {

struct ArrayRange {
  std::uint64_t begin = 0;
  std::uint64_t end = 0;  // exclusive
  std::uint64_t size() const { return end - begin; }
  friend bool operator==(const ArrayRange&, const ArrayRange&) = default;
};

// Sorted, disjoint, non-adjacent ranges.
class RangeSet {
 public:
  void add(ArrayRange r);
  const std::vector<ArrayRange>& ranges() const { return ranges_; }
  std::uint64_t elementCount() const;
  bool empty() const { return ranges_.empty(); }

 private:
  std::vector<ArrayRange> ranges_;
};

}  // namespace tsr::sg
