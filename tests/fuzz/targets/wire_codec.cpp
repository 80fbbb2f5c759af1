#include <cstdlib>

#include "fuzz_targets.hpp"
#include "tsr/sg/errors.hpp"
#include "tsr/sg/replica.hpp"
#include "tsr/sg/wire/wire_codec.hpp"

namespace tsr::fuzz {

// Lists are cut from the stream by their headers, as a node reads them, and
// applied in order, so deltas meet the replica a snapshot built. Small limits
// keep a hostile count from costing the fuzzer its memory budget.
void wireCodec(Bytes bytes) {
  sg::DecodeLimits limits;
  limits.maxMessageBytes = 1 << 20;
  limits.maxArrayElements = 1 << 20;
  sg::Replica replica(4);
  while (bytes.size() >= sg::kWireHeaderBytes) {
    std::size_t length = 0;
    try {
      length = sg::decodeHeader(bytes.first(sg::kWireHeaderBytes), limits);
    } catch (const sg::DecodeError&) {
      return;
    }
    if (length > bytes.size() - sg::kWireHeaderBytes) return;
    const Bytes message = bytes.first(sg::kWireHeaderBytes + length);
    bytes = bytes.subspan(message.size());
    sg::ChangeListPtr list;
    try {
      list = sg::decode(message, limits);
    } catch (const sg::DecodeError&) {
      continue;
    }
    // What decodes must encode to bytes that decode again.
    const std::vector<std::uint8_t> again = sg::encode(*list);
    try {
      sg::decode(again, limits);
    } catch (const sg::DecodeError&) {
      std::abort();
    }
    try {
      replica.apply(list);
    } catch (const sg::ApplyError&) {}
  }
}

}  // namespace tsr::fuzz
