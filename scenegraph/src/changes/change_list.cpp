#include "tsr/sg/changes/change_list.hpp"

#include <algorithm>
#include <bit>
#include <stdexcept>
#include <string>

#include "tsr/sg/container.hpp"
#include "tsr/sg/container_factory.hpp"

namespace tsr::sg {

const RangedEdit* ChangeEntry::rangedEdit(FieldIndex f) const {
  for (const auto& e : rangedEdits)
    if (e.field == f) return &e;
  return nullptr;
}

std::span<const std::uint8_t> ChangeList::values(const ChangeEntry& e) const {
  return std::span<const std::uint8_t>(values_).subspan(e.valueOffset, e.valueSize);
}

std::span<const SharedSlice> ChangeList::slices(const ChangeEntry& e) const {
  // A slice follows at least its encoding byte and count, so it belongs to
  // the entry whose values it ends or lies inside: (start, end].
  auto after = [](std::uint64_t at, const SharedSlice& s) { return at < s.offset; };
  auto first = std::upper_bound(slices_.begin(), slices_.end(), e.valueOffset, after);
  auto last = std::upper_bound(first, slices_.end(), e.valueOffset + e.valueSize, after);
  return {first, last};
}

std::uint64_t ChangeList::fieldChangeCount() const {
  std::uint64_t n = 0;
  for (const auto& e : creations_) n += std::popcount(e.mask);
  for (const auto& e : changes_) n += std::popcount(e.mask);
  return n;
}

ChangeList::Builder::Builder(Kind kind, std::uint64_t version) : list_(new ChangeList) {
  list_->kind_ = kind;
  list_->version_ = version;
}

ChangeList::Builder::~Builder() = default;

ChangeEntry& ChangeList::Builder::begin(bool creation, ContainerId id, ContainerType type, FieldMask mask) {
  auto& entries = creation ? list_->creations_ : list_->changes_;
  ChangeEntry& e = entries.emplace_back();
  e.id = id;
  e.type = type;
  e.mask = mask;
  e.valueOffset = list_->values_.size();
  return e;
}

namespace {
void collectReferences(const Container& c, FieldMask mask, std::vector<Reference>& out) {
  for (FieldMask refs = mask & c.referenceFields(); refs; refs &= refs - 1) {
    auto f = static_cast<FieldIndex>(std::countr_zero(refs));
    c.forEachReference(f, [&](ContainerId id) { out.push_back({f, id}); });
  }
}
}  // namespace

void ChangeList::Builder::addCreation(const Container& c) { addEntry(true, c, c.allFields(), {}); }

void ChangeList::Builder::addChange(const Container& c, FieldMask mask, const std::vector<RangedEdit>& edits) {
  addEntry(false, c, mask, edits);
}

void ChangeList::Builder::addEntry(bool creation, const Container& c, FieldMask mask,
                                   const std::vector<RangedEdit>& edits) {
  ChangeEntry& e = begin(creation, c.id(), c.type(), mask);
  ByteWriter w(list_->values_, &list_->slices_);
  for (FieldMask m = mask; m; m &= m - 1) {
    auto f = static_cast<FieldIndex>(std::countr_zero(m));
    auto edit = std::find_if(edits.begin(), edits.end(), [&](const RangedEdit& r) { return r.field == f; });
    if (edit != edits.end()) {
      c.writeField(f, w, &edit->ranges);
      e.rangedEdits.push_back(*edit);
    } else {
      c.writeField(f, w, nullptr);
    }
  }
  e.valueSize = list_->values_.size() - e.valueOffset;
  collectReferences(c, mask, e.references);
}

std::shared_ptr<const ChangeList> ChangeList::Builder::finish() { return std::move(list_); }

void ChangeList::Builder::addCopy(const ChangeList& from, const ChangeEntry& e, bool creation) {
  ChangeEntry& copy = begin(creation, e.id, e.type, e.mask);
  const std::uint64_t shift = copy.valueOffset - e.valueOffset;  // unsigned wrap-around cancels in the sum
  auto values = from.values(e);
  list_->values_.insert(list_->values_.end(), values.begin(), values.end());
  copy.valueSize = e.valueSize;
  copy.rangedEdits = e.rangedEdits;
  copy.references = e.references;
  for (const SharedSlice& slice : from.slices(e)) {
    list_->slices_.push_back(slice);
    list_->slices_.back().offset += shift;
  }
}

namespace {
// What an entry takes on the wire, within a few bytes (id, type, mask and
// size varints at most 30).
std::size_t encodedBytes(const ChangeList& list, const ChangeEntry& e) {
  std::size_t n = e.valueSize + 30;
  for (const SharedSlice& slice : list.slices(e)) n += slice.size;
  return n;
}
}  // namespace

std::vector<ChangeListPtr> splitSnapshot(const ChangeListPtr& whole, std::size_t partBytes, std::size_t maxBytes) {
  const ChangeList& snapshot = *whole;
  if (!snapshot.isSnapshot()) throw std::invalid_argument("splitSnapshot: not a snapshot");
  if (maxBytes == 0) maxBytes = partBytes;
  partBytes = std::min(partBytes, maxBytes);
  constexpr std::size_t kListOverhead = 64;  // header, version and counts
  std::size_t total = kListOverhead;
  for (const auto& e : snapshot.creations()) total += encodedBytes(snapshot, e);
  if (total <= partBytes) return {whole};

  std::vector<std::vector<const ChangeEntry*>> groups(1);
  std::size_t bytes = kListOverhead;
  for (const auto& e : snapshot.creations()) {
    std::size_t n = encodedBytes(snapshot, e);
    if (n + kListOverhead > maxBytes)
      throw std::length_error("container " + std::to_string(e.id) + " takes " + std::to_string(n) +
                              " bytes, more than a message of " + std::to_string(maxBytes) + " can carry");
    if (bytes + n > partBytes && !groups.back().empty()) {  // a larger container goes alone
      groups.emplace_back();
      bytes = kListOverhead;
    }
    groups.back().push_back(&e);
    bytes += n;
  }
  std::vector<ChangeListPtr> parts;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    ChangeList::Builder b(g + 1 == groups.size() ? ChangeList::Kind::Snapshot : ChangeList::Kind::SnapshotPart,
                          snapshot.version());
    for (const ChangeEntry* e : groups[g]) b.addCopy(snapshot, *e, true);
    parts.push_back(b.finish());
  }
  return parts;
}

