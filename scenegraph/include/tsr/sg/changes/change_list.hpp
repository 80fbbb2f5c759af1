#pragma once
// One frame's changes to a scene, immutable once built. The vocabulary, as
// precise as it needs to be:
//  - creation:    a container with this id and type now exists, with every
//                 field set to the values carried. Ids are never reused.
//  - change:      these fields (mask) of an existing container now hold the
//                 values carried; an array field edited by range carries
//                 only those element runs plus the length it must have.
//                 Setting a field several times in a frame gives one change
//                 with the last value.
//  - destruction: the container no longer exists. Whatever referred to it
//                 was changed in the same list to refer to it no more.
// Entries come creations first, then changes, then destructions, each in
// ascending id order. A snapshot is a list of creations only, describing a
// whole scene at its version, for replicas that start empty. A snapshot too
// large for one message goes as parts (splitSnapshot): creations in id
// order, each part but the last of kind SnapshotPart, the last a Snapshot;
// a replica applies them together when the last arrives.
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "tsr/sg/array_range.hpp"
#include "tsr/sg/types.hpp"
#include "tsr/sg/wire/decode_limits.hpp"
#include "tsr/sg/wire/shared_slices.hpp"

namespace tsr::sg {

class Container;

// A ranged array edit: the array has `length` elements, of which `ranges` changed.
struct RangedEdit {
  FieldIndex field = 0;
  std::uint64_t length = 0;
  std::vector<ArrayRange> ranges;
};

// A reference held after the change by one of the entry's fields.
struct Reference {
  FieldIndex field = 0;
  ContainerId target = kNoContainer;
};

struct ChangeEntry {
  ContainerId id = kNoContainer;
  ContainerType type = ContainerType::Group;
  FieldMask mask = 0;
  std::vector<RangedEdit> rangedEdits;  // only fields edited by range
  std::vector<Reference> references;    // of the masked reference fields
  std::uint64_t valueOffset = 0;        // into ChangeList::values()
  std::uint64_t valueSize = 0;

  bool changed(FieldIndex f) const { return (mask & fieldBit(f)) != 0; }
  // The ranges of field f when it was edited by range, else null (whole or unchanged).
  const RangedEdit* rangedEdit(FieldIndex f) const;
};

struct Destruction {
  ContainerId id = kNoContainer;
  ContainerType type = ContainerType::Group;
};

class ChangeList {
 public:
  enum class Kind : std::uint8_t { Delta = 0, Snapshot = 1, SnapshotPart = 2 };

  Kind kind() const { return kind_; }
  bool isSnapshot() const { return kind_ == Kind::Snapshot; }
  // A part of a snapshot that more parts follow.
  bool isSnapshotPart() const { return kind_ == Kind::SnapshotPart; }
  // A whole scene or a part of one, rather than a delta.
  bool carriesSnapshot() const { return kind_ != Kind::Delta; }
  // The scene version after this list; a delta applies to baseVersion().
  std::uint64_t version() const { return version_; }
  std::uint64_t baseVersion() const { return kind_ == Kind::Delta ? version_ - 1 : 0; }

  const std::vector<ChangeEntry>& creations() const { return creations_; }
  const std::vector<ChangeEntry>& changes() const { return changes_; }
  const std::vector<Destruction>& destructions() const { return destructions_; }
  std::span<const std::uint8_t> values(const ChangeEntry& e) const;
  const std::vector<std::uint8_t>& values() const { return values_; }
  // Whole arrays held by reference, by their place in values(): a list
  // carries a mesh without copying it (see SharedSlice).
  const SharedSlices& slices() const { return slices_; }
  // The slices of one entry's values.
  std::span<const SharedSlice> slices(const ChangeEntry& e) const;

  bool empty() const { return creations_.empty() && changes_.empty() && destructions_.empty(); }
  // Field changes carried by change entries (creations count each field).
  std::uint64_t fieldChangeCount() const;

  // Builds a list. Entries from live containers are trusted; entries from
  // bytes are checked field by field, so a built list is always well formed.
  class Builder {
   public:
    Builder(Kind kind, std::uint64_t version);
    ~Builder();
    // Serialises the masked fields of a container; `edits` gives the ranges
    // of fields edited by range (others go whole).
    void addCreation(const Container& c);
    void addChange(const Container& c, FieldMask mask, const std::vector<RangedEdit>& edits);
    void addDestruction(ContainerId id, ContainerType type);
    // Adds a creation or change of another list as it stands there (its
    // values and the arrays it shares).
    void addCopy(const ChangeList& from, const ChangeEntry& e, bool creation);
    // Adds an entry from untrusted serialised values; throws DecodeError
    // (offsets relative to `baseOffset`) when they are malformed. Whole
    // arrays are kept as shared arrays, ready for a replica to take.
    void addEncoded(bool creation, ContainerId id, std::uint64_t rawType, FieldMask mask,
                    std::span<const std::uint8_t> values, const DecodeLimits& limits, std::size_t baseOffset);
    std::shared_ptr<const ChangeList> finish();

   private:
    ChangeEntry& begin(bool creation, ContainerId id, ContainerType type, FieldMask mask);
    void addEntry(bool creation, const Container& c, FieldMask mask, const std::vector<RangedEdit>& edits);
    std::shared_ptr<ChangeList> list_;
    std::vector<std::unique_ptr<Container>> scratch_;  // one per type, for checking encoded values
  };

 private:
  ChangeList() = default;
  Kind kind_ = Kind::Delta;
  std::uint64_t version_ = 0;
  std::vector<ChangeEntry> creations_;
  std::vector<ChangeEntry> changes_;
  std::vector<Destruction> destructions_;
  std::vector<std::uint8_t> values_;
  SharedSlices slices_;
};

using ChangeListPtr = std::shared_ptr<const ChangeList>;

// A snapshot as parts whose encoding (sg::encode) takes about `partBytes`
// each: the snapshot itself when it fits. A container larger than a part
// goes in a part of its own, which must still fit `maxBytes` (a message's
// bound; by default the part size): otherwise std::length_error names it.
std::vector<ChangeListPtr> splitSnapshot(const ChangeListPtr& snapshot, std::size_t partBytes,
                                         std::size_t maxBytes = 0);
// The parts of one snapshot, in order, as the one snapshot they came from.
// Throws ApplyError when they are not the parts of one snapshot.
ChangeListPtr joinSnapshot(std::span<const ChangeListPtr> parts);

}  // namespace tsr::sg
