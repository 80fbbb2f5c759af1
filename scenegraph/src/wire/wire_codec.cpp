#include "tsr/sg/wire/wire_codec.hpp"

#include <algorithm>
#include <cstring>

#include "tsr/sg/wire/byte_reader.hpp"
#include "tsr/sg/wire/byte_writer.hpp"

namespace tsr::sg {

namespace {
constexpr std::uint8_t kMagic[4] = {'T', 'S', 'R', 'C'};

// An entry's values with its shared arrays' elements written where they
// belong, so the bytes are the same whether a list held slices or not.
void writeValues(ByteWriter& w, const ChangeList& list, const ChangeEntry& e) {
  const auto slices = list.slices(e);
  std::size_t size = e.valueSize;
  for (const SharedSlice& slice : slices) size += slice.size;
  w.varint(size);
  const std::uint8_t* values = list.values().data();
  std::uint64_t from = e.valueOffset;
  for (const SharedSlice& slice : slices) {
    w.raw(values + from, slice.offset - from);
    w.raw(slice.bytes, slice.size);
    from = slice.offset;
  }
  w.raw(values + from, e.valueOffset + e.valueSize - from);
}
}  // namespace

void encodeAppend(const ChangeList& list, std::vector<std::uint8_t>& out) {
  ByteWriter w(out);
  std::size_t start = w.size();
  w.raw(kMagic, sizeof kMagic);
  w.u8(kWireFormatVersion);
  w.u8(static_cast<std::uint8_t>(list.kind()));
  w.u32(0);  // payload length, patched below
  w.varint(list.version());
  w.varint(list.creations().size());
  w.varint(list.changes().size());
  w.varint(list.destructions().size());
  for (const auto* entries : {&list.creations(), &list.changes()}) {
    for (const auto& e : *entries) {
      w.varint(e.id);
      w.u8(static_cast<std::uint8_t>(e.type));
      w.varint(e.mask);
      writeValues(w, list, e);
    }
  }
  for (const auto& d : list.destructions()) {
    w.varint(d.id);
    w.u8(static_cast<std::uint8_t>(d.type));
  }
  std::size_t payload = w.size() - start - kWireHeaderBytes;
  if (payload > UINT32_MAX) throw std::length_error("change list too large to encode");
  w.patchU32(start + 6, static_cast<std::uint32_t>(payload));
}

std::vector<std::uint8_t> encode(const ChangeList& list) {
  std::vector<std::uint8_t> out;
  encodeAppend(list, out);
  return out;
}

std::size_t decodeHeader(std::span<const std::uint8_t> header, const DecodeLimits& limits) {
  ByteReader r(header);
  auto magic = r.take(sizeof kMagic, "magic");
  if (std::memcmp(magic.data(), kMagic, sizeof kMagic) != 0)
    throw DecodeError(0, "not a Tessera change list (bad magic)");
  std::uint8_t protocol = r.u8();
  if (protocol != kWireFormatVersion)
    throw DecodeError(4, "protocol version " + std::to_string(protocol) + ", this build speaks " +
                             std::to_string(kWireFormatVersion));
  std::uint8_t kind = r.u8();
  if (kind > 2) throw DecodeError(5, "unknown change list kind " + std::to_string(kind));
  std::uint32_t length = r.u32();
  if (length > limits.maxMessageBytes)
    throw DecodeError(6, "payload of " + std::to_string(length) + " bytes exceeds the limit of " +
                             std::to_string(limits.maxMessageBytes));
  return length;
}

ChangeListPtr decode(std::span<const std::uint8_t> bytes, const DecodeLimits& limits) {
  if (bytes.size() < kWireHeaderBytes)
    throw DecodeError(bytes.size(), "truncated header: " + std::to_string(bytes.size()) + " of " +
                                        std::to_string(kWireHeaderBytes) + " bytes");
  std::size_t length = decodeHeader(bytes.first(kWireHeaderBytes), limits);
  if (bytes.size() - kWireHeaderBytes != length)
    throw DecodeError(kWireHeaderBytes, "header announces " + std::to_string(length) + " payload bytes, " +
                                            std::to_string(bytes.size() - kWireHeaderBytes) + " present");
  auto kind = static_cast<ChangeList::Kind>(bytes[5]);
  ByteReader r(bytes.subspan(kWireHeaderBytes), kWireHeaderBytes);
  std::uint64_t version = r.varint();
  if (kind == ChangeList::Kind::Delta && version == 0) r.fail("a delta cannot have version 0");
  // Each entry takes at least 4 bytes (id, type, mask, size), a destruction 2.
  std::size_t nCreations = r.count(limits.maxEntries, 4, "creation");
  std::size_t nChanges = r.count(limits.maxEntries, 4, "change");
  std::size_t nDestructions = r.count(limits.maxEntries, 2, "destruction");
  if (kind != ChangeList::Kind::Delta && (nChanges || nDestructions)) r.fail("a snapshot holds creations only");

  ChangeList::Builder builder(kind, version);
  ContainerId previous = 0;
  for (std::size_t i = 0; i < nCreations + nChanges; ++i) {
    bool creation = i < nCreations;
    if (i == nCreations) previous = 0;
    std::size_t at = r.offset();
    ContainerId id = r.varint();
    if (id <= previous) throw DecodeError(at, "entry ids must ascend (id " + std::to_string(id) + ")");
    previous = id;
    std::uint64_t type = r.u8();
    FieldMask mask = r.varint();
    std::size_t size = r.count(limits.maxMessageBytes, 1, "value byte");
    std::size_t valuesAt = r.offset();
    builder.addEncoded(creation, id, type, mask, r.take(size, "values"), limits, valuesAt);
  }
  previous = 0;
  for (std::size_t i = 0; i < nDestructions; ++i) {
    std::size_t at = r.offset();
    ContainerId id = r.varint();
    if (id <= previous) throw DecodeError(at, "destruction ids must ascend (id " + std::to_string(id) + ")");
    previous = id;
    std::uint64_t type = r.u8();
    if (!isKnownType(type)) throw DecodeError(at, "unknown container type " + std::to_string(type));
    builder.addDestruction(id, static_cast<ContainerType>(type));
  }
  if (!r.atEnd()) r.fail(std::to_string(r.remaining()) + " bytes after the last entry");
  return builder.finish();
}

}  // namespace tsr::sg
