#pragma once
// One or more consecutive change lists folded into a single per-container
// view, for consumers that read the replica's current state and only need
// to know what to look at: a scene adapter catching up after a pause syncs
// once, not once per missed frame.
#include <map>

#include "tsr/sg/changes/change_list.hpp"

namespace tsr::sg {

class MergedChanges {
 public:
  struct Entry {
    ContainerType type = ContainerType::Group;
    bool created = false;    // new since the first list; read every field
    bool destroyed = false;  // gone by the last list
    FieldMask mask = 0;      // fields changed (all of them when created)
    // Array fields changed only by range in every list, with merged ranges;
    // any other masked array field changed whole.
    std::vector<RangedEdit> rangedEdits;
    const RangedEdit* rangedEdit(FieldIndex f) const;
    bool changed(FieldIndex f) const { return (mask & fieldBit(f)) != 0; }
  };

  explicit MergedChanges(std::uint64_t baseVersion) : version_(baseVersion) {}
  // Folds in the next list; throws std::invalid_argument when it does not follow.
  void add(const ChangeList& list);

  // By ascending id; containers created and destroyed within the lists are absent.
  const std::map<ContainerId, Entry>& entries() const { return entries_; }
  bool empty() const { return entries_.empty(); }
  std::uint64_t version() const { return version_; }

 private:
  std::map<ContainerId, Entry> entries_;
  std::map<ContainerId, FieldMask> wholeArrays_;
  std::uint64_t version_;
};

}  // namespace tsr::sg
