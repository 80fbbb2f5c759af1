#include "tsr/cluster/frame_header.hpp"

#include <algorithm>
#include <array>
#include <string>

#include "tsr/cluster/protocol_error.hpp"
#include "tsr/sg/wire/byte_reader.hpp"
#include "tsr/sg/wire/byte_writer.hpp"

namespace tsr::cluster {

using Kind = ProtocolError::Kind;

FrameHeader decodeFrameHeader(std::span<const std::uint8_t> bytes, std::uint8_t expectedVersion) {
  if (bytes.size() != kFrameHeaderBytes)
    throw ProtocolError(Kind::Malformed, "frame header must be " + std::to_string(kFrameHeaderBytes) + " bytes");
  if (!std::equal(kFrameMagic.begin(), kFrameMagic.end(), bytes.begin()))
    throw ProtocolError(Kind::BadMagic, "not a Tessera node frame (bad magic)");
  sg::ByteReader r(bytes.subspan(4), 4);
  FrameHeader h;
  h.version = r.u8();
  std::uint8_t type = r.u8();
  h.length = r.u32();
  if (h.version != expectedVersion)
    throw ProtocolError(Kind::VersionMismatch, "peer speaks protocol version " + std::to_string(h.version) +
                                                   ", this build speaks " + std::to_string(expectedVersion));
  const MessageSpec* s = findSpec(type);
  if (!s) throw ProtocolError(Kind::UnknownType, "unknown message type " + std::to_string(type));
  h.type = s->type;
  if (h.length > s->maxPayload)
    throw ProtocolError(Kind::Oversized, std::string(s->name) + " announces " + std::to_string(h.length) +
                                             " bytes, the maximum is " + std::to_string(s->maxPayload));
  return h;
}

void writeFrameHeader(std::vector<std::uint8_t>& out, const FrameHeader& header) {
  sg::ByteWriter w(out);
  w.raw(kFrameMagic.data(), kFrameMagic.size());
  w.u8(header.version);
  w.u8(static_cast<std::uint8_t>(header.type));
  w.u32(header.length);
}

const char* name(ProtocolError::Kind kind) {
  // In Kind's order. The assert catches a table out of step with the
  // enumerators up to the last one named there; a kind appended after it
  // needs its name here and the assert moved to it.
  static constexpr std::array kNames{"bad magic", "version mismatch",      "unknown type", "oversized", "unexpected",
                                     "malformed", "authentication failed", "rejected",     "timeout",   "closed"};
  static_assert(kNames.size() == std::size_t(Kind::Closed) + 1);
  return std::size_t(kind) < kNames.size() ? kNames[std::size_t(kind)] : "unknown";
}

}  // namespace tsr::cluster
