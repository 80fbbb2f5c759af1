#pragma once
// Upper bounds a decoder enforces on untrusted input, on top of "no count
// larger than the bytes that remain".
#include <cstddef>
#include <cstdint>

namespace tsr::sg {

struct DecodeLimits {
  std::size_t maxMessageBytes = std::size_t{1} << 30;   // one change list on the wire
  std::size_t maxEntries = std::size_t{1} << 22;        // containers per change list
  std::size_t maxArrayElements = std::size_t{1} << 28;  // elements of one array field
  std::size_t maxRanges = std::size_t{1} << 20;         // sub-ranges of one array field
  std::size_t maxStringBytes = std::size_t{1} << 16;    // names, attachment keys and strings
  std::size_t maxAttachments = 1024;                    // attachments per container
};

}  // namespace tsr::sg
