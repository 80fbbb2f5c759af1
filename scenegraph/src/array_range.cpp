#include "tsr/sg/array_range.hpp"

#include <algorithm>

namespace tsr::sg {

void RangeSet::add(ArrayRange r) {
  if (r.begin >= r.end) return;
  // Find the first range that ends at or after r.begin: everything before it
  // is untouched; every range from there that starts at or before r.end merges.
  auto first = std::lower_bound(ranges_.begin(), ranges_.end(), r.begin,
                                [](const ArrayRange& x, std::uint64_t b) { return x.end < b; });
  auto last = first;
  while (last != ranges_.end() && last->begin <= r.end) {
    r.begin = std::min(r.begin, last->begin);
    r.end = std::max(r.end, last->end);
    ++last;
  }
  first = ranges_.erase(first, last);
  ranges_.insert(first, r);
}

std::uint64_t RangeSet::elementCount() const {
  std::uint64_t n = 0;
  for (const auto& r : ranges_) n += r.size();
  return n;
}

}  // namespace tsr::sg
