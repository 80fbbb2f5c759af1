#pragma once
// The binary form of a change list, for sockets and files.
//
//   header   "TSRC"  protocol u8  kind u8  payload-length u32     (10 bytes)
//   payload  version varint
//            creations varint  changes varint  destructions varint
//            entry*   id varint  type u8  mask varint  size varint  values
//            destr*   id varint  type u8
//
// Little-endian; values are the fields of the mask in ascending order, each
// as field_codec.hpp writes it. Rule for the unknown: a protocol version
// fixes the container types and their fields, so an unknown type, an unknown
// field bit, a creation without every field, trailing bytes, or a length or
// count beyond the bytes that remain or beyond DecodeLimits is rejected with
// a DecodeError naming the byte offset. Nothing is skipped silently.
#include <cstdint>
#include <span>
#include <vector>

#include "tsr/sg/changes/change_list.hpp"
#include "tsr/sg/wire/decode_limits.hpp"

namespace tsr::sg {

inline constexpr std::uint8_t kWireFormatVersion = 2;  // 2: Light lost its unused range
inline constexpr std::size_t kWireHeaderBytes = 10;

std::vector<std::uint8_t> encode(const ChangeList& list);
void encodeAppend(const ChangeList& list, std::vector<std::uint8_t>& out);

// Decodes exactly one encoded change list occupying all of `bytes`.
ChangeListPtr decode(std::span<const std::uint8_t> bytes, const DecodeLimits& limits = {});

// The payload length a header announces, after checking magic, protocol
// and the limit; for framing on streams.
std::size_t decodeHeader(std::span<const std::uint8_t> header, const DecodeLimits& limits = {});

}  // namespace tsr::sg
