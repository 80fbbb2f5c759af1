#include "tsr/sg/changes/merged_changes.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

#include "tsr/sg/container_factory.hpp"

namespace tsr::sg {

const RangedEdit* MergedChanges::Entry::rangedEdit(FieldIndex f) const {
  for (const auto& e : rangedEdits)
    if (e.field == f) return &e;
  return nullptr;
}

void MergedChanges::add(const ChangeList& list) {
  if (list.isSnapshot() || list.baseVersion() != version_)
    throw std::invalid_argument("change list " + std::to_string(list.version()) + " does not follow version " +
                                std::to_string(version_));
  for (const auto& c : list.creations()) {
    Entry& e = entries_[c.id];
    e = Entry{};
    e.type = c.type;
    e.created = true;
    e.mask = c.mask;
  }
  for (const auto& c : list.changes()) {
    Entry& e = entries_[c.id];
    e.type = c.type;
    e.mask |= c.mask;
    if (e.created) continue;
    // Fold ranges: a field edited whole at any point stays whole.
    FieldMask& whole = wholeArrays_[c.id];
    const Container& proto = prototype(c.type);
    for (FieldMask m = c.mask; m; m &= m - 1) {
      auto f = static_cast<FieldIndex>(std::countr_zero(m));
      if (proto.fieldInfo(f).kind != FieldKind::Array) continue;
      const RangedEdit* incoming = c.rangedEdit(f);
      auto held = std::find_if(e.rangedEdits.begin(), e.rangedEdits.end(), [&](auto& r) { return r.field == f; });
      if (!incoming || (whole & fieldBit(f))) {
        whole |= fieldBit(f);
        if (held != e.rangedEdits.end()) e.rangedEdits.erase(held);
        continue;
      }
      if (held == e.rangedEdits.end()) {
        e.rangedEdits.push_back(*incoming);
        continue;
      }
      RangeSet merged;
      for (const auto& r : held->ranges) merged.add(r);
      for (const auto& r : incoming->ranges) merged.add(r);
      held->ranges = merged.ranges();
      held->length = incoming->length;
    }
  }
  for (const auto& d : list.destructions()) {
    auto it = entries_.find(d.id);
    if (it != entries_.end() && it->second.created) {
      entries_.erase(it);  // never seen by the consumer
      wholeArrays_.erase(d.id);
      continue;
    }
    Entry& e = entries_[d.id];
    e.type = d.type;
    e.destroyed = true;
    e.rangedEdits.clear();
  }
  version_ = list.version();
}

}  // namespace tsr::sg
