#include "tsr/cluster/messages.hpp"

#include <algorithm>
#include <array>
#include <exception>

#include "tsr/cluster/protocol_error.hpp"
#include "tsr/sg/errors.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace tsr::cluster {

const char* name(ErrorReport::Kind kind) {
  // Indexed by the wire number. The assert catches a table out of step with
  // the kinds up to PrepareFailed; a kind appended after it needs its name
  // here and the assert moved to it.
  static constexpr std::array kNames{"protocol violation", "scene rejected", "unknown back-end",
                                     "invalid parameter",  "render failed",  "prepare failed"};
  static_assert(kNames.size() == std::size_t(ErrorReport::Kind::PrepareFailed) + 1);
  return std::size_t(kind) < kNames.size() ? kNames[std::size_t(kind)] : "unknown";
}

Frame frameFromPayload(MessageType type, std::span<const std::uint8_t> payload) {
  if (payload.size() > spec(type).maxPayload)
    throw ProtocolError(
        ProtocolError::Kind::Oversized,
        std::string(name(type)) + " of " + std::to_string(payload.size()) + " bytes exceeds its maximum");
  auto bytes = std::make_shared<std::vector<std::uint8_t>>();
  bytes->reserve(kFrameHeaderBytes + payload.size());
  writeFrameHeader(*bytes, {kProtocolVersion, type, static_cast<std::uint32_t>(payload.size())});
  bytes->insert(bytes->end(), payload.begin(), payload.end());
  return bytes;
}

Frame changeListFrame(MessageType type, const sg::ChangeList& list) {
  auto bytes = std::make_shared<std::vector<std::uint8_t>>();
  writeFrameHeader(*bytes, {kProtocolVersion, type, 0});
  sg::encodeAppend(list, *bytes);
  const std::size_t payload = bytes->size() - kFrameHeaderBytes;
  if (payload > spec(type).maxPayload)
    throw ProtocolError(ProtocolError::Kind::Oversized,
                        std::string(name(type)) + " of " + std::to_string(payload) + " bytes exceeds its maximum");
  std::vector<std::uint8_t> header;
  writeFrameHeader(header, {kProtocolVersion, type, static_cast<std::uint32_t>(payload)});
  std::copy(header.begin(), header.end(), bytes->begin());
  return bytes;
}

void checkDecodable(MessageType expected, const Message& message) {
  if (message.type != expected)
    throw ProtocolError(ProtocolError::Kind::Unexpected,
                        std::string("expected ") + name(expected) + ", got " + name(message.type));
}

void rethrowAsMalformed(MessageType type) {
  try {
    throw;
  } catch (const sg::DecodeError& e) {
    throw ProtocolError(ProtocolError::Kind::Malformed, std::string(name(type)) + ": " + e.what());
  }
}

}  // namespace tsr::cluster
