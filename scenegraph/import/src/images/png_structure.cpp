#include "images/png_structure.hpp"

#include <array>
#include <cstring>

namespace tsr::sg {
namespace {

std::uint32_t bigEndian(const std::uint8_t* p) {
  return std::uint32_t{p[0]} << 24 | std::uint32_t{p[1]} << 16 | std::uint32_t{p[2]} << 8 | p[3];
}

std::uint32_t crc32(const std::uint8_t* p, std::size_t n) {
  static const std::array<std::uint32_t, 256> table = [] {
    std::array<std::uint32_t, 256> t{};
    for (std::uint32_t i = 0; i < 256; ++i) {
      std::uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = c & 1 ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      t[i] = c;
    }
    return t;
  }();
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) c = table[(c ^ p[i]) & 0xFF] ^ (c >> 8);
  return c ^ 0xFFFFFFFFu;
}

}  // namespace

std::string pngStructureProblem(const std::vector<std::uint8_t>& bytes) {
  static const std::uint8_t signature[] = {0x89, 'P', 'N', 'G', 0x0D, 0x0A, 0x1A, 0x0A};
  if (bytes.size() < sizeof(signature) || std::memcmp(bytes.data(), signature, sizeof(signature)) != 0)
    return "is no PNG (bad signature)";
  std::size_t at = sizeof(signature);
  bool first = true;
  while (at < bytes.size()) {
    if (bytes.size() - at < 12)
      return "is a truncated PNG (a chunk header is cut off at byte " + std::to_string(at) + ")";
    const std::uint32_t length = bigEndian(&bytes[at]);
    if (length > bytes.size() - at - 12)
      return "is a truncated PNG (a chunk at byte " + std::to_string(at) + " runs past the end)";
    const std::string type(reinterpret_cast<const char*>(&bytes[at + 4]), 4);
    if (first && type != "IHDR") return "is a damaged PNG (the first chunk is not IHDR)";
    first = false;
    if (crc32(&bytes[at + 4], length + 4) != bigEndian(&bytes[at + 8 + length]))
      return "is a damaged PNG (CRC mismatch in the " + type + " chunk at byte " + std::to_string(at) + ")";
    at += 12 + std::size_t{length};
    if (type == "IEND") return {};
  }
  return "is a truncated PNG (no IEND chunk)";
}

}  // namespace tsr::sg
