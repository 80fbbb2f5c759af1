#pragma once
// Bounded reader over untrusted bytes: every read checks what remains and
// throws DecodeError with the offset; nothing is allocated from a length
// before that length has been checked against the bytes that remain.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

#include "tsr/sg/errors.hpp"

namespace tsr::sg {

class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes, std::size_t baseOffset = 0)
      : bytes_(bytes), base_(baseOffset) {}

  std::size_t offset() const { return base_ + pos_; }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  bool atEnd() const { return pos_ == bytes_.size(); }

  [[noreturn]] void fail(const std::string& reason) const { throw DecodeError(offset(), reason); }

  std::uint8_t u8() {
    need(1, "byte");
    return bytes_[pos_++];
  }
  std::uint32_t u32() {
    std::uint32_t v;
    copy(&v, sizeof v, "32-bit integer");
    return v;
  }
  std::uint64_t varint() {
    std::uint64_t v = 0;
    for (unsigned shift = 0;; shift += 7) {
      if (shift > 63) fail("varint longer than 10 bytes");
      std::uint8_t b = u8();
      if (shift == 63 && (b & 0x7e)) fail("varint overflows 64 bits");
      v |= std::uint64_t{b & 0x7fu} << shift;
      if (!(b & 0x80)) return v;
    }
  }
  std::int64_t svarint() {
    std::uint64_t z = varint();
    return static_cast<std::int64_t>((z >> 1) ^ (~(z & 1) + 1));
  }
  // A count that must not exceed `max`, and whose elements, each at least
  // `minElementBytes` long, must fit in the bytes that remain.
  std::size_t count(std::size_t max, std::size_t minElementBytes, const char* what) {
    std::size_t at = offset();
    std::uint64_t n = varint();
    if (n > max)
      throw DecodeError(at,
                        std::string(what) + " count " + std::to_string(n) + " exceeds limit " + std::to_string(max));
    if (minElementBytes && n > remaining() / minElementBytes)
      throw DecodeError(at, std::string(what) + " count " + std::to_string(n) + " exceeds the bytes that remain");
    return static_cast<std::size_t>(n);
  }
  float f32() {
    float v;
    copy(&v, sizeof v, "float");
    if (!std::isfinite(v)) throw DecodeError(offset() - sizeof v, "non-finite float");
    return v;
  }
  double f64() {
    double v;
    copy(&v, sizeof v, "double");
    if (!std::isfinite(v)) throw DecodeError(offset() - sizeof v, "non-finite double");
    return v;
  }
  std::string string(std::size_t maxBytes) {
    std::size_t n = count(maxBytes, 1, "string byte");
    std::string s(reinterpret_cast<const char*>(bytes_.data() + pos_), n);
    pos_ += n;
    return s;
  }
  void copy(void* out, std::size_t size, const char* what) {
    need(size, what);
    if (size == 0) return;  // out may be null for an empty array
    std::memcpy(out, bytes_.data() + pos_, size);
    pos_ += size;
  }
  std::span<const std::uint8_t> take(std::size_t size, const char* what) {
    need(size, what);
    auto s = bytes_.subspan(pos_, size);
    pos_ += size;
    return s;
  }
  void skip(std::size_t size, const char* what) { take(size, what); }

 private:
  void need(std::size_t size, const char* what) const {
    if (size > remaining())
      fail(std::string("truncated ") + what + ": need " + std::to_string(size) + " bytes, " +
           std::to_string(remaining()) + " remain");
  }

  std::span<const std::uint8_t> bytes_;
  std::size_t base_;
  std::size_t pos_ = 0;
};

}  // namespace tsr::sg