ChangeListPtr joinSnapshot(std::span<const ChangeListPtr> parts) {
  if (parts.empty()) throw ApplyError("no snapshot parts to join");
  const std::uint64_t version = parts.back()->version();
  ContainerId previous = kNoContainer;
  ChangeList::Builder b(ChangeList::Kind::Snapshot, version);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const ChangeList& part = *parts[i];
    const bool last = i + 1 == parts.size();
    if (last ? !part.isSnapshot() : !part.isSnapshotPart())
      throw ApplyError("snapshot parts must end with the snapshot and hold no other list");
    if (part.version() != version)
      throw ApplyError("snapshot part of version " + std::to_string(part.version()) + " among parts of version " +
                       std::to_string(version));
    for (const auto& e : part.creations()) {
      if (e.id <= previous) throw ApplyError("snapshot parts repeat or reorder container " + std::to_string(e.id));
      previous = e.id;
      b.addCopy(part, e, true);
    }
  }
  return b.finish();
}

void ChangeList::Builder::addDestruction(ContainerId id, ContainerType type) {
  list_->destructions_.push_back({id, type});
}

void ChangeList::Builder::addEncoded(bool creation, ContainerId id, std::uint64_t rawType, FieldMask mask,
                                     std::span<const std::uint8_t> values, const DecodeLimits& limits,
                                     std::size_t baseOffset) {
  if (!isKnownType(rawType)) throw DecodeError(baseOffset, "unknown container type " + std::to_string(rawType));
  auto type = static_cast<ContainerType>(rawType);
  if (id == kNoContainer) throw DecodeError(baseOffset, "entry with container id 0");
  if (scratch_.empty()) scratch_.resize(kContainerTypeCount + 1);
  auto& scratch = scratch_[rawType];
  if (!scratch) scratch = makeContainer(type);
  FieldMask all = scratch->allFields();
  if (mask & ~all)
    throw DecodeError(baseOffset, "unknown field " + std::to_string(std::countr_zero(mask & ~all)) + " for " +
                                      std::string(typeName(type)));
  if (creation && mask != all)
    throw DecodeError(baseOffset, "creation of " + std::string(typeName(type)) + " without every field");
  if (!creation && mask == 0) throw DecodeError(baseOffset, "change entry without fields");

  ChangeEntry& e = begin(creation, id, type, mask);
  ByteReader r(values, baseOffset);
  FieldReadContext ctx{limits, /*scan=*/true};
  SharedSlices collected;
  ctx.collected = &collected;
  for (FieldMask m = mask; m; m &= m - 1) {
    auto f = static_cast<FieldIndex>(std::countr_zero(m));
    ctx.sawRanges = false;
    scratch->readField(f, r, ctx);
    if (ctx.sawRanges) {
      if (creation) r.fail("a creation carries whole arrays, not ranges");
      e.rangedEdits.push_back({f, ctx.rangedTotal, ctx.ranges});
    }
  }
  if (!r.atEnd()) r.fail(std::to_string(r.remaining()) + " bytes left over after the fields");
  collectReferences(*scratch, mask, e.references);
  // The bytes without the collected arrays' elements, which the list holds
  // as slices at the places they leave.
  std::size_t from = 0;
  for (SharedSlice& slice : collected) {
    std::size_t at = slice.offset - baseOffset;
    list_->values_.insert(list_->values_.end(), values.begin() + static_cast<std::ptrdiff_t>(from),
                          values.begin() + static_cast<std::ptrdiff_t>(at));
    from = at + slice.size;
    slice.offset = list_->values_.size();
    list_->slices_.push_back(std::move(slice));
  }
  list_->values_.insert(list_->values_.end(), values.begin() + static_cast<std::ptrdiff_t>(from), values.end());
  e.valueSize = list_->values_.size() - e.valueOffset;
}

}  // namespace tsr::sg
